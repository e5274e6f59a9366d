// `wrc study solver` and `wrc study tables`: what accuracy costs in time.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "studies/study_commands.h"
#include "studies/study_common.h"
#include "tools/wrc/commands.h"
#include "tools/wrc/gnuplot.h"
#include "tools/wrc/output_text.h"
#include "tools/wrc/thread_option.h"
#include "tools/wrc/verify.h"
#include "wrc/core/case.h"
#include "wrc/core/errors.h"
#include "wrc/core/halfspace.h"
#include "wrc/core/scene.h"
#include "wrc/core/solver_status.h"
#include "wrc/core/wheelrail.h"
#include "wrc/generator/generator.h"

namespace wrc::cli {
namespace {

namespace fs = std::filesystem;

// ---- solver: accuracy against element size and time ------------------------------------------

// What the solver study compares between element sizes: the total force on the rail (on body 1
// for half-space cases) and the wheelset height (the approach for half-space cases).
struct SolverRow {
  std::string name;
  double size = 0.0, seconds = 0.0, fx = 0.0, fy = 0.0, fz = 0.0, z = 0.0;
  std::string status;
};

// The case with elements of `size` mm in both directions.
Case WithElementSize(Case c, double size) {
  c.grid.dx = size;
  if (c.type == CaseType::kWheelRail) {
    c.grid.ds = size;
  } else {
    c.grid.dy = size;
  }
  return c;
}

// One solve of `c` (best of two: the first run also warms the per-size influence caches).
SolverRow SolveTimed(const Case& c) {
  SolverRow row;
  double best = 1e300;
  for (int rep = 0; rep < 2; ++rep) {
    const auto t0 = std::chrono::steady_clock::now();
    if (c.type == CaseType::kWheelRail) {
      const WheelRailResult r = SolveWheelRail(c);
      row = {"", 0.0, 0.0, r.force_T(0), r.force_T(1), r.force_T(2), r.z, ToString(r.status)};
    } else {
      const HalfspaceResult r = SolveHalfspace(c);
      row = {"", 0.0, 0.0, r.fx, r.fy, r.fn, r.approach, ToString(r.status)};
    }
    best = std::min(best, SecondsSince(t0));
  }
  row.seconds = best;
  return row;
}

// Writes the gnuplot script and runs it; a missing gnuplot costs the picture, not the data.
void DrawStudy(const fs::path& dir, const std::string& script_name, const std::string& script,
               const std::string& study) {
  DrawOrSay(dir, script_name, script,
            "wrc study " + study +
                ": gnuplot is not installed (Debian: gnuplot-nox); the data is in " + dir.string());
}

// The error of fy of `r` against the finest solve of its case, as a fraction of that solve's fz.
double FyError(const std::vector<SolverRow>& rows, const SolverRow& r, double finest) {
  for (const SolverRow& f : rows) {
    if (f.name == r.name && f.size == finest) {
      const double load = std::fabs(f.fz) > 0.0 ? std::fabs(f.fz) : 1.0;
      return std::fabs(r.fy - f.fy) / load;
    }
  }
  return NAN;
}

// One data block per case (gnuplot's `index`): element size, time per solve, error of fy, and
// whether the size is the case's own (as its file gives it). The finest size is the reference
// and has no error to draw on the logarithmic axis, so it is left out.
void WriteSolverLines(const fs::path& path, const std::vector<SolverRow>& rows,
                      const std::vector<std::string>& names, double finest,
                      const std::vector<double>& own_size) {
  OutputText dat(path);
  dat.precision(8);
  for (std::size_t k = 0; k < names.size(); ++k) {
    dat << (k ? "\n\n" : "") << "# " << names[k] << "\n# element_mm seconds err_fy_rel_load own\n";
    for (const SolverRow& r : rows) {
      if (r.name != names[k] || r.size == finest) continue;
      dat << r.size << ' ' << r.seconds << ' ' << FyError(rows, r, finest) << ' '
          << (r.size == own_size[k] ? 1 : 0) << '\n';
    }
  }
  dat.Commit();
}

// The plot's ranges, set from the drawn points (time, error of fy): gnuplot's own would be
// empty, with warnings, when every case has one coarse size (two sizes given). Each range spans
// its points and a quarter of a decade more on each side; a single value a decade around it.
std::string LogRanges(const std::vector<SolverRow>& rows, double finest) {
  double x_lo = INFINITY, x_hi = 0.0, y_lo = INFINITY, y_hi = 0.0;
  for (const SolverRow& r : rows) {
    const double error = FyError(rows, r, finest);
    if (r.size == finest || !(r.seconds > 0.0) || !(error > 0.0)) continue;
    x_lo = std::min(x_lo, r.seconds), x_hi = std::max(x_hi, r.seconds);
    y_lo = std::min(y_lo, error), y_hi = std::max(y_hi, error);
  }
  if (!(x_hi > 0.0)) return "set xrange [1e-3:1]\nset yrange [1e-6:1]\n";  // nothing to draw
  auto range = [](double lo, double hi) {
    const double margin = lo == hi ? std::sqrt(10.0) : std::pow(10.0, 0.25);
    std::ostringstream text;
    text << '[' << lo / margin << ':' << hi * margin << "]\n";
    return text.str();
  };
  return "set xrange " + range(x_lo, x_hi) + "set yrange " + range(y_lo, y_hi);
}

// Error of fy against time: each case its own coloured line through its element sizes (labelled
// at each point), and a ring around the solves at each case's own element size.
void DrawSolverPicture(const fs::path& out, const std::vector<SolverRow>& rows,
                       const std::vector<double>& sizes, const std::vector<double>& own_size) {
  std::vector<std::string> names;
  for (const SolverRow& r : rows) {
    if (std::find(names.begin(), names.end(), r.name) == names.end()) names.push_back(r.name);
  }
  WriteSolverLines(out / "solver_lines.dat", rows, names, sizes.back(), own_size);
  // Colours that stay apart on white (ColorBrewer's Dark2), repeated beyond eight cases.
  const char* colours[] = {"#1b9e77", "#d95f02", "#7570b3", "#e7298a",
                           "#66a61e", "#a6761d", "#e6ab02", "#666666"};
  std::ostringstream gp;
  gp << "set terminal pngcairo noenhanced size 1000,650 font ',10'\nset output 'solver.png'\n"
     << "set logscale xy\nset format xy '%g'\nset grid\n"
     << "set key outside right top box opaque Left reverse width 1\n"
     << "set xlabel 'time per solve, s'\n"
     << "set ylabel 'error of fy against " << sizes.back() << " mm elements, fraction of fz'\n"
     << "set title 'Solver accuracy against cost (point labels: element size dx = ds, mm)'\n"
     << LogRanges(rows, sizes.back()) << "plot ";
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string colour = std::string("rgb '") + colours[k % 8] + "'";
    gp << "'solver_lines.dat' index " << k << " using 2:3 with linespoints lw 2 pt 7 lc " << colour
       << " title '" << names[k] << "', '' index " << k
       << " using 2:3:(sprintf('%g', $1)) with labels offset char 1.2,0.6 tc " << colour
       << " notitle, ";
  }
  gp << "'solver_lines.dat' using 2:($4 > 0 ? $3 : 1/0) with points pt 6 ps 3 lw 2 lc "
        "rgb 'black' title \"the case file's own element size\"\n";
  DrawStudy(out, "solver.gp", gp.str(), "solver");
}

void WriteSolverReport(const fs::path& out, const std::vector<SolverRow>& rows,
                       const std::vector<double>& sizes, const std::vector<double>& own_size) {
  OutputText csv(out / "solver.csv");
  csv << "case,element_mm,seconds,status,fx,fy,fz,z,err_fx_rel_load,err_fy_rel_load,err_z_um\n";
  csv.precision(8);
  OutputText md(out / "solver.md");
  md << "# Solver accuracy against cost\n\nEvery case solved with square elements of each size "
        "(best time of two solves); errors against the finest size, forces as a fraction of "
        "that solve's vertical (normal) force, z (the approach for half-space cases) in µm.\n\n"
     << "| case | element (mm) | s per solve | status | abs Δfx / fz | abs Δfy / fz | abs Δz (µm) "
        "|\n"
     << "|---|---|---|---|---|---|---|\n";
  const double finest = sizes.back();
  for (const SolverRow& r : rows) {
    const SolverRow* fine = nullptr;
    for (const SolverRow& f : rows) {
      if (f.name == r.name && f.size == finest) fine = &f;
    }
    const double load = std::fabs(fine->fz) > 0.0 ? std::fabs(fine->fz) : 1.0;
    const double efx = std::fabs(r.fx - fine->fx) / load, efy = std::fabs(r.fy - fine->fy) / load;
    const double ez = 1e3 * std::fabs(r.z - fine->z);
    csv << '"' << r.name << "\"," << r.size << ',' << r.seconds << ',' << r.status << ',' << r.fx
        << ',' << r.fy << ',' << r.fz << ',' << r.z << ',' << efx << ',' << efy << ',' << ez
        << '\n';
    char line[300];
    std::snprintf(line, sizeof line, "| %s | %.3g | %.4f | %s | %.2e | %.2e | %.3f |\n",
                  r.name.c_str(), r.size, r.seconds, r.status.c_str(), efx, efy, ez);
    md << line;
  }
  md << "\nData: `solver.csv`; picture: `solver.png` (error of fy against time per solve, one "
        "line per case; `solver_lines.dat` holds what it draws).\n";
  csv.Commit();
  DrawSolverPicture(out, rows, sizes, own_size);
  md.Commit();
}

// Solver accuracy against cost: each case at each element size, errors against the finest.
int StudySolver(const std::vector<std::string>& case_paths, std::vector<double> sizes,
                const fs::path& out) {
  std::sort(sizes.begin(), sizes.end(), std::greater<double>());
  std::vector<Case> cases;
  for (const std::string& path : case_paths) cases.push_back(LoadCase(path));  // all read first
  fs::create_directories(out);
  std::vector<SolverRow> rows;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    for (const double size : sizes) {
      SolverRow row = SolveTimed(WithElementSize(cases[k], size));
      row.name = fs::path(case_paths[k]).filename().string();
      row.size = size;
      std::cerr << "solver study: " << row.name << " at " << size << " mm: " << row.seconds
                << " s, " << row.status << '\n';
      rows.push_back(row);
    }
  }
  std::vector<double> own_size;  // each case's element size as its file gives it
  for (const Case& c : cases) own_size.push_back(c.grid.dx);
  WriteSolverReport(out, rows, sizes, own_size);
  SayReport("solver study", out / "solver.md");
  return kExitOk;
}

// ---- tables: accuracy against points, size and time -----------------------------------------

struct TableRow {
  std::string kind;  // kRefined, kMidpoints or kUniform
  double target = 0.0;
  int pass = -1;  // kMidpoints: the pass of the refinement
  std::size_t points = 0;
  double generate_s = 0.0, cpu_s = 0.0;
  std::uintmax_t bytes = 0;
  // Per mode (0 linear, 1 cubic): the largest p95 / max of the force errors relative to the
  // local load, z's p95 (mm), the lookup time.
  double force_p95[2] = {}, force_max[2] = {}, force_rms[2] = {}, z_p95[2] = {}, lookup_ns[2] = {};
  std::string axes;
};

// The kinds of table a study compares: the scene's refinement at each target, the passes of one
// refinement that stops only when every sampled midpoint is within the target (quantile 1: the
// rule of tables made before the quantile stop, so the generator that came before), and uniform
// tables with the refined tables' node counts.
constexpr const char* kRefined = "refined";
constexpr const char* kMidpoints = "midpoint_rule";
constexpr const char* kUniform = "uniform";

struct TablesStudy {
  fs::path scene, out;
  std::vector<double> targets;
  double midpoint_target = 0.0;  ///< 0: no midpoint-rule run
  bool uniform = false;
  int samples = 1000;
  std::uint64_t seed = 1;
  int threads = 0;
};

std::vector<double> Linspace(double first, double last, std::size_t n) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) {
    v[i] = n == 1 ? first : first + (last - first) * static_cast<double>(i) / (n - 1);
  }
  if (n > 1) v.back() = last;
  return v;
}

double JsonNumber(const nlohmann::json& j) { return j.is_number() ? j.get<double>() : NAN; }

void Measure(const fs::path& table, const TablesStudy& study, TableRow* row) {
  VerifyOptions options;
  options.table = table.string();
  options.samples = study.samples;
  options.seed = study.seed;
  options.threads = study.threads;
  const Verification v = VerifyTable(options);
  for (int mode = 0; mode < 2; ++mode) {
    const nlohmann::json& m = v.report["interpolation"][mode == 0 ? "linear" : "cubic"];
    for (const std::string& name : v.output_names) {
      const nlohmann::json& o = m["outputs"][name];
      if (IsForceOutput(name)) {
        row->force_p95[mode] = std::max(row->force_p95[mode], JsonNumber(o["load"]["p95"]));
        row->force_max[mode] = std::max(row->force_max[mode], JsonNumber(o["load"]["max"]));
        row->force_rms[mode] = std::max(row->force_rms[mode], JsonNumber(o["load"]["rms"]));
      }
      if (name == "z") row->z_p95[mode] = JsonNumber(o["p95_abs"]);
    }
    row->lookup_ns[mode] = 1e9 * JsonNumber(m["lookup_time_s"]["mean"]);
  }
  row->bytes = fs::file_size(table);
}

GenerateSummary Generate(const Scene& scene, const fs::path& table, int threads, bool keep_passes) {
  fs::remove(table);
  std::error_code ignored;
  fs::remove(fs::path(table.string() + ".journal"), ignored);
  fs::remove_all(fs::path(table.string() + ".refine"), ignored);
  GenerateOptions options;
  options.output = table;
  options.threads = threads;
  options.progress = ProgressMode::kOff;
  options.handle_signals = true;
  options.keep_passes = keep_passes;
  const GenerateSummary summary = GenerateTable(scene, options);
  if (!summary.complete) {
    throw Interrupted("interrupted while generating " + table.string() +
                      "; the study's report is not written");
  }
  return summary;
}

std::string AxesText(const std::vector<SceneAxis>& axes) {
  std::string text;
  for (const SceneAxis& a : axes) {
    text += (text.empty() ? "" : " × ") + a.name + " " + std::to_string(a.values.size());
  }
  return text;
}

std::string RowLabel(const TableRow& r) {
  char label[64];
  if (r.kind == kMidpoints) {
    std::snprintf(label, sizeof label, "midpoint rule %g, pass %d", r.target, r.pass);
  } else {
    std::snprintf(label, sizeof label, "%s %g", r.kind.c_str(), r.target);
  }
  return label;
}

void WriteTablesCsv(const fs::path& out, const std::vector<TableRow>& rows) {
  OutputText csv(out / "tables.csv");
  csv << "kind,target,pass,points,generate_s,cpu_s,file_bytes,force_p95_linear,force_rms_linear,"
         "force_max_linear,z_p95_linear_mm,lookup_ns_linear,force_p95_cubic,force_rms_cubic,"
         "force_max_cubic,z_p95_cubic_mm,lookup_ns_cubic,axes\n";
  csv.precision(6);
  for (const TableRow& r : rows) {
    csv << r.kind << ',' << r.target << ',' << r.pass << ',' << r.points << ',' << r.generate_s
        << ',' << r.cpu_s << ',' << r.bytes;
    for (int m = 0; m < 2; ++m) {
      csv << ',' << r.force_p95[m] << ',' << r.force_rms[m] << ',' << r.force_max[m] << ','
          << r.z_p95[m] << ',' << r.lookup_ns[m];
    }
    csv << ",\"" << r.axes << "\"\n";
  }
  csv.Commit();
}

void WriteTablesMarkdown(const fs::path& out, const TablesStudy& study,
                         const std::vector<TableRow>& rows) {
  OutputText md(out / "tables.md");
  md << "# Table accuracy against size and time\n\nTables of `" << study.scene.filename().string()
     << "`, " << study.samples << " uniform random samples (seed " << study.seed
     << ") re-solved exactly. Force errors: the largest over the force outputs, as a fraction "
        "of the local wheel load. CPU: the generating process's CPU time (all threads) up to "
        "that table.\n\n"
     << "| table | points | CPU (s) | wall (s) | file (MB) | p95 lin | rms lin | max lin | "
        "p95 cub | rms cub | z p95 lin (µm) | lookup lin / cub (ns) |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const TableRow& r : rows) {
    char line[400];
    std::snprintf(line, sizeof line,
                  "| %s | %zu | %.0f | %.0f | %.1f | %.2f %% | %.2f %% | %.1f %% | %.2f %% | "
                  "%.2f %% | %.1f | %.0f / %.0f |\n",
                  RowLabel(r).c_str(), r.points, r.cpu_s, r.generate_s, r.bytes / 1e6,
                  100 * r.force_p95[0], 100 * r.force_rms[0], 100 * r.force_max[0],
                  100 * r.force_p95[1], 100 * r.force_rms[1], 1e3 * r.z_p95[0], r.lookup_ns[0],
                  r.lookup_ns[1]);
    md << line;
  }
  md.Commit();
}

// One data file per kind (CPU s, MB, points, p95 multilinear and cubic in %), so lines connect.
void WriteTablesData(const fs::path& out, const std::vector<TableRow>& rows) {
  for (const char* kind : {kRefined, kMidpoints, kUniform}) {
    OutputText dat(out / (std::string("tables_") + kind + ".dat"));
    dat << "# cpu_s file_mb points p95_linear_percent p95_cubic_percent\n";
    for (const TableRow& r : rows) {
      if (r.kind != kind) continue;
      dat << r.cpu_s << ' ' << r.bytes / 1e6 << ' ' << r.points << ' ' << 100 * r.force_p95[0]
          << ' ' << 100 * r.force_p95[1] << '\n';
    }
    dat.Commit();
  }
}

// p95 against CPU time (left) and file size (right); every kind that has rows.
void DrawTables(const fs::path& out, const TablesStudy& study, const std::vector<TableRow>& rows) {
  struct Series {
    const char* kind;
    const char* title;
    const char* colours[2];
  };
  const Series series[] = {{kRefined, "refined (quantile stop)", {"#2166ac", "#67a9cf"}},
                           {kMidpoints, "midpoint rule, its passes", {"#b2182b", "#ef8a62"}},
                           {kUniform, "uniform", {"#4d9221", "#a1d76a"}}};
  std::string plots[2];
  const int x_column[2] = {1, 2};
  for (int panel = 0; panel < 2; ++panel) {
    for (const Series& s : series) {
      if (std::none_of(rows.begin(), rows.end(),
                       [&](const TableRow& r) { return r.kind == s.kind; }))
        continue;
      for (int mode = 0; mode < 2; ++mode) {
        plots[panel] += std::string(plots[panel].empty() ? "plot " : ", ") + "'tables_" + s.kind +
                        ".dat' using " + std::to_string(x_column[panel]) + ":" +
                        std::to_string(4 + mode) + " with linespoints pt " +
                        std::to_string(mode == 0 ? 7 : 6) + " lc rgb '" + s.colours[mode] +
                        "' title '" + s.title + (mode == 0 ? ", multilinear'" : ", cubic'");
      }
    }
    plots[panel] += ", 1 with lines dt 2 lc rgb '#404040' title '1 % of the load'\n";
  }
  std::ostringstream gp;
  gp << "set terminal pngcairo noenhanced size 1400,620 font ',10'\nset output 'tables.png'\n"
     << "set multiplot layout 1,2 title \"" << study.scene.filename().string()
     << ": verified p95 force error against generation cost (" << study.samples
     << " exact solves per table)\"\n"
     << "set logscale xy\nset grid\nset key top right\nset yrange [0.1:*]\n"
     << "set ylabel 'p95 force error, % of the local wheel load'\n"
     << "set xlabel 'generation CPU time (s, all threads)'\n"
     << plots[0] << "set xlabel 'table file (MB)'\n"
     << plots[1] << "unset multiplot\n";
  DrawStudy(out, "tables.gp", gp.str(), "tables");
}

void WriteTablesReport(const fs::path& out, const TablesStudy& study,
                       const std::vector<TableRow>& rows) {
  WriteTablesCsv(out, rows);
  WriteTablesData(out, rows);
  DrawTables(out, study, rows);
  WriteTablesMarkdown(out, study, rows);
}

void SayRow(const TableRow& row) {
  std::cerr << "tables study: " << RowLabel(row) << ": " << row.points << " points"
            << (row.axes.empty() ? "" : " (" + row.axes + ")") << ", " << row.cpu_s
            << " CPU s, p95 " << 100 * row.force_p95[0] << " % (cubic " << 100 * row.force_p95[1]
            << " %) of the load\n";
}

// One table of the study: generated, timed and verified; *axes receives its nodes.
TableRow GenerateAndMeasure(const Scene& scene, const char* kind, double target,
                            const fs::path& path, const TablesStudy& study,
                            std::vector<SceneAxis>* axes) {
  const auto t0 = std::chrono::steady_clock::now();
  const GenerateSummary summary = Generate(scene, path, study.threads, false);
  TableRow row;
  row.kind = kind;
  row.target = target;
  row.points = summary.points;
  row.generate_s = SecondsSince(t0);
  row.cpu_s = summary.cpu_seconds;
  row.axes = AxesText(summary.axes);
  *axes = summary.axes;
  Measure(path, study, &row);
  SayRow(row);
  return row;
}

// The scene with `[table.refine]`: a scene without one gets the section's defaults (which
// outputs are refined and their targets), read by the scene parser as if the user had written an
// empty section.
Scene RefinableScene(const Scene& scene, const fs::path& path) {
  if (scene.refine) return scene;
  return ParseScene(scene.base.source_text + "\n[table.refine]\n", path.parent_path(),
                    scene.base.source_name);
}

// The scene refined to `target`, its absolute targets (z) scaled with the force target, so
// that every target of a study is a target on every refined output.
Scene AtTarget(const Scene& scene, double target) {
  Scene refined = scene;
  const double scale = target / scene.refine->load_fraction;
  refined.refine->load_fraction = target;
  for (auto& [name, value] : refined.refine->absolute) value *= scale;
  return refined;
}

// The midpoint rule's refinement once, every pass's grid kept and measured: each is the table
// that rule gives when its budget stops it there.
std::vector<TableRow> MidpointRulePasses(const Scene& scene, const TablesStudy& study) {
  Scene refined = AtTarget(scene, study.midpoint_target);
  refined.refine->quantile = 1.0;
  const fs::path path =
      study.out / ("midpoint_rule_" + std::to_string(study.midpoint_target) + ".h5");
  const auto t0 = std::chrono::steady_clock::now();
  const GenerateSummary summary = Generate(refined, path, study.threads, true);
  const double wall = SecondsSince(t0);
  std::vector<TableRow> rows;
  for (std::size_t p = 0; p < summary.passes.size(); ++p) {
    TableRow row;
    row.kind = kMidpoints;
    row.target = study.midpoint_target;
    row.pass = static_cast<int>(p);
    row.points = summary.passes[p].points;
    row.cpu_s = summary.passes[p].cpu_seconds;
    row.generate_s = wall * row.cpu_s / summary.cpu_seconds;  // the run's wall time, pro rata
    Measure(path.string() + ".pass" + std::to_string(p) + ".h5", study, &row);
    SayRow(row);
    rows.push_back(row);
  }
  return rows;
}

// Refined tables at several targets and, with --uniform, for each a uniform table with the same
// node count per axis over the same ranges; with --midpoint-rule the passes of that rule's run;
// all verified at the same random points.
int StudyTables(const TablesStudy& study) {
  const Scene scene = RefinableScene(LoadScene(study.scene), study.scene);
  fs::create_directories(study.out);
  std::vector<TableRow> rows;
  for (const double target : study.targets) {
    const Scene refined = AtTarget(scene, target);
    std::vector<SceneAxis> nodes;
    rows.push_back(GenerateAndMeasure(refined, kRefined, target,
                                      study.out / ("refined_" + std::to_string(target) + ".h5"),
                                      study, &nodes));
    if (study.uniform) {
      Scene uniform = scene;
      uniform.refine.reset();
      for (std::size_t a = 0; a < uniform.axes.size(); ++a) {
        std::vector<double>& v = uniform.axes[a].values;
        v = Linspace(v.front(), v.back(), nodes[a].values.size());
      }
      rows.push_back(GenerateAndMeasure(uniform, kUniform, target,
                                        study.out / ("uniform_" + std::to_string(target) + ".h5"),
                                        study, &nodes));
    }
    WriteTablesReport(study.out, study, rows);  // after each target: nothing lost
  }
  if (study.midpoint_target > 0.0) {
    for (TableRow& row : MidpointRulePasses(scene, study)) rows.push_back(std::move(row));
    WriteTablesReport(study.out, study, rows);
  }
  return kExitOk;
}

}  // namespace

void AddCostStudies(CLI::App& study, int* exit_code) {
  auto* solver = study.add_subcommand(
      "solver", "Solver accuracy against time: the given cases at several element sizes");
  auto cases = std::make_shared<std::vector<std::string>>();
  auto sizes = std::make_shared<std::vector<double>>(std::vector<double>{1.0, 0.5, 0.25, 0.2, 0.1});
  auto solver_out = std::make_shared<std::string>("study-solver");
  solver->add_option("CASE", *cases, "Case files (wheel-rail or half-space)")
      ->required()
      ->check(CLI::ExistingFile);
  solver
      ->add_option("--sizes", *sizes,
                   "Element sizes dx = ds (dy), mm; the finest is the "
                   "reference")
      ->delimiter(',')
      ->check(GreaterThanZero())
      ->capture_default_str();
  AddOutOption(solver, solver_out.get(), "Output directory (solver.csv, .png, .md)");
  OnRun(solver, exit_code, "wrc study solver", [=]() {
    if (sizes->size() < 2) throw InputError("--sizes: give at least two element sizes");
    return StudySolver(*cases, *sizes, *solver_out);
  });
  auto* tables = study.add_subcommand(
      "tables",
      "Table accuracy against generation time and size: refined tables of a scene at several "
      "targets, the passes of the midpoint rule, uniform tables");
  auto options = std::make_shared<TablesStudy>();
  options->targets = {0.04, 0.02, 0.01};
  options->out = "study-tables";
  tables->add_option("SCENE", options->scene, "Scene file (any; its axes give the ranges)")
      ->required();
  AddOutOption(tables, &options->out, "Output directory (tables.csv, .png, .md, the tables)");
  tables
      ->add_option("--targets", options->targets,
                   "Refinement targets, fractions of the local wheel load")
      ->delimiter(',')
      ->capture_default_str();
  tables
      ->add_option("--midpoint-rule", options->midpoint_target,
                   "Also refine at this target until every sampled midpoint is within it "
                   "(quantile 1) and measure every pass")
      ->check(CLI::Range(1e-6, 1.0));
  tables->add_flag("--uniform", options->uniform,
                   "Also a uniform table with each refined table's node counts");
  tables->add_option("--samples", options->samples, "Exact solves per table")
      ->check(GreaterThanZero())
      ->capture_default_str();
  tables->add_option("--seed", options->seed, "Seed of the sample points")->capture_default_str();
  AddThreadsOption(tables, &options->threads, true, "Worker threads; 0: all cores");
  OnRun(tables, exit_code, "wrc study tables", [options]() { return StudyTables(*options); });
}

}  // namespace wrc::cli
