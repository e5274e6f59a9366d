#pragma once
// The numbers of a data file as rows: comment lines (#) and a header line (starting with a
// letter) skipped, fields split at `separator` (runs of it count once). For the benchmark tables
// of tests/data (EN 15302's Δr and conicity files) and the CSV files `wrc` writes.

#include <cctype>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace wrc::test_support {

inline std::vector<std::vector<double>> NumberRows(const std::string& path, char separator) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#' || std::isalpha(static_cast<unsigned char>(line[0]))) {
      continue;
    }
    std::vector<double> row;
    std::istringstream fields(line);
    for (std::string field; std::getline(fields, field, separator);) {
      if (!field.empty()) row.push_back(std::stod(field));
    }
    rows.push_back(row);
  }
  return rows;
}

}  // namespace wrc::test_support
