// `wrc plot patch|profiles|table` (docs/plots.md, docs/reference/cli.md).

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "tools/wrc/commands.h"
#include "tools/wrc/plot.h"
#include "wrc/core/errors.h"
#include "wrc/runtime.hpp"

namespace wrc::cli {

namespace fs = std::filesystem;

int CsvTable::Column(const std::string& name) const {
  const int c = FirstColumn({name});
  if (c < 0) throw InputError(source + ": no column '" + name + "' in its header");
  return c;
}

int CsvTable::FirstColumn(const std::vector<std::string>& wanted) const {
  for (const std::string& w : wanted) {
    for (std::size_t c = 0; c < names.size(); ++c) {
      if (names[c] == w) return static_cast<int>(c);
    }
  }
  return -1;
}

CsvTable ReadCsv(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot be read");
  CsvTable csv;
  csv.source = path.string();
  std::string line;
  std::getline(in, line);
  std::stringstream header(line);
  for (std::string name; std::getline(header, name, ',');) csv.names.push_back(name);
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    std::vector<double> row;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) {
      char* end = nullptr;
      row.push_back(std::strtod(cell.c_str(), &end));
      if (end == cell.c_str()) {
        throw InputError(csv.source + ":" + std::to_string(number) + ": '" + cell +
                         "' is not a number");
      }
    }
    if (row.size() != csv.names.size()) {
      throw InputError(csv.source + ":" + std::to_string(number) + ": " +
                       std::to_string(row.size()) + " cells, the header names " +
                       std::to_string(csv.names.size()));
    }
    csv.rows.push_back(std::move(row));
  }
  return csv;
}

std::string Short(double value, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

namespace {

// Runs one plot: prints the files it wrote, one per line; bad input is a message and exit 2.
template <typename Plot>
void RunPlot(const char* name, int* exit_code, Plot plot) {
  try {
    for (const fs::path& file : plot()) std::cout << file.string() << '\n';
    *exit_code = kExitOk;
  } catch (...) {
    *exit_code = ReportFailure(std::string("wrc plot ") + name);
  }
}

// "name=value,name=value" of --at, parsed into the request.
std::map<std::string, double> ParseAt(const std::vector<std::string>& items) {
  std::map<std::string, double> at;
  for (const std::string& item : items) {
    const std::size_t eq = item.find('=');
    char* end = nullptr;
    const double value = eq == std::string::npos ? NAN : std::strtod(item.c_str() + eq + 1, &end);
    if (eq == std::string::npos || eq == 0 || end == item.c_str() + eq + 1 || *end != '\0' ||
        !std::isfinite(value)) {
      throw InputError("--at " + item + ": give axis=value, e.g. --at yaw=0.002");
    }
    if (!at.emplace(item.substr(0, eq), value).second) {
      throw InputError("--at " + item + ": axis " + item.substr(0, eq) + " is given twice");
    }
  }
  return at;
}

void AddPatch(CLI::App& plot, int* exit_code) {
  auto* cmd = plot.add_subcommand(
      "patch", "Maps of pressure, traction, adhesion/slip and rigid slip of each contact patch");
  auto case_path = std::make_shared<std::string>();
  auto from = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>("plot-patch");
  auto power = std::make_shared<bool>(false);
  cmd->add_option("CASE", *case_path, "Case file to solve (TOML)");
  cmd->add_flag("--frictional-power", *power,
                "Also map where the frictional work is done: the dissipated power per area, "
                "W/mm2 (wheel-rail solves)");
  cmd->add_option("--from", *from, "Plot a `wrc solve --out DIR` directory instead of solving");
  cmd->add_option("--out", *out, "Output directory (PNG, data, scripts)")->capture_default_str();
  cmd->callback([=]() {
    RunPlot("patch", exit_code, [&] {
      if (case_path->empty() == from->empty()) {
        throw InputError("give either a case file or --from DIR (a `wrc solve --out` directory)");
      }
      return from->empty() ? PlotPatchesOfCase(*case_path, *out, *power)
                           : PlotPatchesFrom(*from, *out, *power);
    });
  });
}

void AddProfiles(CLI::App& plot, int* exit_code) {
  auto* cmd = plot.add_subcommand(
      "profiles", "Wheel and rail profiles in place at the case's pose, patches and the gap");
  auto case_path = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>("plot-profiles");
  cmd->add_option("CASE", *case_path, "Wheel-rail case file (TOML)")->required();
  cmd->add_option("--out", *out, "Output directory (PNG, data, script)")->capture_default_str();
  cmd->callback(
      [=]() { RunPlot("profiles", exit_code, [&] { return PlotProfiles(*case_path, *out); }); });
}

void AddTable(CLI::App& plot, int* exit_code) {
  auto* cmd = plot.add_subcommand(
      "table", "One output of a table along one axis, or over two axes, with the table's nodes");
  auto request = std::make_shared<TablePlotRequest>();
  auto table = std::make_shared<std::string>();
  auto at = std::make_shared<std::vector<std::string>>();
  auto out = std::make_shared<std::string>("plot-table");
  auto interpolation = std::make_shared<std::string>("linear");
  request->samples = 201;
  cmd->add_option("TABLE", *table, "Table file (HDF5, from wrc generate)")->required();
  cmd->add_option("--output", request->output, "Output to draw, e.g. fy")->required();
  cmd->add_option("--x", request->x_axis, "Axis along the horizontal")->required();
  cmd->add_option("--y", request->y_axis, "Second axis: a map over both");
  cmd->add_option("--at", *at,
                  "Values of the other axes, name=value,... (default: the node nearest the "
                  "middle of each)")
      ->delimiter(',');
  cmd->add_option("--interpolation", *interpolation, "Between the nodes: linear or cubic")
      ->check(CLI::IsMember({"linear", "cubic"}))
      ->capture_default_str();
  cmd->add_option("--samples", request->samples, "Interpolated points per axis")
      ->check(CLI::Range(2, 2000))
      ->capture_default_str();
  cmd->add_option("--out", *out, "Output directory (PNG, data, script)")->capture_default_str();
  cmd->callback([=]() {
    RunPlot("table", exit_code, [&] {
      request->table = *table;
      request->at = ParseAt(*at);
      request->cubic = *interpolation == "cubic";
      return PlotTable(*request, *out);
    });
  });
}

}  // namespace

void AddPlotCommand(CLI::App& app, int* exit_code) {
  auto* plot = app.add_subcommand(
      "plot", "Pictures: contact patches, profiles in place, table slices and maps (PNG + data)");
  plot->require_subcommand(1);
  AddPatch(*plot, exit_code);
  AddProfiles(*plot, exit_code);
  AddTable(*plot, exit_code);
}

}  // namespace wrc::cli
