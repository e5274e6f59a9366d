// `wrc study solver` and `wrc study tables` (SPEC §7, issue 8): what accuracy costs in time.

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
#include "wrc/case.h"
#include "wrc/wheelrail.h"

namespace wrc::cli {
namespace {

namespace fs = std::filesystem;

double Seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int Shell(const std::string& command) { return std::system(command.c_str()); }

std::string ReadAll(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

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

// Table accuracy against cost: tables/demo.toml at its own density and with every step
// halved, each generated and verified.
int StudyTables(const fs::path& out, const fs::path& source_dir, const std::string& exe) {
  fs::create_directories(out);
  const std::string base = ReadAll(source_dir / "tables" / "demo.toml");
  std::ofstream summary(out / "tables.md");
  std::ofstream csv(out / "tables.csv");
  csv << "density,points,generate_s,file_bytes,lookup_ns,fy_max_rel,fy_rms,z_rms_um\n";
  summary << "| table | points | generate (s) | file (kB) | lookup (ns) | fy max_rel | fy rms (N) |"
          << " z rms (µm) |\n|---|---|---|---|---|---|---|---|\n";
  for (int level = 0; level < 3; ++level) {
    // Halve every axis step per level by inserting midpoints into explicit lists or halving
    // 'step' values of ranges (the demo scene uses ranges with steps and lists).
    std::string text = base;
    std::string::size_type pos = 0;
    while ((pos = text.find("step = ", pos)) != std::string::npos) {
      pos += 7;
      const std::string::size_type end = text.find_first_of(" }", pos);
      const double step = std::stod(text.substr(pos, end - pos)) / std::pow(2.0, level);
      text.replace(pos, end - pos, std::to_string(step));
    }
    // Explicit axis lists after `axes = [...]`: insert midpoints level times.
    {
      std::istringstream lines(text);
      std::ostringstream rebuilt;
      std::string line;
      bool in_table = false;
      std::size_t points = 1;
      while (std::getline(lines, line)) {
        if (line.rfind("[table]", 0) == 0) in_table = true;
        const auto open = line.find("= ["), close = line.find(']');
        if (in_table && line.rfind("axes", 0) != 0 && line.rfind("outputs", 0) != 0 &&
            open != std::string::npos && close != std::string::npos) {
          std::vector<double> v;
          std::istringstream items(line.substr(open + 3, close - open - 3));
          std::string item;
          while (std::getline(items, item, ',')) v.push_back(std::stod(item));
          for (int l = 0; l < level; ++l) {
            std::vector<double> w;
            for (std::size_t k = 0; k < v.size(); ++k) {
              if (k > 0) w.push_back(0.5 * (v[k - 1] + v[k]));
              w.push_back(v[k]);
            }
            v = w;
          }
          std::ostringstream list;
          list.precision(12);
          for (std::size_t k = 0; k < v.size(); ++k) list << (k ? ", " : "") << v[k];
          line = line.substr(0, open + 3) + list.str() + "]";
        }
        rebuilt << line << '\n';
      }
      (void)points;
      text = rebuilt.str();
    }
    const fs::path scene = out / ("tables_" + std::to_string(level) + ".toml");
    const fs::path table = out / ("tables_" + std::to_string(level) + ".h5");
    // Profile paths of the demo are relative to tables/.
    std::string fixed = text;
    const std::string key = "profiles/";
    for (std::string::size_type p = 0; (p = fixed.find("\"" + key, p)) != std::string::npos;) {
      fixed.insert(p + 1, fs::absolute(source_dir / "tables").string() + "/");
      p += key.size() + 2;
    }
    std::ofstream(scene) << fixed;
    fs::remove(table);
    fs::remove(fs::path(table.string() + ".journal"));
    const auto t0 = std::chrono::steady_clock::now();
    if (Shell("'" + exe + "' generate '" + scene.string() + "' -o '" + table.string() +
              "' --quiet") != 0) {
      std::cerr << "tables study: generate failed for level " << level << '\n';
      return kExitGateFailed;
    }
    const double generate = Seconds(t0);
    const fs::path report = out / ("verify_" + std::to_string(level) + ".json");
    Shell("'" + exe + "' verify '" + table.string() + "' --samples 100 --seed 3 --json > '" +
          report.string() + "'");
    const auto j = nlohmann::json::parse(ReadAll(report));
    const double lookup = 1e9 * j["lookup_time_s"]["mean"].get<double>();
    const nlohmann::json info = nlohmann::json::parse([&] {
      const fs::path info_file = out / ("info_" + std::to_string(level) + ".json");
      Shell("'" + exe + "' info '" + table.string() + "' --json > '" + info_file.string() + "'");
      return ReadAll(info_file);
    }());
    std::size_t points = 1;
    for (const auto& axis : info["axes"]) points *= axis["size"].get<std::size_t>();
    const auto& fy = j["outputs"]["fy"];
    const double z_rms =
        j["outputs"].contains("z") ? 1e3 * j["outputs"]["z"]["rms"].get<double>() : NAN;
    const auto bytes = fs::file_size(table);
    char line[256];
    std::snprintf(line, sizeof line,
                  "| demo, steps / %d | %zu | %.1f | %.0f | %.0f | %.3g | %.3g | %.3g |\n",
                  1 << level, points, generate, bytes / 1024.0, lookup, fy["max_rel"].get<double>(),
                  fy["rms"].get<double>(), z_rms);
    summary << line;
    csv << level << ',' << points << ',' << generate << ',' << bytes << ',' << lookup << ','
        << fy["max_rel"].get<double>() << ',' << fy["rms"].get<double>() << ',' << z_rms << '\n';
    std::cerr << "tables study: level " << level << " done\n";
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
  auto* tables = study.add_subcommand("tables", "Table accuracy against cost over densities");
  tables->add_option("--out", *out, "Output directory");
  tables->add_option("--source", *source, "The wrc checkout (for tables/demo.toml)");
  auto exe = std::make_shared<std::string>("build/wrc");
  tables->add_option("--wrc", *exe, "The wrc binary used for generate/verify");
  tables->callback([=]() {
    try {
      *exit_code = StudyTables(*out, *source, fs::absolute(*exe).string());
    } catch (const std::exception& e) {
      std::cerr << "wrc study tables: error: " << e.what() << '\n';
      *exit_code = kExitBadInput;
    }
  });
}

}  // namespace wrc::cli
