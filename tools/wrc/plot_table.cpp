// `wrc plot table`: one output of a table along one axis (the other axes fixed) or over two axes,
// interpolated by the runtime as a simulator would read it, with the table's nodes marked.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "tools/wrc/gnuplot.h"
#include "tools/wrc/output_text.h"
#include "tools/wrc/plot.h"
#include "wrc/core/errors.h"
#include "wrc/runtime.hpp"

namespace wrc::cli {
namespace {

namespace fs = std::filesystem;

std::string Joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& n : names) text += (text.empty() ? "" : ", ") + n;
  return text;
}

int AxisIndex(const Table& table, const std::string& name, const std::string& option) {
  const std::vector<std::string> names = table.axis_names();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) {
    throw InputError(option + " " + name +
                     ": the table has no such axis (its axes: " + Joined(names) + ")");
  }
  return static_cast<int>(it - names.begin());
}

int OutputIndex(const Table& table, const std::string& name) {
  const std::vector<std::string> names = table.output_names();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) {
    throw InputError("--output " + name +
                     ": the table has no such output (its outputs: " + Joined(names) + ")");
  }
  return static_cast<int>(it - names.begin());
}

// The node of axis `a` nearest the middle of its range: a slice through stored values.
double MiddleNode(const std::vector<double>& nodes) {
  const double middle = 0.5 * (nodes.front() + nodes.back());
  return *std::min_element(nodes.begin(), nodes.end(), [&](double a, double b) {
    return std::fabs(a - middle) < std::fabs(b - middle);
  });
}

// The point the slice or map goes through: --at values, else the middle node of each axis.
std::vector<double> BasePoint(const Table& table, const TablePlotRequest& r,
                              const std::vector<int>& drawn) {
  std::vector<double> point(table.num_axes());
  for (int a = 0; a < table.num_axes(); ++a) point[a] = MiddleNode(table.axis_values(a));
  for (const auto& [name, value] : r.at) {
    const int a = AxisIndex(table, name, "--at");
    if (std::find(drawn.begin(), drawn.end(), a) != drawn.end()) {
      throw InputError("--at " + name + ": that axis is drawn (--x/--y); fix only the others");
    }
    const std::vector<double> nodes = table.axis_values(a);
    if (value < nodes.front() || value > nodes.back()) {
      throw InputError("--at " + name + "=" + FormatNumber(value) + ": outside the table's " +
                       FormatNumber(nodes.front()) + " … " + FormatNumber(nodes.back()));
    }
    point[a] = value;
  }
  return point;
}

std::vector<double> Samples(const std::vector<double>& nodes, int n) {
  std::vector<double> v(n);
  for (int k = 0; k < n; ++k) v[k] = nodes.front() + (nodes.back() - nodes.front()) * k / (n - 1);
  v.back() = nodes.back();
  return v;
}

// The output at `point` and the runtime's flags (clamped, a failed node in the cell).
std::pair<double, int> Value(const Table& table, std::vector<double> point, int output) {
  int flags = 0;
  const std::vector<double> values = table.eval(point, &flags);
  return {values[output], flags};
}

// "name value unit, ..." of the fixed axes, for titles and the data files' headers.
std::string FixedText(const Table& table, const std::vector<double>& point,
                      const std::vector<int>& drawn) {
  std::string text;
  for (int a = 0; a < table.num_axes(); ++a) {
    if (std::find(drawn.begin(), drawn.end(), a) != drawn.end()) continue;
    text += (text.empty() ? "" : ", ") + table.axis_name(a) + " " + Short(point[a], 6) + " " +
            table.axis_unit(a);
  }
  return text.empty() ? "no other axes" : text;
}

std::string Label(const Table& table, int axis) {
  return table.axis_name(axis) + ", " + table.axis_unit(axis);
}

// 1-D: the interpolated curve and the values at the nodes of the drawn axis.
std::string Slice(const Table& table, const TablePlotRequest& r, const std::string& stem,
                  const fs::path& out, int ax, int output, const std::vector<double>& base) {
  const std::vector<double> nodes = table.axis_values(ax);
  std::vector<double> point = base;
  OutputText curve(out / (stem + ".dat")), at_nodes(out / (stem + "_nodes.dat"));
  const std::string header = "# " + table.axis_name(ax) + " " + r.output + " flags (at " +
                             FixedText(table, base, {ax}) + ")\n";
  curve << header;
  at_nodes << header;
  curve.precision(10);
  at_nodes.precision(10);
  for (const double x : Samples(nodes, r.samples)) {
    point[ax] = x;
    const auto [value, flags] = Value(table, point, output);
    curve << x << ' ' << value << ' ' << flags << '\n';
  }
  for (const double x : nodes) {
    point[ax] = x;
    const auto [value, flags] = Value(table, point, output);
    at_nodes << x << ' ' << value << ' ' << flags << '\n';
  }
  curve.Commit();
  at_nodes.Commit();
  std::ostringstream gp;
  gp << "set xlabel '" << Label(table, ax) << "'\nset ylabel '" << r.output << ", "
     << table.output_unit(output) << "'\nset key top left box opaque\nset xrange [" << nodes.front()
     << ':' << nodes.back() << "]\n"
     << "plot '" << stem << ".dat' using 1:2 with lines lw 2 lc rgb '#2166ac' title '"
     << (r.cubic ? "cubic" : "multilinear") << " interpolation', '" << stem
     << "_nodes.dat' using 1:2 with points pt 7 ps 0.8 lc rgb '#b2182b' title 'table nodes ("
     << nodes.size() << ")'\n";
  return gp.str();
}

// 2-D: the interpolated map on a uniform sample grid (rows of the second axis) and the node
// pairs of both axes.
std::string Map(const Table& table, const TablePlotRequest& r, const std::string& stem,
                const fs::path& out, int ax, int ay, int output, const std::vector<double>& base) {
  const std::vector<double> xn = table.axis_values(ax), yn = table.axis_values(ay);
  std::vector<double> point = base;
  OutputText map(out / (stem + ".dat")), at_nodes(out / (stem + "_nodes.dat"));
  const std::string header = "# " + table.axis_name(ax) + " " + table.axis_name(ay) + " " +
                             r.output + " flags (at " + FixedText(table, base, {ax, ay}) + ")\n";
  map << header;
  at_nodes << header;
  map.precision(10);
  at_nodes.precision(10);
  for (const double y : Samples(yn, r.samples)) {
    for (const double x : Samples(xn, r.samples)) {
      point[ax] = x;
      point[ay] = y;
      const auto [value, flags] = Value(table, point, output);
      map << x << ' ' << y << ' ' << value << ' ' << flags << '\n';
    }
    map << '\n';
  }
  for (const double y : yn) {
    for (const double x : xn) {
      point[ax] = x;
      point[ay] = y;
      const auto [value, flags] = Value(table, point, output);
      at_nodes << x << ' ' << y << ' ' << value << ' ' << flags << '\n';
    }
  }
  map.Commit();
  at_nodes.Commit();
  std::ostringstream gp;
  gp << "set xlabel '" << Label(table, ax) << "'\nset ylabel '" << Label(table, ay)
     << "'\nset cblabel '" << r.output << ", " << table.output_unit(output)
     << "'\n"
     // A sequential palette (dark to light, viridis-like): the value, not its sign, matters.
     << "set palette defined (0 '#440154', 0.25 '#3b528b', 0.5 '#21918c', 0.75 '#5ec962', 1 "
        "'#fde725')\n"
     << "set xrange [" << xn.front() << ':' << xn.back() << "]\nset yrange [" << yn.front() << ':'
     << yn.back() << "]\nset label 1 'dots: the " << xn.size() << " x " << yn.size()
     << " table nodes' at graph 0.01, graph -0.08 left\n"
     << "plot '" << stem << ".dat' using 1:2:3 with image notitle, '" << stem
     << "_nodes.dat' using 1:2 with points pt 7 ps 0.35 lc rgb '#000000' notitle\n";
  return gp.str();
}

}  // namespace

WrittenFiles PlotTable(const TablePlotRequest& r, const fs::path& out) {
  if (!fs::is_regular_file(r.table)) {
    throw InputError(r.table.string() + ": no such table file");
  }
  Table table(r.table.string());
  table.set_interpolation(r.cubic ? Interpolation::kCubic : Interpolation::kLinear);
  const int output = OutputIndex(table, r.output);
  const int ax = AxisIndex(table, r.x_axis, "--x");
  const int ay = r.y_axis.empty() ? -1 : AxisIndex(table, r.y_axis, "--y");
  if (ay == ax) throw InputError("--y " + r.y_axis + ": the same axis as --x");
  std::vector<int> drawn{ax};
  if (ay >= 0) drawn.push_back(ay);
  const std::vector<double> base = BasePoint(table, r, drawn);
  const std::string stem =
      "table_" + r.output + "_" + r.x_axis + (ay >= 0 ? "_" + r.y_axis : std::string());
  fs::create_directories(out);
  std::ostringstream gp;
  gp << "set terminal pngcairo noenhanced size 1000," << (ay >= 0 ? 800 : 600)
     << " font ',10'\nset output '" << stem << ".png'\nset grid\n"
     << "set title \"" << fs::path(r.table).filename().string() << ": " << r.output << " at "
     << FixedText(table, base, drawn) << "\"\n"
     << (ay >= 0 ? Map(table, r, stem, out, ax, ay, output, base)
                 : Slice(table, r, stem, out, ax, output, base));
  WrittenFiles written{out / (stem + ".dat"), out / (stem + "_nodes.dat")};
  if (!RunGnuplot(out, stem + ".gp", gp.str())) {
    std::cerr << "wrc plot table: gnuplot is not installed (Debian: gnuplot-nox): "
              << "no picture, the data is written\n";
    return written;
  }
  written.push_back(out / (stem + ".gp"));
  written.push_back(out / (stem + ".png"));
  return written;
}

}  // namespace wrc::cli
