// `wrc verify TABLE.h5`: re-solves sampled points exactly with the scene stored in the table
// and reports how far the interpolated table is from the full solver, where the error is
// (--csv, an error map through the worst point with --map), and gates on a tolerance.

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tools/wrc/commands.h"
#include "tools/wrc/gnuplot.h"
#include "tools/wrc/output_text.h"
#include "tools/wrc/thread_option.h"
#include "tools/wrc/verify.h"
#include "wrc/core/errors.h"
#include "wrc/core/output_file.h"
#include "wrc/runtime.hpp"

namespace wrc::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct CommandOptions {
  VerifyOptions verify;
  bool as_json = false;
  double tolerance = -1.0;
  std::string csv;
  std::string map_axes;  ///< "AXIS1,AXIS2"
  std::string map_output;
  int map_size = 31;
  std::string png = "verify_map.png";
};

double Get(const json& j) { return j.is_number() ? j.get<double>() : NAN; }

void WriteCsv(const Verification& v, const std::string& path) {
  std::ostringstream csv;
  csv.precision(12);
  for (const std::string& axis : v.axis_names) csv << axis << ',';
  csv << "status,load,patch_change";
  for (const std::string& o : v.output_names) {
    csv << ',' << o << "_exact," << o << "_linear," << o << "_cubic";
  }
  csv << '\n';
  for (const VerifiedPoint& p : v.points) {
    for (const double x : p.point) csv << x << ',';
    csv << p.status << ',' << p.load << ',' << p.patch_change;
    for (std::size_t o = 0; o < v.output_names.size(); ++o) {
      const auto at = [&](const std::vector<double>& values) {
        return o < values.size() ? values[o] : NAN;
      };
      csv << ',' << at(p.exact) << ',' << at(p.linear) << ',' << at(p.cubic);
    }
    csv << '\n';
  }
  WriteFileAtomically(path, csv.str());
}

// The output the map shows by default: the force with the largest p95 error relative to the
// load (or the largest max_rel where the table has no forces).
std::string WorstOutput(const Verification& v) {
  std::string best;
  double worst = -1.0;
  for (const std::string& name : v.output_names) {
    const json& o = v.report["outputs"][name];
    const double e = IsForceOutput(name) ? Get(o["load"]["p95"]) : -1.0;
    if (e > worst) {
      worst = e;
      best = name;
    }
  }
  if (!best.empty()) return best;
  for (const std::string& name : v.output_names) {
    const double e = Get(v.report["outputs"][name]["max_rel"]);
    if (e > worst) {
      worst = e;
      best = name;
    }
  }
  return best;
}

int IndexOf(const std::vector<std::string>& names, const std::string& name, const char* what) {
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) {
    std::string all;
    for (const std::string& n : names) all += (all.empty() ? "" : ", ") + n;
    throw InputError(std::string("--map: the table has no ") + what + " \"" + name + "\" (it has " +
                     all + ")");
  }
  return static_cast<int>(it - names.begin());
}

// A map of the error of one output over two axes, through the sampled point where that output
// is worst: exact solves on a map_size² grid, the table's nodes drawn over it.
void WriteErrorMap(const Verification& v, const CommandOptions& opt) {
  const auto comma = opt.map_axes.find(',');
  if (comma == std::string::npos) throw InputError("--map takes two axis names: AXIS1,AXIS2");
  const int ax = IndexOf(v.axis_names, opt.map_axes.substr(0, comma), "axis");
  const int ay = IndexOf(v.axis_names, opt.map_axes.substr(comma + 1), "axis");
  if (ax == ay) throw InputError("--map needs two different axes");
  const std::string output = opt.map_output.empty() ? WorstOutput(v) : opt.map_output;
  const int o = IndexOf(v.output_names, output, "output");
  const json& worst = v.report["outputs"][output]["worst"];
  auto stored = LoadStoredScene(opt.verify.table);
  Table table(opt.verify.table);
  std::vector<double> through(v.axis_names.size());
  for (std::size_t a = 0; a < v.axis_names.size(); ++a) {
    const std::vector<double> nodes = table.axis_values(static_cast<int>(a));
    through[a] = worst.contains(v.axis_names[a]) ? worst[v.axis_names[a]].get<double>()
                                                 : 0.5 * (nodes.front() + nodes.back());
  }
  const std::vector<double> xs = table.axis_values(ax), ys = table.axis_values(ay);
  std::vector<std::vector<double>> points;
  const int n = std::max(2, opt.map_size);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      std::vector<double> p = through;
      p[ax] = xs.front() + (xs.back() - xs.front()) * i / (n - 1);
      p[ay] = ys.front() + (ys.back() - ys.front()) * j / (n - 1);
      points.push_back(p);
    }
  }
  std::vector<std::vector<double>> exact;
  std::vector<int> status;
  std::vector<double> seconds;
  std::vector<std::string> messages;
  SolveExactly(stored->scene, points, opt.verify.threads, &exact, &status, &seconds, &messages);
  const bool force = IsForceOutput(output);
  const int fz_axis = [&] {
    for (std::size_t a = 0; a < v.axis_names.size(); ++a) {
      if (v.axis_names[a] == "fz") return static_cast<int>(a);
    }
    return -1;
  }();
  const auto fz_out = std::find(v.output_names.begin(), v.output_names.end(), "fz");
  const fs::path png = opt.png;
  const fs::path data = fs::path(png).replace_extension(".dat");
  {
    OutputText out(data);
    out.precision(10);
    std::vector<double> values(v.output_names.size());
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (k > 0 && k % n == 0) out << '\n';
      double e = NAN;
      if (status[k] <= 1 && table.try_eval(points[k].data(), values.data()) >= 0) {
        e = values[o] - exact[k][o];
        if (force) {
          double load = fz_axis >= 0 ? points[k][fz_axis] : NAN;
          if (!(load > 0.0) && stored->scene.base.state.fz) load = *stored->scene.base.state.fz;
          if (!(load > 0.0) && fz_out != v.output_names.end()) {
            load = std::fabs(exact[k][fz_out - v.output_names.begin()]);
          }
          e = 100.0 * e / load;
        }
      }
      out << points[k][ax] << ' ' << points[k][ay] << ' ' << (std::isfinite(e) ? e : NAN) << '\n';
    }
    out.Commit();
  }
  const fs::path nodes = fs::path(png).replace_extension(".nodes");
  {
    OutputText out(nodes);
    out.precision(12);
    for (const double x : xs)
      out << x << ' ' << ys.front() << ' ' << 0 << ' ' << ys.back() - ys.front() << '\n';
    for (const double y : ys)
      out << xs.front() << ' ' << y << ' ' << xs.back() - xs.front() << ' ' << 0 << '\n';
    out.Commit();
  }
  std::ostringstream through_text;
  for (std::size_t a = 0; a < v.axis_names.size(); ++a) {
    if (static_cast<int>(a) == ax || static_cast<int>(a) == ay) continue;
    through_text << (through_text.str().empty() ? "" : ", ") << v.axis_names[a] << " = "
                 << through[a];
  }
  const fs::path script = fs::path(png).replace_extension(".gp");
  {
    // Absolute names: gnuplot runs in the script's folder.
    std::ostringstream gp;
    gp << "set terminal pngcairo noenhanced size 1000,760 font ',10'\n"
       << "set output '" << fs::absolute(png).string() << "'\n"
       << "set title \"" << fs::path(opt.verify.table).filename().string() << ": error of "
       << output << " (table − solver" << (force ? ", % of the local wheel load" : "") << ")\\n"
       << (through_text.str().empty() ? "" : "through " + through_text.str() + "; ")
       << "lines: table nodes\"\n"
       << "set xlabel '" << v.axis_names[ax] << " (" << table.axis_unit(ax) << ")'\n"
       << "set ylabel '" << v.axis_names[ay] << " (" << table.axis_unit(ay) << ")'\n"
       << "set cblabel '" << output << " error" << (force ? " (% of load)" : "") << "'\n"
       << "set palette defined (-1 '#2166ac', 0 '#f7f7f7', 1 '#b2182b')\n"
       << "stats '" << fs::absolute(data).string() << "' using 3 nooutput\n"
       << "m = (abs(STATS_min) > abs(STATS_max) ? abs(STATS_min) : abs(STATS_max))\n"
       << "if (m <= 0) m = 1\n"
       << "set cbrange [-m:m]\nset xrange [" << xs.front() << ":" << xs.back() << "]\n"
       << "set yrange [" << ys.front() << ":" << ys.back() << "]\n"
       << "plot '" << fs::absolute(data).string() << "' using 1:2:3 with image notitle, '"
       << fs::absolute(nodes).string()
       << "' using 1:2:3:4 with vectors nohead lc rgb '#60000000' lw 0.5 notitle\n";
    if (!RunGnuplot(script.parent_path(), script.filename().string(), gp.str())) {
      throw InputError("gnuplot is not installed (Debian: gnuplot-nox): cannot draw " +
                       png.string());
    }
  }
  std::cerr << "wrc verify: wrote " << png.string() << " (" << output << " over "
            << v.axis_names[ax] << " and " << v.axis_names[ay] << ", " << n * n
            << " exact solves; data in " << data.string() << ")\n";
}

// A percentage in a column of `width`, or "-" where no sample gave one (no sample in cells
// where the patch count changes, say): a reader sees "none", not nan%.
std::string PercentColumn(double fraction, int width) {
  char text[40];
  if (std::isfinite(fraction)) {
    std::snprintf(text, sizeof text, "%*.3f%%", width - 1, 100 * fraction);
  } else {
    std::snprintf(text, sizeof text, "%*s", width, "-");
  }
  return text;
}

// An absolute error in a column of `width`, or "-" where no sample gave one.
std::string NumberColumn(double value, int width) {
  char text[40];
  if (std::isfinite(value)) {
    std::snprintf(text, sizeof text, "%*.4g", width, value);
  } else {
    std::snprintf(text, sizeof text, "%*s", width, "-");
  }
  return text;
}

void PrintText(const Verification& v, const CommandOptions& opt) {
  const json& r = v.report;
  const json& counts = r["exact_status"];
  std::printf(
      "%s: %d samples (%s, seed %llu), exact solves: %d ok, %d no contact, %d not converged, "
      "%d errors; %.3f s per solve; %d samples in cells where the patch count changes\n",
      opt.verify.table.c_str(), opt.verify.samples, r["sampler"].get<std::string>().c_str(),
      static_cast<unsigned long long>(opt.verify.seed), counts["ok"].get<int>(),
      counts["no_contact"].get<int>(), counts["not_converged"].get<int>(),
      counts["error"].get<int>(), r["solve_time_s"]["mean"].get<double>(),
      r["points_in_patch_change_cells"].get<int>());
  if (r.contains("first_error")) {
    std::printf("first failed exact solve: %s\n", r["first_error"].get<std::string>().c_str());
  }
  for (const char* key : {"linear", "cubic"}) {
    const json& m = r["interpolation"][key];
    std::printf(
        "\n%s interpolation (%.0f ns per lookup):\n  %-14s %11s %11s %11s %9s | %8s %8s %8s | "
        "%9s %9s\n",
        key, 1e9 * m["lookup_time_s"]["mean"].get<double>(), "output", "max_abs", "rms", "p95_abs",
        "max_rel", "p95/load", "rms/load", "max/load", "max same", "max chg");
    for (auto it = m["outputs"].begin(); it != m["outputs"].end(); ++it) {
      const json& o = *it;
      std::printf("  %-14s %11.4g %11.4g %11.4g %9.3g", it.key().c_str(), Get(o["max_abs"]),
                  Get(o["rms"]), Get(o["p95_abs"]), Get(o["max_rel"]));
      if (o.contains("load")) {
        std::printf(" | %s %s %s", PercentColumn(Get(o["load"]["p95"]), 8).c_str(),
                    PercentColumn(Get(o["load"]["rms"]), 8).c_str(),
                    PercentColumn(Get(o["load"]["max"]), 8).c_str());
        std::printf(" | %s %s",
                    PercentColumn(Get(o["cells"]["same_patches"]["max_load"]), 9).c_str(),
                    PercentColumn(Get(o["cells"]["patch_change"]["max_load"]), 9).c_str());
      } else {
        std::printf(" | %8s %8s %8s | %s %s", "", "", "",
                    NumberColumn(Get(o["cells"]["same_patches"]["max_abs"]), 9).c_str(),
                    NumberColumn(Get(o["cells"]["patch_change"]["max_abs"]), 9).c_str());
      }
      std::printf("\n");
    }
  }
  std::printf(
      "\n/load: error as a fraction of the local wheel load; same / chg: the largest error in "
      "cells where the patch count is the same at every corner / changes (-: no sample there)\n");
}

// The outputs that fail the gate, each with why: max_rel above the tolerance, or no sample
// point that could be compared (a gate met by nothing would be a lie).
std::vector<std::string> GateFailures(const Verification& v, double tolerance) {
  std::vector<std::string> failures;
  if (tolerance < 0.0) return failures;
  for (const std::string& name : v.output_names) {
    const json& o = v.report["outputs"][name];
    char text[160];
    if (o["compared"].get<int>() == 0) {
      std::snprintf(text, sizeof text, "%s (no point compared)", name.c_str());
    } else if (Get(o["max_rel"]) > tolerance) {
      std::snprintf(text, sizeof text, "%s (max_rel %.3g)", name.c_str(), Get(o["max_rel"]));
    } else {
      continue;
    }
    failures.push_back(text);
  }
  return failures;
}

// None of the exact solves gave a result: nothing was verified, whatever the table holds.
void RequireSomeExactSolve(const Verification& v) {
  const json& counts = v.report["exact_status"];
  if (counts["ok"].get<int>() + counts["no_contact"].get<int>() > 0) return;
  std::string why = v.report.contains("first_error")
                        ? " (the first: " + v.report["first_error"].get<std::string>() + ")"
                        : std::string(" (none converged)");
  throw InputError("none of the " + std::to_string(v.points.size()) + " exact solves succeeded" +
                   why + "; the table could not be verified");
}

// Every file this run writes, checked before the (long) exact solves: none may be the table.
void RequireOutputsApartFromTheTable(const CommandOptions& opt) {
  const fs::path table = opt.verify.table;
  if (!opt.csv.empty()) RequireNotAnInput(opt.csv, {table});
  if (opt.map_axes.empty()) return;
  for (const char* extension : {"", ".dat", ".nodes", ".gp"}) {
    fs::path file = opt.png;
    if (*extension != '\0') file.replace_extension(extension);
    RequireNotAnInput(file, {table});
  }
}

int RunVerify(const CommandOptions& opt) {
  RequireOutputsApartFromTheTable(opt);
  const Verification v = VerifyTable(opt.verify);
  if (!opt.csv.empty()) WriteCsv(v, opt.csv);
  if (!opt.map_axes.empty()) WriteErrorMap(v, opt);
  const std::vector<std::string> failures = GateFailures(v, opt.tolerance);
  if (opt.as_json) {
    std::cout << v.report.dump(1) << '\n';
  } else {
    PrintText(v, opt);
    if (opt.tolerance >= 0.0) {
      std::string by;
      for (const std::string& f : failures) by += (by.empty() ? " by " : ", ") + f;
      std::printf("\ntolerance %.3g on max_rel: %s%s\n", opt.tolerance,
                  failures.empty() ? "met" : "EXCEEDED", by.c_str());
    }
  }
  std::cout.flush();
  if (!std::cout || std::fflush(stdout) != 0) {
    throw InputError("cannot write the report to standard output");
  }
  RequireSomeExactSolve(v);
  return failures.empty() ? kExitOk : kExitGateFailed;
}

}  // namespace

void AddVerifyCommand(CLI::App& app, int* exit_code) {
  auto* cmd = app.add_subcommand("verify", "Re-solve sampled points and compare with a table");
  auto opt = std::make_shared<CommandOptions>();
  cmd->add_option("TABLE", opt->verify.table, "Table (HDF5) written by wrc generate")->required();
  // Each sample is a full solve (about 20 ms) and a row of the report held in memory: a million
  // is hours of solving, already far past what an error distribution needs.
  cmd->add_option("--samples", opt->verify.samples, "Number of sample points (at most 1000000)")
      ->check(NumberCheck([](double v) { return v > 0.0 && v <= 1e6; }, "1 to 1000000", "1-1e6"))
      ->capture_default_str();
  cmd->add_option("--seed", opt->verify.seed, "Random seed (fixed: results are repeatable)")
      ->check(CLI::Validator(
          [](std::string& text) {
            // CLI11 would wrap -1 and saturate 2^64 to 2^64 - 1: another seed than written.
            errno = 0;
            const bool digits =
                !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
            std::strtoull(text.c_str(), nullptr, 10);
            return digits && errno != ERANGE ? std::string()
                                             : "must be a whole number 0 … 2^64 - 1, is " + text;
          },
          "SEED"))
      ->capture_default_str();
  cmd->add_option("--sampler", opt->verify.sampler, "uniform or lhs (Latin hypercube)")
      ->check(CLI::IsMember({"uniform", "lhs"}))
      ->capture_default_str();
  cmd->add_flag("--near-jumps", opt->verify.near_jumps,
                "Sample the cells where neighbouring table values jump (two-point contact)");
  cmd->add_flag("--json", opt->as_json, "Print the report as JSON");
  cmd->add_option("--tolerance", opt->tolerance,
                  "Fail (exit 1) when any output's max_rel exceeds this")
      ->check(CLI::Validator(
          [](std::string& text) {
            const double value = std::strtod(text.c_str(), nullptr);
            return std::isfinite(value) && value >= 0.0
                       ? std::string()
                       : "must be a finite number >= 0, is " + text;
          },
          "NUMBER >= 0"));
  cmd->add_option("--threads", opt->verify.threads, "Worker threads (default: all cores)")
      ->check(ThreadCount(true));
  cmd->add_option("--csv", opt->csv,
                  "Write every sampled point to this CSV file (point, status, load, exact and "
                  "table values of each output)");
  cmd->add_option("--map", opt->map_axes,
                  "Draw the error over two axes, AXIS1,AXIS2, through the worst sampled point");
  cmd->add_option("--map-output", opt->map_output,
                  "Output drawn by --map (default: the force with the largest p95 error)");
  cmd->add_option("--map-size", opt->map_size, "Exact solves per side of the --map grid")
      ->check(CLI::Range(2, 400))
      ->capture_default_str();
  cmd->add_option("--png", opt->png, "Where --map writes its picture")->capture_default_str();
  cmd->callback([=]() {
    try {
      *exit_code = RunVerify(*opt);
    } catch (...) {
      *exit_code = ReportFailure("wrc verify");
    }
  });
}

}  // namespace wrc::cli
