// `wrc study paper`: the paper's two-point and conformal contact results (§4.1) reproduced on
// the shipped heavy-haul profiles: Fig. 13 (vertical force and L/V against the wheelset height
// as the flange-root and tread patches merge) and Figs. 14–16 (creep forces against the wheel's
// angular velocity, tractions and rigid slip of three methods). CSV, gnuplot PNGs and a README
// that puts wrc's numbers beside the paper's.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "studies/shipped_files.h"
#include "studies/study_commands.h"
#include "studies/study_common.h"
#include "tools/wrc/commands.h"
#include "tools/wrc/output_text.h"
#include "tools/wrc/thread_option.h"
#include "wrc/core/case.h"
#include "wrc/core/errors.h"
#include "wrc/core/output_file.h"

namespace wrc::cli {
namespace {

namespace fs = std::filesystem;

constexpr const char* kWho = "wrc study paper";

struct PaperOptions {
  std::string out = "study-paper";
  int threads = AllCores();
  std::vector<double> z_range = {1.0, 1.25, 0.005};  // mm: from, to, step
  int halvings = 3;
  std::vector<double> omega_range = {-34.5, -31.0, 0.1};  // rad/s: from, to, step
  // Fig. 14 positions: the paper's y, and where the high-mileage wheel, with its flange 5.4 mm
  // thinner than the mid-mileage wheel's (Sd 30.9 against 36.3 mm), has flange-root contact.
  std::vector<double> fig14_y = {10.65, 16.0};
  double element = 0.4;  // mm
  std::vector<int> figures = {13, 14};
};

// The paper's numbers that wrc's are put beside (§4.1.1, §4.1.2).
constexpr double kPaperDropKn = 18.1;
constexpr double kPaperLvBefore = 0.92, kPaperLvAfter = 1.13;
constexpr double kPaperMergeZ = 1.18;  // mm
constexpr double kPaperIcpAngleDeg = -32.6, kPaperWgtAngleDeg = -18.6;
constexpr double kMapOmega = -33.7;  // rad/s, Figs. 15–16

// Planar patches are combined once their interpenetration regions touch, as CONTACT's planar
// approach does; the curved reference combines greedily, regions closer than d_sep = 30 mm
// (§4.1.1).
double CombineDistance(const PaperMethod& m) {
  return m.reference == ReferenceSurface::kCurved ? 30.0 : 0.0;
}

// The §4.1 case: the high-mileage wheel on the worn high rail of the 257 m curve, track and
// wheelset as tables/heavy_haul.toml, friction 0.35 on the tread falling to 0.2 on the gauge
// face (flange lubrication), v = 15 m/s, yaw 5 mrad. `state` holds the pose.
std::string HeavyHaulCase(const PaperMethod& m, double element, const std::string& state) {
  std::ostringstream t;
  t.precision(12);
  t << "# The paper's §4.1 heavy-haul case, written by `wrc study paper`.\n"
    << "[problem]\ntype = \"wheel-rail\"\n"
    << "[rail]\nprofile = \"profiles/site_b_hr.prr\"\n"
    << "[wheel]\nprofile = \"profiles/worn_high_mileage.prw\"\n"
    << "[track]\ngauge_height = 15.875\ngauge_width = 1435.1\ncant = 0.0\n"
    << "[wheelset]\nside = \"right\"\nflange_back_distance = 1347.4\n"
    << "flange_back_position = 0.0\nnominal_radius = 444.0\n"
    << "[material]\npoisson = 0.28\nshear_modulus = 82000.0\n"
    << "[friction]\nalpha_deg = [-30.0, -20.0]\nmu = [0.2, 0.35]\n"
    << "[grid]\ndx = " << element << "\nds = " << element << "\n"
    << MethodSection(m, CombineDistance(m)) << "[state]\n"
    << state;
  return t.str();
}

// §4.1.1: y = 14.85 mm (full flange contact), roll −1.3 mrad, ω = −32.1 rad/s, z prescribed.
std::string Fig13State(double z) {
  std::ostringstream t;
  t.precision(12);
  t << "y = 14.85\nz = " << z << "\nroll = -0.0013\nyaw = 0.005\nvelocity = 15000.0\n"
    << "omega = -32.1\n";
  return t.str();
}

// §4.1.2: y = 10.65 mm, roll +1.3 mrad, Fz = 160 kN, ω varied.
std::string Fig14State(double y, double omega) {
  std::ostringstream t;
  t.precision(12);
  t << "y = " << y
    << "\nfz = 160000.0\nroll = 0.0013\nyaw = 0.005\nvelocity = 15000.0\nomega = " << omega << "\n";
  return t.str();
}

// Writes the case into dir/inputs (next to the profiles) and loads it, so that a user can
// re-solve any point with `wrc solve`.
Case WriteAndLoad(const fs::path& inputs, const std::string& name, const std::string& text) {
  const fs::path path = inputs / (name + ".toml");
  WriteFileAtomically(path, text);
  return LoadCase(path);
}

std::vector<double> Range(const std::vector<double>& r) {
  std::vector<double> v;
  const int n = static_cast<int>(std::lround((r[1] - r[0]) / r[2]));
  for (int k = 0; k <= n; ++k) v.push_back(r[0] + k * r[2]);
  return v;
}

// ---- Fig. 13 ----------------------------------------------------------------------------

struct ZPoint {
  int level = 0;  // 0: the sweep; n: the window around the jump at the step halved n times
  double z = 0.0;
  SolveSummary s;
};

// One step between neighbouring heights.
struct Step {
  double z0 = NAN, z1 = NAN;
  double dfz = NAN;   // N, fz(z1) − fz(z0)
  double jump = NAN;  // N, dfz less the mean of the neighbouring steps (the trend)
  double lv0 = NAN, lv1 = NAN;
};

// The largest |Δfz| between neighbours, and the step that deviates most from its neighbours'
// mean: a smooth curve gives O(h²) there, a jump its height whatever the step.
struct StepAnalysis {
  Step largest, jump;
};

StepAnalysis AnalyzeSteps(const std::vector<const ZPoint*>& p) {
  StepAnalysis a;
  std::vector<double> d;
  for (std::size_t k = 0; k + 1 < p.size(); ++k) d.push_back(p[k + 1]->s.fz - p[k]->s.fz);
  for (std::size_t k = 0; k < d.size(); ++k) {
    if (!std::isfinite(d[k])) continue;
    double trend = 0.0;
    int n = 0;
    for (std::size_t j : {k - 1, k + 1}) {
      if (j < d.size() && std::isfinite(d[j])) trend += d[j], ++n;
    }
    const Step step{p[k]->z,    p[k + 1]->z,   d[k], n ? d[k] - trend / n : NAN,
                    p[k]->s.lv, p[k + 1]->s.lv};
    if (!(std::fabs(step.dfz) <= std::fabs(a.largest.dfz))) a.largest = step;
    if (std::isfinite(step.jump) && !(std::fabs(step.jump) <= std::fabs(a.jump.jump))) {
      a.jump = step;
    }
  }
  return a;
}

struct Fig13 {
  std::vector<std::string> methods = {"icp-loc", "curved"};
  std::vector<std::vector<ZPoint>> points;          // per method, sorted by z
  std::vector<std::vector<StepAnalysis>> analysis;  // per method, per level
  std::vector<double> steps;                        // per level, mm
  double window_from = NAN, window_to = NAN;        // mm
};

// The points of one level (the sweep's inside the window for level 0), by z.
std::vector<const ZPoint*> LevelPoints(const Fig13& f, std::size_t m, int level) {
  std::vector<const ZPoint*> out;
  for (const ZPoint& p : f.points[m]) {
    const bool inside = p.z >= f.window_from - 1e-9 && p.z <= f.window_to + 1e-9;
    if (p.level == level && inside) out.push_back(&p);
  }
  return out;
}

std::vector<ZPoint> SolveHeights(const Case& base, const std::vector<double>& zs, int level,
                                 int threads) {
  std::vector<Case> cases(zs.size(), base);
  for (std::size_t k = 0; k < zs.size(); ++k) cases[k].state.z = zs[k];
  const std::vector<SolveSummary> s = SolveAll(cases, threads);
  std::vector<ZPoint> out;
  for (std::size_t k = 0; k < zs.size(); ++k) out.push_back({level, zs[k], s[k]});
  return out;
}

// The window around icp-loc's jump in the sweep: two steps either side of it.
void PlaceWindow(const PaperOptions& o, Fig13* f) {
  std::vector<const ZPoint*> sweep;
  for (const ZPoint& p : f->points[0]) sweep.push_back(&p);
  const StepAnalysis a = AnalyzeSteps(sweep);
  const double h = o.z_range[2];
  const double centre = std::isfinite(a.jump.z0) ? a.jump.z0 : 0.5 * (o.z_range[0] + o.z_range[1]);
  f->window_from = std::max(o.z_range[0], centre - 2.0 * h);
  f->window_to = std::min(o.z_range[1], centre + 3.0 * h);
}

Fig13 RunFig13(const PaperOptions& o, const fs::path& inputs) {
  Fig13 f;
  std::vector<Case> bases;
  for (const std::string& name : f.methods) {
    const PaperMethod& m = PaperMethodNamed(name);
    bases.push_back(WriteAndLoad(inputs, "fig13_" + name,
                                 HeavyHaulCase(m, o.element, Fig13State(o.z_range[0]))));
  }
  const std::vector<double> zs = Range(o.z_range);
  std::cerr << kWho << ": Fig. 13, " << zs.size() << " heights × " << f.methods.size()
            << " methods\n";
  for (const Case& base : bases) f.points.push_back(SolveHeights(base, zs, 0, o.threads));
  PlaceWindow(o, &f);
  f.steps.push_back(o.z_range[2]);
  for (int level = 1; level <= o.halvings; ++level) {
    const double h = o.z_range[2] / std::pow(2.0, level);
    f.steps.push_back(h);
    const std::vector<double> fine = Range({f.window_from, f.window_to, h});
    std::cerr << kWho << ": Fig. 13, step " << h << " mm around the jump (" << fine.size()
              << " heights)\n";
    for (std::size_t m = 0; m < bases.size(); ++m) {
      std::vector<ZPoint> more = SolveHeights(bases[m], fine, level, o.threads);
      f.points[m].insert(f.points[m].end(), more.begin(), more.end());
    }
  }
  for (auto& points : f.points) {
    std::stable_sort(points.begin(), points.end(),
                     [](const ZPoint& a, const ZPoint& b) { return a.z < b.z; });
  }
  f.analysis.resize(f.methods.size());
  for (std::size_t m = 0; m < f.methods.size(); ++m) {
    for (int level = 0; level <= o.halvings; ++level) {
      f.analysis[m].push_back(AnalyzeSteps(LevelPoints(f, m, level)));
    }
  }
  return f;
}

void WriteFig13Csv(const fs::path& dir, const Fig13& f) {
  OutputText csv(dir / "fig13.csv");
  csv.precision(10);
  csv << "method_index,method,level,z,status,fx,fy,fz,lv,n_patches,message\n";
  for (std::size_t m = 0; m < f.methods.size(); ++m) {
    for (const ZPoint& p : f.points[m]) {
      csv << m << ',' << f.methods[m] << ',' << p.level << ',' << p.z << ',' << p.s.status << ','
          << p.s.fx << ',' << p.s.fy << ',' << p.s.fz << ',' << p.s.lv << ',' << p.s.n_patches
          << ",\"" << p.s.message << "\"\n";
    }
  }
  OutputText steps(dir / "fig13_halving.csv");
  steps.precision(10);
  steps << "method,level,step_mm,largest_dfz_N,largest_z0,largest_z1,jump_N,jump_z0,jump_z1,"
           "lv_before,lv_after\n";
  for (std::size_t m = 0; m < f.methods.size(); ++m) {
    for (std::size_t level = 0; level < f.analysis[m].size(); ++level) {
      const StepAnalysis& a = f.analysis[m][level];
      steps << f.methods[m] << ',' << level << ',' << f.steps[level] << ',' << a.largest.dfz << ','
            << a.largest.z0 << ',' << a.largest.z1 << ',' << a.jump.jump << ',' << a.jump.z0 << ','
            << a.jump.z1 << ',' << a.jump.lv0 << ',' << a.jump.lv1 << '\n';
    }
  }
  csv.Commit();
  steps.Commit();
}

// One line per method of `data` (column 1: the method's index): x from column `x`, y from the
// gnuplot expression `y`.
std::string MethodLines(const std::string& data, int x, const std::string& y,
                        const std::vector<std::string>& methods, const char* const* colours) {
  std::ostringstream gp;
  for (std::size_t m = 0; m < methods.size(); ++m) {
    gp << (m ? ", " : "") << "'" << data << "' skip 1 using ($1==" << m << " ? $" << x
       << " : 1/0):" << y << " with linespoints lc rgb '" << colours[m] << "' pt 7 ps 0.4 title '"
       << methods[m] << "'";
  }
  return gp.str();
}

void PlotFig13(const fs::path& dir, const Fig13& f) {
  std::ostringstream gp;
  gp << "set terminal pngcairo size 1200,850 font ',10'\nset output 'fig13.png'\n"
     << "set datafile separator ','\nset grid\nset key top left\n"
     << "set multiplot layout 2,2 title 'Heavy haul, y = 14.85 mm: two patches merge (paper "
        "Fig. 13); bottom: around the jump, step halved'\n"
     << "set xlabel 'wheelset z, mm'\n";
  const char* colour[] = {"#d62728", "#1f77b4"};
  auto panel = [&](const std::string& ylabel, const std::string& column, bool zoom) {
    const bool lv = column == "9";  // L/V starts high on the left: its key goes bottom left
    gp << "set ylabel '" << ylabel << "'\nset key " << (lv ? "bottom" : "top") << " left\n";
    if (zoom) {
      gp << "set xrange [" << f.window_from << ':' << f.window_to << "]\n";
    } else {
      gp << "set xrange [*:*]\n";
    }
    gp << "plot " << MethodLines("fig13.csv", 4, column, f.methods, colour) << "\n";
  };
  panel("F_z, kN", "($8/1000)", false);
  panel("L/V = F_y / F_z, -", "9", false);
  panel("F_z, kN", "($8/1000)", true);
  panel("L/V = F_y / F_z, -", "9", true);
  gp << "unset multiplot\n";
  RunGnuplot(dir, "fig13", gp.str(), kWho);
}

// ---- Figs. 14–16 ------------------------------------------------------------------------

struct Fig14 {
  double y = 0.0;
  std::string suffix;  // of the file names: "_y10.65"
  std::vector<std::string> methods = {"icp-loc", "wgt-loc-2", "curved"};
  std::vector<double> omegas;
  std::vector<std::vector<SolveSummary>> sweep;  // per method, per omega
  std::vector<SolveSummary> maps;                // per method, at kMapOmega with fields
};

Fig14 RunFig14(const PaperOptions& o, const fs::path& inputs, double y) {
  Fig14 f;
  f.y = y;
  std::ostringstream suffix;
  suffix << "_y" << y;
  f.suffix = suffix.str();
  f.omegas = Range(o.omega_range);
  std::vector<Case> bases;
  for (const std::string& name : f.methods) {
    bases.push_back(
        WriteAndLoad(inputs, "fig14" + f.suffix + "_" + name,
                     HeavyHaulCase(PaperMethodNamed(name), o.element, Fig14State(y, kMapOmega))));
  }
  std::cerr << kWho << ": Fig. 14 at y = " << y << " mm, " << f.omegas.size()
            << " angular velocities × " << f.methods.size() << " methods (fz prescribed)\n";
  for (const Case& base : bases) {
    std::vector<Case> cases(f.omegas.size(), base);
    for (std::size_t k = 0; k < cases.size(); ++k) cases[k].state.omega = f.omegas[k];
    f.sweep.push_back(SolveAll(cases, o.threads));
  }
  WheelRailOptions with_fields;
  with_fields.keep_fields = true;
  f.maps = SolveAll(bases, o.threads, with_fields);
  return f;
}

void WriteFig14Csv(const fs::path& dir, const Fig14& f) {
  OutputText csv(dir / ("fig14" + f.suffix + ".csv"));
  csv.precision(10);
  csv << "method_index,method,omega,status,fx,fs,fy,fz,z,n_patches,contact_angle_deg,mu,message\n";
  for (std::size_t m = 0; m < f.methods.size(); ++m) {
    for (std::size_t k = 0; k < f.omegas.size(); ++k) {
      const SolveSummary& s = f.sweep[m][k];
      csv << m << ',' << f.methods[m] << ',' << f.omegas[k] << ',' << s.status << ',' << s.fx << ','
          << s.fs << ',' << s.fy << ',' << s.fz << ',' << s.z << ',' << s.n_patches << ','
          << Degrees(s.contact_angle) << ',' << s.mu << ",\"" << s.message << "\"\n";
    }
  }
  csv.Commit();
}

// Per element in contact: tractions (Fig. 15) and rigid slip (Fig. 16), in each patch's own
// (x, s) frame.
void WriteFieldsCsv(const fs::path& dir, const Fig14& f) {
  OutputText csv(dir / ("fig15_16_fields" + f.suffix + ".csv"));
  csv.precision(8);
  csv << "method_index,method,patch,x,s,pn,px,ps,wx,ws,y_track,y_plane\n";
  for (std::size_t m = 0; m < f.methods.size(); ++m) {
    const std::vector<PatchResult>& patches = f.maps[m].result.patches;
    for (std::size_t p = 0; p < patches.size(); ++p) {
      const PatchResult& r = patches[p];
      for (int j = 0; j < r.grid.ny; ++j) {
        for (int i = 0; i < r.grid.nx; ++i) {
          const std::size_t e = r.grid.index(i, j);
          if (e >= r.pn.size() || !(r.pn[e] > 0.0)) continue;
          const double wx = e < r.wx.size() ? r.wx[e] : NAN, ws = e < r.ws.size() ? r.ws[e] : NAN;
          csv << m << ',' << f.methods[m] << ',' << p + 1 << ',' << r.grid.x(i) << ','
              << r.grid.y(j) << ',' << r.pn[e] << ',' << r.px[e] << ',' << r.ps[e] << ',' << wx
              << ',' << ws << ',' << LateralTrackY(r, j) << ','
              << r.reference_T(1) + r.grid.y(j) * std::cos(r.contact_angle) << '\n';
        }
      }
    }
  }
  csv.Commit();
}

void PlotFig14(const fs::path& dir, const Fig14& f) {
  std::ostringstream gp;
  const std::string data = "fig14" + f.suffix + ".csv";
  gp << "set terminal pngcairo size 1200,500 font ',10'\nset output 'fig14" << f.suffix
     << ".png'\nset datafile separator ','\nset grid\nset key bottom right\n"
     << "set multiplot layout 1,2 title 'Heavy haul, high-mileage wheel, y = " << f.y
     << " mm, F_z = 160 kN: creep forces against the angular velocity (paper Fig. 14)'\n"
     << "set xlabel 'omega, rad/s'\n";
  const char* colour[] = {"#d62728", "#2ca02c", "#1f77b4"};
  for (const auto& [label, column] : {std::pair<std::string, std::string>{"F_x, kN", "($5/1000)"},
                                      {"F_s (sum over patches), kN", "($6/1000)"}}) {
    gp << "set ylabel '" << label << "'\nplot " << MethodLines(data, 3, column, f.methods, colour)
       << "\n";
  }
  gp << "unset multiplot\n";
  RunGnuplot(dir, "fig14" + f.suffix, gp.str(), kWho);
}

// Heat maps of two field columns per method, each element drawn as its dx × ds cell at its
// lateral track position (the patches of a planar method each have their own plane).
void PlotFieldMaps(const fs::path& dir, const Fig14& f, double element, const std::string& name,
                   const std::string& title, const std::vector<std::string>& labels,
                   const std::vector<int>& columns) {
  const std::string data = "fig15_16_fields" + f.suffix + ".csv";
  std::ostringstream gp;
  gp << "set terminal pngcairo size 1100," << 260 * f.methods.size() + 60
     << " font ',10'\nset output '" << name << f.suffix << ".png'\nset datafile separator ','\n"
     << "set multiplot layout " << f.methods.size() << ",2 title '" << title << ", y = " << f.y
     << " mm'\n"
     << "set xlabel 'lateral position y, track frame, mm'\nset ylabel 'x, mm'\n"
     << "set palette defined (-1 '#2166ac', 0 '#f7f7f7', 1 '#b2182b')\nset style fill solid\n";
  for (std::size_t m = 0; m < f.methods.size(); ++m) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      gp << "set title '" << f.methods[m] << ": " << labels[c] << "'\nset cbrange [*:*]\n"
         << "stats '" << data << "' skip 1 using ($1==" << m << " ? abs($" << columns[c]
         << ") : 1/0) nooutput\nif (STATS_records > 0) { set cbrange [-STATS_max:STATS_max] }\n"
         << "plot '" << data << "' skip 1 using ($1==" << m << " ? $11 : 1/0):4:(" << element / 2
         << "):(" << element / 2 << "):" << columns[c] << " with boxxyerror lc palette notitle\n";
    }
  }
  gp << "unset multiplot\n";
  RunGnuplot(dir, name + f.suffix, gp.str(), kWho);
}

// ---- README -----------------------------------------------------------------------------

// L/V of method m at height z (NaN when not solved there).
double LvAt(const Fig13& f, std::size_t m, double z) {
  for (const ZPoint& p : f.points[m]) {
    if (std::fabs(p.z - z) < 1e-9) return p.s.lv;
  }
  return NAN;
}

void WriteFig13Summary(std::ostream& md, const Fig13& f) {
  const StepAnalysis& icp = f.analysis[0].back();
  md << "## Fig. 13: patches merging (§4.1.1)\n\n"
     << "y = 14.85 mm, roll −1.3 mrad, yaw 5 mrad, v = 15 m/s, ω = −32.1 rad/s, z prescribed. "
     << "icp-loc (planar, initial contact point, sampled angle) solves the flange, flange-root "
        "and tread patches apart and combines two once their interpenetration regions touch; "
        "curved combines regions closer than 30 mm (greedy combination). "
     << "[fig13.png](fig13.png), data [fig13.csv](fig13.csv), "
        "[fig13_halving.csv](fig13_halving.csv).\n\n"
     << "| quantity | paper (CONTACT) | wrc icp-loc | wrc curved |\n|---|---|---|---|\n"
     << "| z of the merge, mm | " << kPaperMergeZ << " | " << Fixed(icp.jump.z0, 4) << " … "
     << Fixed(icp.jump.z1, 4) << " | no merge (one patch) |\n"
     << "| drop of Fz, kN | " << kPaperDropKn << " | " << Kn(-icp.jump.jump) << " | – |\n"
     << "| L/V before → after | " << kPaperLvBefore << " → " << kPaperLvAfter << " | "
     << Fixed(icp.jump.lv0, 3) << " → " << Fixed(icp.jump.lv1, 3) << " | "
     << Fixed(LvAt(f, 1, icp.jump.z0), 3) << " → " << Fixed(LvAt(f, 1, icp.jump.z1), 3)
     << " (same heights) |\n\n"
     << "The drop is the step of Fz between neighbouring heights less the mean of the steps "
        "beside it (the rising trend), at the finest step.\n\n"
     << "Under step halving (window " << Fixed(f.window_from, 4) << " … " << Fixed(f.window_to, 4)
     << " mm around the jump): the largest step of Fz between "
        "neighbouring heights, and the step that departs most from its neighbours (kN):\n\n"
     << "| step, mm | icp-loc largest step | icp-loc jump | curved largest step | curved jump "
        "|\n|---|---|---|---|---|\n";
  for (std::size_t level = 0; level < f.steps.size(); ++level) {
    const StepAnalysis& a = f.analysis[0][level];
    const StepAnalysis& b = f.analysis[1][level];
    md << "| " << f.steps[level] << " | " << Kn(a.largest.dfz, 2) << " | " << Kn(a.jump.jump, 2)
       << " | " << Kn(b.largest.dfz, 2) << " | " << Kn(b.jump.jump, 2) << " |\n";
  }
  md << "\nA continuous curve has its largest step halve with the step and its jump shrink "
        "faster still, down to the small ripple of the discretisation (the patch grid moves "
        "with z); a jump keeps both at its height.\n\n";
}

void WriteFig14Intro(std::ostream& md) {
  md << "## Figs. 14–16: rigid slip and creep forces (§4.1.2)\n\n"
     << "Roll +1.3 mrad, yaw 5 mrad, v = 15 m/s, Fz = 160 kN prescribed (z solved), ω varied. "
        "The paper uses the **mid-mileage** wheel of the heavy-haul set, which is not among "
        "the profiles wrc has (CONTACT's test bank holds the high rail and the high-mileage "
        "wheel only); wrc runs the **high-mileage** wheel of Fig. 13, at the paper's y = 10.65 "
        "mm and at y = 16 mm, where this wheel, its flange 5.4 mm thinner (Sd 30.9 against "
        "36.3 mm), has the flange-root contact the paper's wheel has at 10.65 mm. So the "
        "numbers are not the paper's; the comparison is of what the methods do.\n\n";
}

void WriteFig14Summary(std::ostream& md, const Fig14& f) {
  md << "### y = " << f.y << " mm\n\n"
     << "[fig14" << f.suffix << ".png](fig14" << f.suffix << ".png) (Fx, Fs against ω), "
     << "[fig15_tractions" << f.suffix << ".png](fig15_tractions" << f.suffix << ".png), "
     << "[fig16_rigid_slip" << f.suffix << ".png](fig16_rigid_slip" << f.suffix
     << ".png) at ω = " << kMapOmega << " rad/s; data [fig14" << f.suffix << ".csv](fig14"
     << f.suffix << ".csv), [fig15_16_fields" << f.suffix << ".csv](fig15_16_fields" << f.suffix
     << ".csv). At ω = " << kMapOmega << " rad/s:\n\n"
     << "| method | paper (mid-mileage wheel): δ, μ | wrc: δ of the main patch | μ there | "
        "patches | Fx, kN | Fs, kN | Fy, kN |\n|---|---|---|---|---|---|---|---|\n";
  const std::string paper[] = {Fixed(kPaperIcpAngleDeg, 1) + "°, 0.20 (flange)",
                               Fixed(kPaperWgtAngleDeg, 1) + "°, 0.35 (tread)",
                               "varies: 0.20 … 0.35 across the patch"};
  for (std::size_t m = 0; m < f.methods.size(); ++m) {
    const SolveSummary& s = f.maps[m];
    md << "| " << f.methods[m] << " | " << paper[m] << " | " << Fixed(Degrees(s.contact_angle), 1)
       << "° | " << Fixed(s.mu, 3) << " | " << s.n_patches << " | " << Kn(s.fx) << " | " << Kn(s.fs)
       << " | " << Kn(s.fy) << " |\n";
  }
  md << "\n";
}

void WriteReadme(const fs::path& dir, const PaperOptions& o, const Fig13* f13,
                 const std::vector<Fig14>& f14) {
  OutputText md(dir / "README.md");
  md << "# The paper's §4.1 results, reproduced by wrc\n\n"
     << "Generated by `wrc study paper --out " << o.out << " --element " << o.element
     << " --z-range " << o.z_range[0] << ',' << o.z_range[1] << ',' << o.z_range[2]
     << " --halvings " << o.halvings << " --omega-range " << o.omega_range[0] << ','
     << o.omega_range[1] << ',' << o.omega_range[2]
     << "`. The high-mileage wheel and the worn high rail of the 257 m curve (tables/profiles/"
        "worn_high_mileage.prw, site_b_hr.prr), track and wheelset as tables/heavy_haul.toml, "
        "friction 0.35 on the tread falling to 0.2 on the gauge face, elements of "
     << o.element
     << " mm. The case files solved are in `inputs/` (`wrc solve inputs/fig13_curved.toml` "
        "re-solves one point).\n\n";
  if (f13) WriteFig13Summary(md, *f13);
  if (!f14.empty()) WriteFig14Intro(md);
  for (const Fig14& f : f14) WriteFig14Summary(md, f);
  md.Commit();
}

void ReproduceFig14(const PaperOptions& o, const fs::path& dir, const Fig14& f) {
  WriteFig14Csv(dir, f);
  WriteFieldsCsv(dir, f);
  PlotFig14(dir, f);
  PlotFieldMaps(dir, f, o.element, "fig15_tractions",
                "Tangential tractions at omega = -33.7 rad/s (paper Fig. 15)",
                {"p_x, N/mm^2", "p_s, N/mm^2"}, {7, 8});
  PlotFieldMaps(dir, f, o.element, "fig16_rigid_slip",
                "Relative rigid slip at omega = -33.7 rad/s (paper Fig. 16)", {"w_x, -", "w_s, -"},
                {9, 10});
}

int RunPaperStudy(const PaperOptions& o) {
  const fs::path dir = o.out;
  const fs::path inputs = dir / "inputs";
  fs::create_directories(inputs);
  WriteShippedFiles(inputs, {"profiles/site_b_hr.prr", "profiles/worn_high_mileage.prw"});
  const auto wants = [&](int fig) {
    return std::find(o.figures.begin(), o.figures.end(), fig) != o.figures.end();
  };
  std::unique_ptr<Fig13> f13;
  std::vector<Fig14> f14;
  if (wants(13)) {
    f13 = std::make_unique<Fig13>(RunFig13(o, inputs));
    WriteFig13Csv(dir, *f13);
    PlotFig13(dir, *f13);
  }
  if (wants(14)) {
    for (double y : o.fig14_y) {
      f14.push_back(RunFig14(o, inputs, y));
      ReproduceFig14(o, dir, f14.back());
    }
  }
  WriteReadme(dir, o, f13.get(), f14);
  SayReport(kWho, dir / "README.md");
  return kExitOk;
}

void CheckRange(const std::vector<double>& r, const std::string& option) {
  if (r.size() != 3 || !(r[2] > 0.0) || !(r[1] > r[0]) || (r[1] - r[0]) / r[2] > 1e4) {
    throw InputError(option + ": give FROM,TO,STEP with FROM < TO, STEP > 0, at most 1e4 steps");
  }
}

}  // namespace

void AddPaperStudy(CLI::App& study, int* exit_code) {
  auto* paper = study.add_subcommand(
      "paper",
      "The paper's two-point and conformal contact results (Figs. 13-16) on the shipped "
      "heavy-haul profiles");
  auto o = std::make_shared<PaperOptions>();
  AddOutOption(paper, &o->out, "Output directory (CSV, PNG, README.md, inputs/)");
  AddThreadsOption(paper, &o->threads, false);
  paper->add_option("--z-range", o->z_range, "Fig. 13: wheelset heights FROM,TO,STEP, mm")
      ->delimiter(',')
      ->expected(3)
      ->capture_default_str();
  paper->add_option("--halvings", o->halvings, "Fig. 13: halve the step this often around the jump")
      ->check(CLI::Range(0, 12))
      ->capture_default_str();
  paper
      ->add_option("--omega-range", o->omega_range,
                   "Fig. 14: angular velocities FROM,TO,STEP, rad/s")
      ->delimiter(',')
      ->expected(3)
      ->capture_default_str();
  paper->add_option("--fig14-y", o->fig14_y, "Fig. 14: lateral positions, mm")
      ->delimiter(',')
      ->capture_default_str();
  paper->add_option("--element", o->element, "Element size dx = ds, mm")
      ->check(CLI::Range(0.05, 5.0))
      ->capture_default_str();
  paper
      ->add_option("--figures", o->figures, "Which figures: 13 (with its halving), 14 (with 15-16)")
      ->delimiter(',')
      ->check(CLI::IsMember({13, 14}))
      ->capture_default_str();
  OnRun(paper, exit_code, kWho, [o]() {
    CheckRange(o->z_range, "--z-range");
    CheckRange(o->omega_range, "--omega-range");
    return RunPaperStudy(*o);
  });
}

}  // namespace wrc::cli
