#pragma once
// `wrc plot` (docs/plots.md): pictures of a solve, of the profiles in place and of a table. Each
// picture comes with the data it draws and its gnuplot script, all in the output directory.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace wrc::cli {

/// The files a plot wrote, in the order written; printed one per line on stdout.
using WrittenFiles = std::vector<std::filesystem::path>;

/// Maps of each contact patch of a solve in `from` (a `wrc solve --out` directory), into `out`;
/// with `power` also the dissipated frictional power per area (wheel–rail solves only).
WrittenFiles PlotPatchesFrom(const std::filesystem::path& from, const std::filesystem::path& out,
                             bool power = false);
/// Solves `case_path`, writes the `wrc solve --out` files into `out`, and plots them there.
WrittenFiles PlotPatchesOfCase(const std::filesystem::path& case_path,
                               const std::filesystem::path& out, bool power = false);

/// Wheel and rail of a wheel–rail case in place at its solved pose, with the contact patches
/// and the gap between the profiles.
WrittenFiles PlotProfiles(const std::filesystem::path& case_path, const std::filesystem::path& out);

/// What `wrc plot table` draws.
struct TablePlotRequest {
  std::filesystem::path table;
  std::string output, x_axis, y_axis;  ///< y_axis empty: a slice along x_axis.
  std::map<std::string, double> at;    ///< Values of the other axes (default: the middle node).
  bool cubic = false;                  ///< Interpolation between the nodes.
  int samples = 0;                     ///< Interpolated points per axis.
};
WrittenFiles PlotTable(const TablePlotRequest& request, const std::filesystem::path& out);

/// A CSV file with a header line of column names and numeric rows.
struct CsvTable {
  std::vector<std::string> names;
  std::vector<std::vector<double>> rows;
  /// Index of column `name`; throws InputError naming the file when it is missing.
  int Column(const std::string& name) const;
  /// Index of the first of `names` present, or -1.
  int FirstColumn(const std::vector<std::string>& names) const;
  std::string source;
};
/// Reads a CSV of numbers; throws InputError for a missing file or a cell that is no number.
CsvTable ReadCsv(const std::filesystem::path& path);

/// A number for a picture's title or label: `digits` significant digits.
std::string Short(double value, int digits = 4);

}  // namespace wrc::cli
