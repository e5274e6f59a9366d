// `wrc plot patch`: per contact patch, maps of pressure, tangential traction, adhesion and slip,
// and rigid slip over the patch's grid, from the files of `wrc solve --out`
// (docs/output-format.md).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tools/angles.h"
#include "tools/wrc/gnuplot.h"
#include "tools/wrc/output_text.h"
#include "tools/wrc/plot.h"
#include "tools/wrc/solve_output.h"
#include "wrc/core/case.h"
#include "wrc/core/errors.h"
#include "wrc/core/halfspace.h"
#include "wrc/core/wheelrail.h"

namespace wrc::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// One patch's fields on its grid, as `wrc solve --out` wrote them; rows j, i fastest.
struct PatchFields {
  int nx = 0, ny = 0;
  double dx = 0.0, ds = 0.0;
  std::vector<double> x, s, pn, px, ps, state;
  // Rigid slip (wheel–rail files); half-space files have only the total slip, drawn instead.
  std::vector<double> wx, ws;
  bool rigid = true;
  // The actual slip (wheel–rail files: sx, ss beside the rigid slip) and the rolling velocity
  // (mm/s, from summary.json), for the frictional power; NaN velocity: not drawn.
  std::vector<double> sx, ss;
  double velocity = NAN;
  // Dissipated frictional power per area at element k, W/mm²: −V·(px·sx + ps·ss)/1000, the
  // density whose integral with the opposite sign is the patch's frictional_power.
  double PowerDensity(std::size_t k) const {
    return -1e-3 * velocity * (px[k] * sx[k] + ps[k] * ss[k]);
  }
  bool HasPower() const { return std::isfinite(velocity) && !sx.empty(); }
};

// The column of the first present name, for files of either kind (s/y, ps/py, ...).
int AnyColumn(const CsvTable& csv, const std::vector<std::string>& names) {
  const int c = csv.FirstColumn(names);
  if (c < 0) throw InputError(csv.source + ": no column " + names.front());
  return c;
}

PatchFields ReadFields(const fs::path& path) {
  const CsvTable csv = ReadCsv(path);
  const int ci = csv.Column("i"), cj = csv.Column("j"), cx = csv.Column("x");
  const int cs = AnyColumn(csv, {"s", "y"}), cpn = csv.Column("pn");
  const int cpx = csv.Column("px"), cps = AnyColumn(csv, {"ps", "py"});
  const int cstate = csv.Column("state");
  int cwx = csv.FirstColumn({"wx"}), cws = csv.FirstColumn({"ws"});
  PatchFields f;
  f.rigid = cwx >= 0 && cws >= 0;
  if (!f.rigid) {
    cwx = AnyColumn(csv, {"sx"});
    cws = AnyColumn(csv, {"ss", "sy"});
  }
  // Wheel–rail files carry the actual slip beside the rigid one.
  const int csx = f.rigid ? csv.FirstColumn({"sx"}) : -1,
            css = f.rigid ? csv.FirstColumn({"ss"}) : -1;
  for (const auto& row : csv.rows) {
    if (csx >= 0 && css >= 0) {
      f.sx.push_back(row[csx]);
      f.ss.push_back(row[css]);
    }
    f.nx = std::max(f.nx, static_cast<int>(row[ci]) + 1);
    f.ny = std::max(f.ny, static_cast<int>(row[cj]) + 1);
    f.x.push_back(row[cx]);
    f.s.push_back(row[cs]);
    f.pn.push_back(row[cpn]);
    f.px.push_back(row[cpx]);
    f.ps.push_back(row[cps]);
    f.state.push_back(row[cstate]);
    f.wx.push_back(row[cwx]);
    f.ws.push_back(row[cws]);
  }
  if (f.x.empty() || static_cast<std::size_t>(f.nx) * f.ny != f.x.size()) {
    throw InputError(path.string() + ": the rows do not make an nx × ny grid (" +
                     std::to_string(f.x.size()) + " rows)");
  }
  f.dx = f.nx > 1 ? f.x[1] - f.x[0] : 1.0;
  f.ds = f.ny > 1 ? f.s[f.nx] - f.s[0] : f.dx;
  return f;
}

// Every k-th element along both directions, so that about 16 arrows span the longer side.
int ArrowStride(const PatchFields& f) { return std::max(1, (std::max(f.nx, f.ny) + 15) / 16); }

// The grid as gnuplot's image and pm3d read it: one line per element, a blank line after each
// row j; x s pn |p_t| px ps state |w| wx ws, and the frictional power density (W/mm²) when the
// fields give it.
void WriteMap(const fs::path& path, const PatchFields& f) {
  OutputText dat(path);
  dat << "# x_mm s_mm pn_N/mm2 pt_N/mm2 px_N/mm2 ps_N/mm2 state "
      << (f.rigid ? "w wx ws (rigid slip)" : "s sx ss (slip)")
      << (f.HasPower() ? " power_W/mm2 (dissipated)" : "") << '\n';
  dat.precision(10);
  for (int j = 0; j < f.ny; ++j) {
    for (int i = 0; i < f.nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * f.nx + i;
      dat << f.x[k] << ' ' << f.s[k] << ' ' << f.pn[k] << ' ' << std::hypot(f.px[k], f.ps[k]) << ' '
          << f.px[k] << ' ' << f.ps[k] << ' ' << f.state[k] << ' ' << std::hypot(f.wx[k], f.ws[k])
          << ' ' << f.wx[k] << ' ' << f.ws[k];
      if (f.HasPower()) dat << ' ' << f.PowerDensity(k);
      dat << '\n';
    }
    dat << '\n';
  }
  dat.Commit();
}

double MaxNorm(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) m = std::max(m, std::hypot(a[k], b[k]));
  return m;
}

// Arrows at every ArrowStride-th element: traction where there is contact, rigid slip
// everywhere, each scaled so that its largest arrow is 0.9 of the arrow spacing (mm).
void WriteArrows(const fs::path& path, const PatchFields& f) {
  const int k_step = ArrowStride(f);
  const double spacing = 0.9 * k_step * std::min(f.dx, f.ds);
  const double pt_max = MaxNorm(f.px, f.ps), w_max = MaxNorm(f.wx, f.ws);
  const double pt_scale = pt_max > 0.0 ? spacing / pt_max : 0.0;
  const double w_scale = w_max > 0.0 ? spacing / w_max : 0.0;
  OutputText dat(path);
  dat << "# x_mm s_mm dx_traction_mm ds_traction_mm dx_slip_mm ds_slip_mm (arrow tails and "
         "lengths; traction scale "
      << pt_scale << " mm per N/mm2, slip scale " << w_scale << " mm)\n";
  dat.precision(8);
  for (int j = k_step / 2; j < f.ny; j += k_step) {
    for (int i = k_step / 2; i < f.nx; i += k_step) {
      const std::size_t k = static_cast<std::size_t>(j) * f.nx + i;
      const bool contact = f.pn[k] > 0.0;
      dat << f.x[k] << ' ' << f.s[k] << ' ' << (contact ? pt_scale * f.px[k] : 0.0) << ' '
          << (contact ? pt_scale * f.ps[k] : 0.0) << ' ' << w_scale * f.wx[k] << ' '
          << w_scale * f.ws[k] << '\n';
    }
  }
  dat.Commit();
}

// The patch's totals and creepages for the picture's title, from summary.json.
std::string PatchTitle(const json& patch, int n) {
  auto get = [&](const char* key) {
    return patch.contains(key) && patch[key].is_number() ? patch[key].get<double>() : NAN;
  };
  std::string title = "patch " + std::to_string(n) + ": Fn " + Short(get("fn")) + " N, Fx " +
                      Short(get("fx")) + " N, Fs " + Short(get("fs")) + " N";
  if (patch.contains("cksi")) {
    title += ";  creepages cksi " + Short(get("cksi"), 3) + ", ceta " + Short(get("ceta"), 3) +
             ", cphi " + Short(get("cphi"), 3) + " 1/mm";
  }
  if (patch.contains("contact_angle")) {
    title += ";  contact angle " + Short(tools::Degrees(get("contact_angle")), 3) + "°";
  }
  return title;
}

// A map panel: an image of column `column` of the map file, optionally with arrows.
std::string Panel(const std::string& stem, const std::string& title, int column,
                  const std::string& palette, const std::string& cb, const std::string& arrows) {
  std::ostringstream gp;
  gp << "set title '" << title << "'\n"
     << palette << cb << "plot '" << stem << "_map.dat' using 1:2:" << column
     << " with image notitle" << arrows << "\n";
  return gp.str();
}

// The dissipated frictional power over the patch, W (the patch's −frictional_power).
double TotalPower(const PatchFields& f) {
  double sum = 0.0;
  for (std::size_t k = 0; k < f.x.size(); ++k) sum += f.PowerDensity(k);
  return sum * f.dx * f.ds;
}

std::string PatchScript(const std::string& stem, const PatchFields& f, const std::string& title,
                        bool power) {
  const double x0 = f.x.front() - 0.5 * f.dx, x1 = f.x.back() + 0.5 * f.dx;
  const double s0 = f.s.front() - 0.5 * f.ds, s1 = f.s.back() + 0.5 * f.ds;
  // Panels of equal aspect laid out 2 × 2; the canvas takes the patch's shape.
  const double aspect = std::clamp((s1 - s0) / (x1 - x0), 0.3, 3.0);
  // Each panel about 560 px wide; its height follows, plus title, labels and the colour box.
  const int width = 1300;
  const int rows = power ? 3 : 2;
  const int height =
      static_cast<int>(std::clamp(140.0 + rows * (470.0 * aspect + 80.0), 500.0, 800.0 * rows));
  const std::string arrow_style = " with vectors head size graph 0.012,25 lc rgb '#000000' notitle";
  std::ostringstream gp;
  gp << "set terminal pngcairo noenhanced size " << width << ',' << height << " font ',10'\n"
     << "set output '" << stem << ".png'\n"
     << "set size ratio -1\nset rmargin 12\nset xrange [" << x0 << ':' << x1 << "]\nset yrange ["
     << s0 << ':' << s1 << "]\n"
     << "set xlabel 'x, mm (rolling direction)'\nset ylabel 's, mm (lateral, along the "
        "contact)'\nset tics out\n"
     << "set multiplot layout " << rows << ",2 title \"" << title << "\" font ',11'\n"
     << Panel(stem, "pressure pn, N/mm2", 3,
              "set palette defined (0 '#ffffff', 1 '#fee391', 2 '#fe9929', 3 '#cc4c02', 4 "
              "'#662506')\n",
              "set cbrange [0:*]\n", "")
     << Panel(stem, "tangential traction |(px, ps)|, N/mm2 (arrows: direction and size)", 4, "", "",
              ", '" + stem + "_arrows.dat' using 1:2:3:4" + arrow_style)
     << Panel(stem, "state", 7,
              "set palette defined (0 '#e8e8e8', 0.999 '#e8e8e8', 1 '#4393c3', 1.999 "
              "'#4393c3', 2 '#d6604d', 3 '#d6604d')\n",
              "set cbrange [-0.5:2.5]\nset cbtics ('exterior' 0, 'adhesion' 1, 'slip' 2)\n", "")
     << "set cbtics autofreq\nset cbrange [0:*]\n"
     << "set palette defined (0 '#ffffff', 1 '#c6dbef', 2 '#4292c6', 3 '#08306b')\n"
     << Panel(stem,
              f.rigid ? "rigid slip |(wx, ws)|, - (arrows: direction)"
                      : "slip |(sx, sy)|, - (arrows: direction)",
              8, "", "", ", '" + stem + "_arrows.dat' using 1:2:5:6" + arrow_style);
  if (power) {
    gp << Panel(stem,
                "dissipated frictional power, W/mm2 (total " + Short(TotalPower(f), 4) + " W)", 11,
                "set palette defined (0 '#ffffff', 1 '#fcbba1', 2 '#ef3b2c', 3 '#67000d')\n",
                "set cbrange [0:*]\n", "");
  }
  gp << "unset multiplot\n";
  return gp.str();
}

// Draws one patch: map and arrow data, script and PNG, named after `stem`.
void DrawPatch(const fs::path& out, const std::string& stem, const PatchFields& f,
               const std::string& title, bool power, WrittenFiles* written) {
  WriteMap(out / (stem + "_map.dat"), f);
  WriteArrows(out / (stem + "_arrows.dat"), f);
  written->push_back(out / (stem + "_map.dat"));
  written->push_back(out / (stem + "_arrows.dat"));
  if (!RunGnuplot(out, stem + ".gp", PatchScript(stem, f, title, power))) {
    std::cerr << "wrc plot patch: gnuplot is not installed (Debian: gnuplot-nox): "
              << "no picture, the data is written\n";
    return;
  }
  written->push_back(out / (stem + ".gp"));
  written->push_back(out / (stem + ".png"));
}

json ReadSummary(const fs::path& from) {
  const fs::path path = from / "summary.json";
  std::ifstream in(path);
  if (!in) {
    throw InputError(path.string() +
                     ": cannot be read (give a directory written by `wrc solve --out DIR`)");
  }
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw InputError(path.string() + ": not a JSON summary: " + e.what());
  }
}

}  // namespace

WrittenFiles PlotPatchesFrom(const fs::path& from, const fs::path& out, bool power) {
  const json summary = ReadSummary(from);
  if (!summary.contains("patches") || !summary["patches"].is_array()) {
    throw InputError((from / "summary.json").string() + ": no list of patches");
  }
  fs::create_directories(out);
  WrittenFiles written;
  const json& patches = summary["patches"];
  if (patches.empty()) {
    std::cerr << "wrc plot patch: " << (from / "summary.json").string()
              << " has no contact patch (status " << summary.value("status", "?")
              << "): nothing to draw\n";
  }
  const bool halfspace = fs::exists(from / "fields.csv");
  const json& wheelset = summary.contains("wheelset") ? summary["wheelset"] : json();
  const double velocity =
      wheelset.is_object() && wheelset.contains("velocity") && wheelset["velocity"].is_number()
          ? wheelset["velocity"].get<double>()
          : NAN;
  if (power && (halfspace || !std::isfinite(velocity))) {
    throw InputError((from / "summary.json").string() +
                     ": --frictional-power needs a wheel–rail solve written by this version of "
                     "`wrc solve --out` (its slip fields and rolling velocity)");
  }
  for (std::size_t n = 0; n < patches.size(); ++n) {
    const std::string stem = "patch" + std::to_string(n + 1);
    const fs::path fields = from / (halfspace ? "fields.csv" : stem + "_fields.csv");
    PatchFields f = ReadFields(fields);
    f.velocity = velocity;
    DrawPatch(out, stem, f, PatchTitle(patches[n], static_cast<int>(n + 1)), power && f.HasPower(),
              &written);
  }
  return written;
}

WrittenFiles PlotPatchesOfCase(const fs::path& case_path, const fs::path& out, bool power) {
  const auto t0 = std::chrono::steady_clock::now();
  const Case c = LoadCase(case_path);
  auto seconds = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  WrittenFiles written{out / "summary.json"};
  if (c.type == CaseType::kHalfspace) {
    const HalfspaceResult r = SolveHalfspace(c);
    WriteHalfspaceFields(out, r, HalfspaceJson(r, seconds()));
    written.push_back(out / "fields.csv");
  } else {
    WheelRailOptions options;
    options.keep_fields = true;
    const WheelRailResult r = SolveWheelRail(c, options);
    WriteWheelRailFields(out, r, WheelRailJson(r, seconds()));
    for (std::size_t n = 0; n < r.patches.size(); ++n) {
      const std::string stem = "patch" + std::to_string(n + 1);
      written.push_back(out / (stem + "_fields.csv"));
      if (!r.patches[n].curve_y.empty()) written.push_back(out / (stem + "_curve.csv"));
    }
  }
  const WrittenFiles drawn = PlotPatchesFrom(out, out, power);
  written.insert(written.end(), drawn.begin(), drawn.end());
  return written;
}

}  // namespace wrc::cli
