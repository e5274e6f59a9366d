// `wrc geometry CASE.toml`: the rigid contact geometry of a wheelset on its track, what a
// vehicle engineer looks at before any simulation: over the wheelset's lateral shift y, the
// rolling-radius difference Δr, the contact angles and the contact points on wheel and rail of
// both wheels, the contact jumps, and the equivalent conicity per EN 15302 against amplitude
// (docs/conicity.md). The case's wheel and rail are the right ones; the left wheel is their
// mirror image unless --left-wheel names a profile of its own. By default the wheelset is not
// rolled, as EN 15302 prescribes (each wheel brought into contact on its own); `--roll solved`
// rolls it until both wheels touch together.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tools/wrc/commands.h"
#include "tools/wrc/gnuplot.h"
#include "tools/wrc/output_text.h"
#include "wrc/core/case.h"
#include "wrc/core/conicity.h"
#include "wrc/core/errors.h"
#include "wrc/core/profile.h"
#include "wrc/core/profile_placement.h"
#include "wrc/runtime.hpp"

namespace wrc::cli {
namespace {

namespace fs = std::filesystem;

struct GeometryOptions {
  std::string case_path, left_wheel, out;
  std::string table;  // a right wheel's table with rolling_radius: its Δr beside the rigid one
  double left_radius = 0.0;  // 0: the case's nominal radius
  double y_max = 10.0, y_step = 0.1;
  double step = 0.01;  // rail arc length between gap samples, mm
  bool json = false;
  std::string roll = "none";  // or "solved"
};

// A contact point jumps when it moves along the rail by more than this between two shifts one
// step apart. On a tabulated profile the point also moves in steps of 1–3 mm where wheel and
// rail are nearly conformal (EN 15302's profile A); a jump between tread and flange, or
// between two tread regions, spans 10 mm and more.
constexpr double kJump = 5.0;

struct Row {
  double y;
  double roll = 0.0;         // rad
  RigidContact right, left;  // left: its right-side equivalent at −y
  bool jump = false;
  // From --table: the rolling radii under the table's load (NaN without a table, or where the
  // table has no contact).
  double table_r_right = NAN, table_r_left = NAN;
};

std::vector<Row> Sweep(const Case& right, const Case& left, const GeometryOptions& o) {
  std::vector<Row> rows;
  const int n = static_cast<int>(std::round(o.y_max / o.y_step));
  for (int i = -n; i <= n; ++i) {
    Row r;
    r.y = std::round(i * o.y_step * 1e9) / 1e9;  // the step's decimals, not its rounding
    if (o.roll == "solved") {
      r.roll = WheelsetRollAt(right, left, r.y, o.step);
      if (!std::isfinite(r.roll)) {
        throw InputError("at y = " + std::to_string(r.y) +
                         " mm no roll within ±50 mrad brings both wheels down together");
      }
    }
    r.right = RigidContactAt(right, {r.y, 0.0, r.roll, 0.0}, o.step);
    r.left = RigidContactAt(left, {-r.y, 0.0, -r.roll, 0.0}, o.step);
    if (!r.right.found || !r.left.found) {
      throw InputError("at y = " + std::to_string(r.y) +
                       " mm a wheel lies nowhere above its rail: the placement ([track], "
                       "[wheelset]) or --y-max does not fit the profiles");
    }
    if (!rows.empty()) {
      r.jump = std::fabs(r.right.rail_y - rows.back().right.rail_y) > kJump ||
               std::fabs(r.left.rail_y - rows.back().left.rail_y) > kJump;
    }
    rows.push_back(r);
  }
  return rows;
}

RollingRadiusDifference DrOf(const std::vector<Row>& rows) {
  RollingRadiusDifference dr;
  for (const Row& r : rows) {
    dr.y.push_back(r.y);
    dr.dr.push_back(r.right.rolling_radius - r.left.rolling_radius);
  }
  return dr;
}

// The table's point for the shifts: y (or y_wheel, the same without roll) at `*lateral`, set per
// shift; every other axis at 0 within its range, except fz at its lightest node, the load
// nearest the rigid contact (CheckGeometryTable refuses a table over z).
std::vector<double> BasePoint(const Table& table, int* lateral) {
  std::vector<double> point;
  for (int a = 0; a < table.num_axes(); ++a) {
    const std::string name = table.axis_name(a);
    const std::vector<double> nodes = table.axis_values(a);
    if (name == "y" || name == "y_wheel") *lateral = a;
    point.push_back(name == "fz" ? nodes.front() : std::clamp(0.0, nodes.front(), nodes.back()));
  }
  return point;
}

void CheckGeometryTable(const Table& table, const std::string& path) {
  const std::vector<std::string> axes = table.axis_names(), outputs = table.output_names();
  const auto has = [](const std::vector<std::string>& names, const char* name) {
    return std::find(names.begin(), names.end(), name) != names.end();
  };
  if (!has(axes, "y") && !has(axes, "y_wheel")) {
    throw InputError(path + ": --table needs a table over y (or y_wheel)");
  }
  if (has(axes, "z")) throw InputError(path + ": --table needs a table at a load (fz), not over z");
  if (!has(outputs, "rolling_radius")) {
    throw InputError(path + ": --table needs the output rolling_radius");
  }
  const char* side = wrc_table_attribute(table.get(), "wheelset_side");
  if (side == nullptr || std::string(side) != "right") {
    throw InputError(path +
                     ": --table needs a table made for the right wheel (its attribute "
                     "wheelset_side; tables written before it: regenerate)");
  }
}

void ReadTableRadii(const std::string& path, std::vector<Row>& rows) {
  const Table table(path);
  CheckGeometryTable(table, path);
  const int radius = table.output_index("rolling_radius");
  int lateral = 0;
  std::vector<double> point = BasePoint(table, &lateral);
  for (Row& r : rows) {
    point[static_cast<std::size_t>(lateral)] = r.y;
    r.table_r_right = table.eval(point)[radius];
    point[static_cast<std::size_t>(lateral)] = -r.y;
    r.table_r_left = table.eval(point)[radius];
  }
}

// Positions in the track frame as a user reads them: the left wheel's mirrored back (y < 0).
// Contact angles in each wheel's own sense, positive where its surface rises towards its
// flange (the tread's cone, about 70° on a flank), so that a symmetric pair differs by 0 at
// y = 0.
void WriteGeometry(const fs::path& path, const std::vector<Row>& rows) {
  OutputText csv(path);
  csv << "y_mm,dr_mm,r_right_mm,r_left_mm,contact_angle_right_rad,contact_angle_left_rad,"
         "rail_y_right_mm,rail_y_left_mm,wheel_y_right_mm,wheel_y_left_mm,jump,roll_rad,"
         "table_dr_mm\n";
  csv.precision(10);
  for (const Row& r : rows) {
    csv << r.y << ',' << r.right.rolling_radius - r.left.rolling_radius << ','
        << r.right.rolling_radius << ',' << r.left.rolling_radius << ',' << -r.right.contact_angle
        << ',' << -r.left.contact_angle << ',' << r.right.rail_y << ',' << -r.left.rail_y << ','
        << r.right.wheel_y << ',' << r.left.wheel_y << ',' << (r.jump ? 1 : 0) << ',' << r.roll
        << ',' << r.table_r_right - r.table_r_left << '\n';
  }
  csv.Commit();
}

// One amplitude: EN 15302's integration (the reference method) and its linear regression.
struct ConicityPoint {
  EquivalentConicity integration;
  double regression = NAN;
  double table = NAN;  // the integration on --table's Δr under load
};

// Δr from --table's rolling radii, where the table gives both (none without a table).
RollingRadiusDifference TableDrOf(const std::vector<Row>& rows) {
  RollingRadiusDifference dr;
  for (const Row& r : rows) {
    const double value = r.table_r_right - r.table_r_left;
    if (!std::isfinite(value)) continue;
    dr.y.push_back(r.y);
    dr.dr.push_back(value);
  }
  return dr;
}

std::vector<ConicityPoint> Conicity(const std::vector<Row>& rows, double y_max) {
  const RollingRadiusDifference dr = DrOf(rows), table_dr = TableDrOf(rows);
  std::vector<ConicityPoint> curve;
  for (int i = 1; i * 0.1 <= y_max + 1e-9; ++i) {
    const double amplitude = 0.1 * i;
    const auto c = EquivalentConicityAt(dr, amplitude);
    if (!c.valid) continue;
    ConicityPoint point{c, EquivalentConicityByRegression(dr, amplitude)};
    if (table_dr.y.size() >= 2) {
      const auto t = EquivalentConicityAt(table_dr, amplitude);
      if (t.valid) point.table = t.tan_gamma_e;
    }
    curve.push_back(point);
  }
  return curve;
}

void WriteConicity(const fs::path& path, const std::vector<ConicityPoint>& curve) {
  OutputText csv(path);
  csv << "amplitude_mm,tan_gamma_e,y_min_mm,y_max_mm,tan_gamma_e_regression,tan_gamma_e_table\n";
  csv.precision(10);
  for (const auto& [c, regression, table] : curve) {
    csv << c.amplitude << ',' << c.tan_gamma_e << ',' << c.y_min << ',' << c.y_max << ','
        << regression << ',' << table << '\n';
  }
  csv.Commit();
}

// The classic panels: Δr(y), the contact angle difference, the contact points on the rail and
// on the wheel against y, and the equivalent conicity against amplitude by both methods.
void DrawGeometry(const fs::path& out, bool with_table) {
  // --table's curves beside the rigid ones (gnuplot refuses a column of NaN alone).
  const std::string table_dr =
      with_table ? ", '' using 1:13 with lines dashtype 3 title 'table (under load)'" : "";
  const std::string table_conicity =
      with_table ? ", '' using 1:6 with lines dashtype 3 title 'table (under load)'" : "";
  const std::string script =
      "set terminal pngcairo size 1200,1300 font ',10'\n"
      "set output 'geometry.png'\n"
      "set datafile separator ','\n"
      "set key autotitle columnhead\n"
      "set multiplot layout 3,2\n"
      "set grid\n"
      "set xlabel 'y, mm'\nset ylabel 'Δr, mm'\nset title 'Rolling-radius difference'\n"
      "plot 'geometry.csv' using 1:2 with lines title 'rigid'" +
      table_dr +
      "\n"
      "set ylabel 'γ_R − γ_L, rad'\nset title 'Contact angle difference'\n"
      "plot 'geometry.csv' using 1:($5-$6) with lines notitle\n"
      "set ylabel 'contact point on the rail, mm (track frame)'\n"
      "set title 'Contact points (|y|, right and left rail)'\n"
      "set key below\n"  // beside no data, whatever the pair
      "plot 'geometry.csv' using 1:7 with points pt 7 ps 0.3 title 'right', "
      "'' using 1:(-$8) with points pt 7 ps 0.3 title 'left (mirrored)'\n"
      "set ylabel 'contact point on the wheel, mm (wheel profile)'\n"
      "set title 'Contact points on the wheels'\n"
      "plot 'geometry.csv' using 1:9 with points pt 7 ps 0.3 title 'right', "
      "'' using 1:10 with points pt 7 ps 0.3 title 'left'\n"
      "set xlabel 'amplitude ŷ, mm'\nset ylabel 'tan γe'\n"
      "set title 'Equivalent conicity (EN 15302)'\n"
      "plot 'conicity.csv' using 1:2 with lines title 'integration (reference method)', "
      "'' using 1:5 with lines dashtype 2 title 'linear regression of Δr'" +
      table_conicity +
      "\n"
      "unset multiplot\n";
  if (!RunGnuplot(out, "geometry.gp", script)) {
    std::cerr << "wrc geometry: gnuplot is not installed: geometry.png is not drawn (the CSV "
                 "files are written)\n";
  }
}

const ConicityPoint* AtAmplitude(const std::vector<ConicityPoint>& curve, double amplitude) {
  for (const auto& point : curve) {
    if (std::fabs(point.integration.amplitude - amplitude) < 1e-9) return &point;
  }
  return nullptr;
}

nlohmann::json NumberOrNull(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json Summary(const std::vector<Row>& rows, const std::vector<ConicityPoint>& curve,
                       const std::string& roll) {
  nlohmann::json j;
  const ConicityPoint* at3 = AtAmplitude(curve, 3.0);
  j["tan_gamma_e_3mm"] = NumberOrNull(at3 ? at3->integration.tan_gamma_e : NAN);
  j["tan_gamma_e_regression_3mm"] = NumberOrNull(at3 ? at3->regression : NAN);
  j["jumps_y_mm"] = nlohmann::json::array();
  for (const Row& r : rows) {
    if (r.jump) j["jumps_y_mm"].push_back(r.y);
  }
  j["conicity"] = nlohmann::json::array();
  for (const auto& [c, regression, table] : curve) {
    j["conicity"].push_back({{"amplitude_mm", c.amplitude},
                             {"tan_gamma_e", c.tan_gamma_e},
                             {"tan_gamma_e_regression", NumberOrNull(regression)},
                             {"tan_gamma_e_table", NumberOrNull(table)}});
  }
  j["roll"] = roll == "solved" ? "solved" : "none (EN 15302)";
  return j;
}

void RunGeometry(const GeometryOptions& o) {
  const Case right = LoadCase(o.case_path);
  Case left = right;
  if (!o.left_wheel.empty()) {
    left.wheel = ProfileSource{};
    left.wheel.path = left.wheel.path_as_written = o.left_wheel;
    // Read once, as LoadCase read the case's own: every shift places it again.
    left.wheel.spline = SplineOf(left.wheel, ProfileKind::kWheel);
  }
  if (o.left_radius > 0.0) left.wheelset.nominal_radius = o.left_radius;
  std::vector<Row> rows = Sweep(right, left, o);
  if (!o.table.empty()) ReadTableRadii(o.table, rows);
  std::vector<double> at_end;
  for (const Row& r : rows) {
    if (r.right.at_profile_end || r.left.at_profile_end) at_end.push_back(r.y);
  }
  if (!at_end.empty()) {
    std::cerr << "wrc geometry: warning: from y = " << at_end.front() << " to " << at_end.back()
              << " mm (" << at_end.size()
              << " shifts) a contact lies at the end of a profile: those rows describe the "
                 "profiles' edges, not a contact; a smaller --y-max stays within them\n";
  }
  const std::vector<ConicityPoint> curve = Conicity(rows, o.y_max);
  const nlohmann::json summary = Summary(rows, curve, o.roll);
  if (!o.out.empty()) {
    fs::create_directories(o.out);
    WriteGeometry(fs::path(o.out) / "geometry.csv", rows);
    WriteConicity(fs::path(o.out) / "conicity.csv", curve);
    DrawGeometry(o.out, !o.table.empty());
  }
  if (o.json) {
    std::cout << summary.dump(2) << '\n';
    return;
  }
  const ConicityPoint* at3 = AtAmplitude(curve, 3.0);
  const auto text = [](double v) { return std::isfinite(v) ? std::to_string(v) : "n/a"; };
  std::cout << "wheelset roll: " << summary["roll"].get<std::string>() << '\n'
            << "equivalent conicity (EN 15302): tan γe(3 mm) = "
            << text(at3 ? at3->integration.tan_gamma_e : NAN)
            << " (linear regression of Δr: " << text(at3 ? at3->regression : NAN) << ")\n"
            << "contact jumps at y = " << summary["jumps_y_mm"].dump() << " mm\n";
}

}  // namespace

void AddGeometryCommand(CLI::App& app, int* exit_code) {
  auto* cmd = app.add_subcommand(
      "geometry",
      "Rigid contact geometry of a wheelset: Δr, contact angles and points over y, "
      "and the equivalent conicity (EN 15302)");
  auto o = std::make_shared<GeometryOptions>();
  cmd->add_option("CASE", o->case_path, "Wheel-rail case: the right wheel and rail")->required();
  cmd->add_option("--left-wheel", o->left_wheel,
                  "Profile of the left wheel (default: the case's wheel, mirrored)");
  cmd->add_option("--left-radius", o->left_radius,
                  "Nominal radius of the left wheel, mm (default: the case's)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--y-max", o->y_max, "Lateral shifts from -Y to Y, mm")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 50.0));
  cmd->add_option("--y-step", o->y_step, "Step in y, mm")
      ->capture_default_str()
      ->check(CLI::Range(0.001, 5.0));
  cmd->add_option("--out", o->out, "Output directory (geometry.csv, conicity.csv, geometry.png)");
  cmd->add_option("--roll", o->roll,
                  "none: each wheel touches its rail on its own (EN 15302); solved: the wheelset "
                  "rolls until both touch together")
      ->capture_default_str()
      ->check(CLI::IsMember({"none", "solved"}));
  cmd->add_option("--table", o->table,
                  "A right wheel's table over y with the output rolling_radius: its Δr under load "
                  "beside the rigid one (geometry.csv column table_dr_mm, and the picture)");
  cmd->add_flag("--json", o->json, "The summary as JSON");
  cmd->callback([=]() {
    try {
      RunGeometry(*o);
      FinishStandardOutput();
      *exit_code = kExitOk;
    } catch (...) {
      *exit_code = ReportFailure("wrc geometry");
    }
  });
}

}  // namespace wrc::cli
