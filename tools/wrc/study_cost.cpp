// `wrc study solver` and `wrc study tables`: what accuracy costs in time.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tools/wrc/commands.h"
#include "tools/wrc/verify.h"
#include "wrc/case.h"
#include "wrc/errors.h"
#include "wrc/generator.h"
#include "wrc/scene.h"
#include "wrc/wheelrail.h"

namespace wrc::cli {
namespace {

namespace fs = std::filesystem;

double Seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int Shell(const std::string& command) { return std::system(command.c_str()); }

// Solver accuracy against cost: the Manchester states of tables/mbench.toml's y range (curved,
// fz = 10 kN) at several element sizes; errors against the finest grid.
int StudySolver(const fs::path& out, const fs::path& source_dir, const std::string& exe) {
  fs::create_directories(out);
  const std::vector<double> sizes = {1.0, 0.5, 0.25, 0.2, 0.1};
  const std::vector<double> ys = {0.0, 2.0, 4.0, 6.0, 8.0};
  const fs::path profiles = fs::absolute(source_dir / "tables" / "profiles");
  struct Row {
    double size, y, seconds, fx, fy, fz, z;
  };
  std::vector<Row> rows;
  for (double y : ys) {
    for (double d : sizes) {
      std::ostringstream t;
      t.precision(12);
      t << "[problem]\ntype = \"wheel-rail\"\n[rail]\nprofile = \""
        << (profiles / "MBench_UIC60_v3.prr").string() << "\"\n[wheel]\nprofile = \""
        << (profiles / "MBench_S1002_v3.prw").string() << "\"\n[grid]\ndx = " << d << "\nds = " << d
        << "\n[method]\nreference = \"curved\"\n[state]\ny = " << y
        << "\nfz = 10000.0\nyaw = 0.0\nspin = 0.0\n";
      const Case c = ParseCase(t.str(), out, "solver_study");
      // Best of two: the first run also warms caches (influence tables are per element size).
      double best = 1e300;
      WheelRailResult r;
      for (int rep = 0; rep < 2; ++rep) {
        const auto t0 = std::chrono::steady_clock::now();
        r = SolveWheelRail(c);
        best = std::min(best, Seconds(t0));
      }
      rows.push_back({d, y, best, r.force_T(0), r.force_T(1), r.force_T(2), r.z});
      std::cerr << "solver study: y " << y << " dx " << d << ": " << best << " s\n";
    }
  }
  std::ofstream csv(out / "solver.csv");
  csv << "element_mm,y_mm,seconds,fx,fy,fz,z,err_fx_rel_load,err_fy_rel_load,err_z_um\n";
  csv.precision(8);
  std::ofstream summary(out / "solver.md");
  summary
      << "| element size (mm) | mean s per solve | max |Δfx|/fz | max |Δfy|/fz | max |Δz| (µm) |\n"
      << "|---|---|---|---|---|\n";
  for (double d : sizes) {
    double time = 0.0, efx = 0.0, efy = 0.0, ez = 0.0;
    for (double y : ys) {
      const Row* row = nullptr;
      const Row* fine = nullptr;
      for (const Row& r : rows) {
        if (r.y == y && r.size == d) row = &r;
        if (r.y == y && r.size == sizes.back()) fine = &r;
      }
      const double a = std::fabs(row->fx - fine->fx) / 1e4, b = std::fabs(row->fy - fine->fy) / 1e4;
      const double c = 1e3 * std::fabs(row->z - fine->z);
      csv << d << ',' << y << ',' << row->seconds << ',' << row->fx << ',' << row->fy << ','
          << row->fz << ',' << row->z << ',' << a << ',' << b << ',' << c << '\n';
      time += row->seconds / ys.size();
      efx = std::max(efx, a);
      efy = std::max(efy, b);
      ez = std::max(ez, c);
    }
    char line[200];
    std::snprintf(line, sizeof line, "| %.2f | %.3f | %.2e | %.2e | %.2f |\n", d, time, efx, efy,
                  ez);
    summary << line;
  }
  csv.close();
  std::ofstream gp(out / "solver.gp");
  gp << "set terminal pngcairo size 900,600 font ',10'\nset output 'solver.png'\n"
     << "set datafile separator ','\nset logscale xy\nset grid\n"
     << "set xlabel 'time per solve, s'\nset ylabel 'error of fy against dx = 0.1 mm, fraction of "
        "fz'\n"
     << "set title 'Solver accuracy against cost: Manchester S1002/UIC60, curved, fz = 10 kN'\n"
     << "plot 'solver.csv' using 3:($9>0?$9:1/0):(sprintf('%.2g', $1)) with labels offset 1,0.5 "
        "notitle, "
     << "'' using 3:($9>0?$9:1/0) with points pt 7 title 'one case (label: element size, mm)'\n";
  gp.close();
  (void)exe;
  Shell("cd '" + out.string() + "' && gnuplot solver.gp");
  return kExitOk;
}

// ---- tables: accuracy against points, size and time -----------------------------------------

struct TableRow {
  std::string kind;  // "uniform" or "refined"
  double target = 0.0;
  std::size_t points = 0;
  double generate_s = 0.0;
  std::uintmax_t bytes = 0;
  // Per mode (0 linear, 1 cubic): the largest p95 / max of the force errors relative to the
  // local load, z's p95 (mm), the lookup time.
  double force_p95[2] = {}, force_max[2] = {}, force_rms[2] = {}, z_p95[2] = {}, lookup_ns[2] = {};
  std::string axes;
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

void Measure(const fs::path& table, int samples, std::uint64_t seed, int threads, TableRow* row) {
  VerifyOptions options;
  options.table = table.string();
  options.samples = samples;
  options.seed = seed;
  options.threads = threads;
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

GenerateSummary Generate(const Scene& scene, const fs::path& table, int threads) {
  fs::remove(table);
  std::error_code ignored;
  fs::remove(fs::path(table.string() + ".journal"), ignored);
  fs::remove_all(fs::path(table.string() + ".refine"), ignored);
  GenerateOptions options;
  options.output = table;
  options.threads = threads;
  options.progress = ProgressMode::kOff;
  options.handle_signals = true;
  const GenerateSummary summary = GenerateTable(scene, options);
  if (!summary.complete) throw InputError("generating " + table.string() + " was interrupted");
  return summary;
}

std::string AxesText(const std::vector<SceneAxis>& axes) {
  std::string text;
  for (const SceneAxis& a : axes) {
    text += (text.empty() ? "" : " × ") + a.name + " " + std::to_string(a.values.size());
  }
  return text;
}

void WriteTablesReport(const fs::path& out, const fs::path& scene_path,
                       const std::vector<TableRow>& rows, int samples, std::uint64_t seed) {
  std::ofstream csv(out / "tables.csv");
  csv << "kind,target,points,generate_s,file_bytes,force_p95_linear,force_rms_linear,"
         "force_max_linear,z_p95_linear_mm,lookup_ns_linear,force_p95_cubic,force_rms_cubic,"
         "force_max_cubic,z_p95_cubic_mm,lookup_ns_cubic,axes\n";
  csv.precision(6);
  std::ofstream md(out / "tables.md");
  md << "Tables of `" << scene_path.filename().string() << "`, " << samples
     << " uniform random samples (seed " << seed
     << ") re-solved exactly. Force errors: the largest over the force outputs, as a fraction "
        "of the local wheel load.\n\n"
     << "| table | points | generate (s) | file (MB) | p95 lin | rms lin | max lin | p95 cub | "
        "rms cub | z p95 lin (µm) | lookup lin / cub (ns) |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const TableRow& r : rows) {
    csv << r.kind << ',' << r.target << ',' << r.points << ',' << r.generate_s << ',' << r.bytes;
    for (int m = 0; m < 2; ++m) {
      csv << ',' << r.force_p95[m] << ',' << r.force_rms[m] << ',' << r.force_max[m] << ','
          << r.z_p95[m] << ',' << r.lookup_ns[m];
    }
    csv << ",\"" << r.axes << "\"\n";
    char line[400];
    std::snprintf(line, sizeof line,
                  "| %s%s | %zu | %.0f | %.1f | %.2f %% | %.2f %% | %.1f %% | %.2f %% | %.2f %% | "
                  "%.1f | %.0f / %.0f |\n",
                  r.kind.c_str(),
                  r.kind == "refined" ? (" " + std::to_string(r.target)).substr(0, 7).c_str() : "",
                  r.points, r.generate_s, r.bytes / 1e6, 100 * r.force_p95[0], 100 * r.force_rms[0],
                  100 * r.force_max[0], 100 * r.force_p95[1], 100 * r.force_rms[1],
                  1e3 * r.z_p95[0], r.lookup_ns[0], r.lookup_ns[1]);
    md << line;
  }
  csv.close();
  // One data file per kind (points, p95 multilinear, p95 cubic in %), so that lines connect.
  for (const char* kind : {"refined", "uniform"}) {
    std::ofstream dat(out / (std::string("tables_") + kind + ".dat"));
    dat << "# points p95_linear_percent p95_cubic_percent\n";
    for (const TableRow& r : rows) {
      if (r.kind == kind) {
        dat << r.points << ' ' << 100 * r.force_p95[0] << ' ' << 100 * r.force_p95[1] << '\n';
      }
    }
  }
  std::ofstream gp(out / "tables.gp");
  gp << "set terminal pngcairo noenhanced size 1000,650 font ',10'\nset output 'tables.png'\n"
     << "set logscale xy\nset grid\nset key top right\nset offsets graph 0.1, graph 0.1, 0, 0\n"
     << "set xlabel 'table points'\nset ylabel 'p95 force error, % of the local wheel load'\n"
     << "set yrange [0.1:*]\n"
     << "set title \"" << scene_path.filename().string()
     << ": interpolation error against table size (" << samples << " exact solves)\"\n"
     << "plot 'tables_uniform.dat' using 1:2 with linespoints pt 5 lc rgb '#b2182b' title "
        "'uniform, multilinear', '' using 1:3 with linespoints pt 4 lc rgb '#ef8a62' title "
        "'uniform, cubic', 'tables_refined.dat' using 1:2 with linespoints pt 7 lc rgb '#2166ac' "
        "title 'refined, multilinear', '' using 1:3 with linespoints pt 6 lc rgb '#67a9cf' title "
        "'refined, cubic', 1 with lines dt 2 lc rgb '#404040' title '1 % of the load'\n";
  gp.close();
  if (Shell("cd '" + out.string() + "' && gnuplot tables.gp") != 0) {
    std::cerr << "wrc study tables: gnuplot failed (is gnuplot installed?)\n";
  }
}

// One table of the study: generated, timed and verified; *axes receives its nodes.
TableRow GenerateAndMeasure(const Scene& scene, const std::string& kind, double target,
                            const fs::path& path, int samples, std::uint64_t seed, int threads,
                            std::vector<SceneAxis>* axes) {
  const auto t0 = std::chrono::steady_clock::now();
  const GenerateSummary summary = Generate(scene, path, threads);
  TableRow row;
  row.kind = kind;
  row.target = target;
  row.points = summary.points;
  row.generate_s = Seconds(t0);
  row.axes = AxesText(summary.axes);
  *axes = summary.axes;
  Measure(path, samples, seed, threads, &row);
  std::cerr << "tables study: " << kind << " (target " << target << "): " << row.points
            << " points (" << row.axes << "), p95 " << 100 * row.force_p95[0] << " % of the load\n";
  return row;
}

// Refined tables at several targets and, for each, a uniform table with the same node count
// per axis over the same ranges; all verified at the same random points.
int StudyTables(const fs::path& scene_path, const fs::path& out, const std::vector<double>& targets,
                int samples, std::uint64_t seed, int threads) {
  const Scene scene = LoadScene(scene_path);
  fs::create_directories(out);
  std::vector<TableRow> rows;
  for (const double target : targets) {
    Scene refined = scene;
    if (!refined.refine) refined.refine = RefineSettings{};
    refined.refine->load_fraction = target;
    std::vector<SceneAxis> nodes;
    rows.push_back(GenerateAndMeasure(refined, "refined", target,
                                      out / ("refined_" + std::to_string(target) + ".h5"), samples,
                                      seed, threads, &nodes));
    Scene uniform = scene;
    uniform.refine.reset();
    for (std::size_t a = 0; a < uniform.axes.size(); ++a) {
      std::vector<double>& v = uniform.axes[a].values;
      v = Linspace(v.front(), v.back(), nodes[a].values.size());
    }
    rows.push_back(GenerateAndMeasure(uniform, "uniform", target,
                                      out / ("uniform_" + std::to_string(target) + ".h5"), samples,
                                      seed, threads, &nodes));
    WriteTablesReport(out, scene_path, rows, samples, seed);  // after each pair: nothing lost
  }
  return kExitOk;
}

}  // namespace

void AddCostStudies(CLI::App& study, int* exit_code) {
  auto out = std::make_shared<std::string>("docs/accuracy-cost");
  auto source = std::make_shared<std::string>(".");
  auto* solver = study.add_subcommand("solver", "Solver accuracy against time over element sizes");
  solver->add_option("--out", *out, "Output directory");
  solver->add_option("--source", *source, "The wrc checkout (for tables/profiles)");
  solver->callback([=]() {
    try {
      *exit_code = StudySolver(*out, *source, "");
    } catch (const std::exception& e) {
      std::cerr << "wrc study solver: error: " << e.what() << '\n';
      *exit_code = kExitBadInput;
    }
  });
  auto* tables = study.add_subcommand(
      "tables", "Table accuracy against size and time: refined and uniform tables of a scene");
  auto scene = std::make_shared<std::string>();
  auto targets = std::make_shared<std::vector<double>>(std::vector<double>{0.04, 0.02, 0.01});
  auto samples = std::make_shared<int>(300);
  auto seed = std::make_shared<std::uint64_t>(1);
  auto threads = std::make_shared<int>(0);
  auto tables_out = std::make_shared<std::string>("study-tables");
  tables->add_option("SCENE", *scene, "Scene file (any; its axes give the ranges)")->required();
  tables->add_option("--out", *tables_out, "Output directory")->capture_default_str();
  tables->add_option("--targets", *targets, "Refinement targets, fractions of the local wheel load")
      ->delimiter(',')
      ->capture_default_str();
  tables->add_option("--samples", *samples, "Exact solves per table")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  tables->add_option("--seed", *seed, "Seed of the sample points")->capture_default_str();
  tables->add_option("--threads", *threads, "Worker threads (default: all cores)");
  tables->callback([=]() {
    try {
      *exit_code = StudyTables(*scene, *tables_out, *targets, *samples, *seed, *threads);
    } catch (const std::exception& e) {
      std::cerr << "wrc study tables: error: " << e.what() << '\n';
      *exit_code = kExitBadInput;
    }
  });
}

}  // namespace wrc::cli
