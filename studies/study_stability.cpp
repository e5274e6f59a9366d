// `wrc study stability`: the hard cases swept in fine steps with the planar and the
// curved method, with the properties that must hold checked and reported (CSV, gnuplot PNGs
// and a Markdown summary).

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "studies/study_commands.h"
#include "studies/study_common.h"
#include "tools/wrc/commands.h"
#include "tools/wrc/gnuplot.h"
#include "tools/wrc/output_text.h"
#include "tools/wrc/thread_option.h"
#include "wrc/core/case.h"
#include "wrc/core/errors.h"
#include "wrc/core/wheelrail.h"

namespace wrc::cli {
namespace {

namespace fs = std::filesystem;

// A number as a person writes it (0.25, 1e+05), for the summary.
std::string FormatSize(double v) {
  std::ostringstream t;
  t << v;
  return t.str();
}

struct Sweep {
  std::string name;       // file stem
  std::string title;      // plot title
  std::string parameter;  // axis label, with unit
  std::vector<double> values;
  bool log_axis = false;
  bool check_continuity = false;  // also solve at half the step and compare jumps
};

struct Sample {
  double parameter = 0.0;
  std::string status;
  double fx = NAN, fy = NAN, fz = NAN, z = NAN, contact_y = NAN;
  int n_patches = 0, normal_iterations = 0, tangential_iterations = 0, fz_iterations = 0;
  double seconds = 0.0;
  std::string message;
};

// Manchester benchmark case text (S1002 on UIC60, right wheel), as the reference cases.
std::string Manchester(const fs::path& profiles, const std::string& method, double dx, double y,
                       double yaw, double spin, double fz, double mu) {
  std::ostringstream t;
  t.precision(12);
  t << "[problem]\ntype = \"wheel-rail\"\n[rail]\nprofile = \""
    << (profiles / "MBench_UIC60_v3.prr").string() << "\"\n[wheel]\nprofile = \""
    << (profiles / "MBench_S1002_v3.prw").string() << "\"\n"
    << "[track]\ngauge_height = 14.0\ngauge_width = 1435.0\ncant = 0.025\n"
    << "[wheelset]\nside = \"right\"\nflange_back_distance = 1360.0\n"
    << "flange_back_position = -70.0\nnominal_radius = 460.0\n"
    << "[friction]\nmu = " << mu << "\n[grid]\ndx = " << dx << "\nds = " << dx << "\n"
    << method << "[state]\ny = " << y << "\nfz = " << fz << "\nroll = 0.0\nyaw = " << yaw
    << "\nvelocity = 2000.0\nspin = " << spin << "\n";
  return t.str();
}

// The paper's §4.1 case, as reference/cases/heavy_haul.
std::string HeavyHaul(const fs::path& profiles, const std::string& method, double z, double fz,
                      double omega) {
  std::ostringstream t;
  t.precision(12);
  t << "[problem]\ntype = \"wheel-rail\"\n[rail]\nprofile = \""
    << (profiles / "site_b_hr.prr").string() << "\"\n[wheel]\nprofile = \""
    << (profiles / "worn_high_mileage.prw").string() << "\"\n"
    << "[track]\ngauge_height = 15.875\ngauge_width = 1435.1\ncant = 0.0\n"
    << "[wheelset]\nside = \"right\"\nflange_back_distance = 1347.4\n"
    << "flange_back_position = 0.0\nnominal_radius = 444.0\n"
    << "[friction]\nalpha_deg = [-30.0, -20.0]\nmu = [0.20, 0.35]\n[grid]\ndx = 0.4\nds = 0.4\n"
    << method << "[state]\ny = 14.85\n"
    << (fz > 0.0 ? "fz = " + std::to_string(fz) : "z = " + std::to_string(z))
    << "\nroll = -0.0013\nyaw = 0.005\nvelocity = 15000.0\nomega = " << omega << "\n";
  return t.str();
}

std::string Groove(const fs::path& profiles, const std::string& method, double fz) {
  std::ostringstream t;
  t.precision(12);
  t << "[problem]\ntype = \"wheel-rail\"\n[rail]\nprofile = \""
    << (profiles / "groove_r1002.prr").string() << "\"\n[wheel]\nprofile = \""
    << (profiles / "circ_r10.prw").string() << "\"\n"
    << "[track]\ngauge_height = -1.0\nrail_y = 0.0\nrail_z = 0.0\ncant = 0.0\n"
    << "[wheelset]\nflange_back_distance = 0.0\nflange_back_position = 0.0\n"
    << "nominal_radius = 420.0\n[material]\nshear_modulus = 80000.0\npoisson = 0.28\n"
    << "[friction]\nmu = 0.3\n[grid]\ndx = 0.2\nds = 0.25\n"
    << method << "[state]\ny = 0.0\nfz = " << fz
    << "\nroll = 0.0\nyaw = 0.0\nvelocity = 420.0\nomega = -1.0\n";
  return t.str();
}

std::vector<double> Range(double from, double to, double step) {
  std::vector<double> v;
  const int n = static_cast<int>(std::lround((to - from) / step));
  for (int k = 0; k <= n; ++k) v.push_back(from + k * step);
  return v;
}

std::vector<double> LogRange(double from, double to, int count) {
  std::vector<double> v;
  for (int k = 0; k < count; ++k) {
    v.push_back(from * std::pow(to / from, static_cast<double>(k) / (count - 1)));
  }
  return v;
}

const std::map<std::string, std::string>& Methods() {
  static const std::map<std::string, std::string> m = {
      {"curved", "[method]\nreference = \"curved\"\ncombine_distance = 6.0\n"},
      {"planar",
       "[method]\nreference = \"planar\"\nposition = \"weighted\"\n"
       "angle = \"weighted\"\nweights = \"quadratic\"\ncombine_distance = 6.0\n"},
      {"planar-icp",
       "[method]\nreference = \"planar\"\nposition = \"initial\"\n"
       "angle = \"sampled\"\ncombine_distance = 6.0\n"}};
  return m;
}

std::string HeavyHaulMethod(const std::string& method) {
  std::string m = Methods().at(method);
  const std::string key = "combine_distance = 6.0";
  return m.replace(m.find(key), key.size(), "combine_distance = 30.0");
}

// How a job builds its case: from text (the built-in suite) or by changing a loaded case.
using CaseMaker = std::function<Case()>;

Sample SolveOne(const CaseMaker& make_case, double parameter) {
  Sample s;
  s.parameter = parameter;
  const auto t0 = std::chrono::steady_clock::now();
  RecordSolveError(
      [&]() {
        const Case c = make_case();
        const WheelRailResult r = SolveWheelRail(c);
        s.status = ToString(r.status);
        s.message = r.message;
        s.fx = r.force_T(0);
        s.fy = r.force_T(1);
        s.fz = r.force_T(2);
        s.z = r.z;
        s.contact_y = r.has_force_location ? r.contact_y : NAN;
        s.n_patches = static_cast<int>(r.patches.size());
        s.fz_iterations = r.fz_iterations;
        for (const PatchResult& p : r.patches) {
          s.normal_iterations = std::max(s.normal_iterations, p.normal_iterations);
          s.tangential_iterations = std::max(s.tangential_iterations, p.tangential_iterations);
        }
      },
      &s.status, &s.message);
  s.seconds = SecondsSince(t0);
  return s;
}

using Job = std::pair<CaseMaker, double>;

std::vector<Sample> RunAll(const std::vector<Job>& jobs, int threads) {
  std::vector<Sample> out(jobs.size());
  RunParallel(
      jobs.size(), threads,
      [&](std::size_t k) { out[k] = SolveOne(jobs[k].first, jobs[k].second); },
      "wrc study stability");
  return out;
}

// Largest deviation of a step's change from the mean of its neighbours' changes: a smooth
// curve gives O(h²) (×1/4 when the step halves), a kink O(h) (×1/2), a jump O(1) (×1).
double LargestJump(const std::vector<Sample>& s, double Sample::*field) {
  double worst = 0.0;
  for (std::size_t k = 1; k + 2 < s.size(); ++k) {
    const double d0 = s[k].*field - s[k - 1].*field, d1 = s[k + 1].*field - s[k].*field;
    const double d2 = s[k + 2].*field - s[k + 1].*field;
    if (std::isfinite(d0) && std::isfinite(d1) && std::isfinite(d2)) {
      worst = std::max(worst, std::fabs(d1 - 0.5 * (d0 + d2)));
    }
  }
  return worst;
}

// The text with gnuplot's enhanced-text subscript marks escaped (file names hold underscores).
std::string LiteralUnderscores(const std::string& text) {
  std::string escaped;
  for (const char c : text) escaped += c == '_' ? std::string("\\_") : std::string(1, c);
  return escaped;
}

void Plot(const fs::path& dir, const Sweep& sweep, const std::vector<std::string>& methods) {
  std::ostringstream gp;
  gp << "set terminal pngcairo size 1000,700 font ',10'\nset output '" << sweep.name
     << ".png'\nset datafile separator ','\nset multiplot layout 2,1 title '"
     << LiteralUnderscores(sweep.title) << "'\nset grid\nset key outside right\n"
     << (sweep.log_axis ? "set logscale x\n" : "") << "set xlabel '" << sweep.parameter
     << "'\nset ylabel 'F_y / F_z (L/V), -'\nplot ";
  for (std::size_t m = 0; m < methods.size(); ++m) {
    gp << (m ? ", " : "") << "'" << sweep.name << ".csv' using ($1==" << m
       << " ? $3 : 1/0):($6/$7) with linespoints pt 7 ps 0.5 title '" << methods[m] << "'";
  }
  gp << "\nset ylabel 'contact location y_r of the resultant, mm'\nplot ";
  for (std::size_t m = 0; m < methods.size(); ++m) {
    gp << (m ? ", " : "") << "'" << sweep.name << ".csv' using ($1==" << m
       << " ? $3 : 1/0):9 with linespoints pt 7 ps 0.5 title '" << methods[m] << "'";
  }
  gp << "\nunset multiplot\n";
  DrawOrSay(dir, sweep.name + ".gp", gp.str(),
            "wrc study stability: gnuplot is not installed (Debian: gnuplot-nox): no " +
                sweep.name + ".png");
}

// What the summary's table holds; `how` says how the study was run.
void WriteSummaryHeader(std::ostream& summary, const std::string& how) {
  summary << "# Stability of the solver\n\n"
          << how << "\n\n"
          << "Methods: planar = weighted centre, weighted angle, quadratic weights;"
          << " planar-icp = initial contact point, sampled angle; curved = the curved reference"
          << " surface.\n\n"
          << "Jump ratio: the largest deviation of one step's change in fz (z sweeps) or fy"
          << " (other sweeps) from its neighbours', at half the step divided by at the full"
          << " step; about 0.25 for a smooth curve, 0.5 for a kink, 1 for a jump.\n\n"
          << "| sweep | method | points | ok | no contact | not converged | error | max normal it."
          << " | max tang. it. | max fz it. | jump ratio | s per solve |\n"
          << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
}

// The sweep's values, and with check_continuity also the values at half the step.
std::vector<double> HalfStepValues(const Sweep& sweep) {
  std::vector<double> half;
  for (std::size_t k = 0; k + 1 < sweep.values.size(); ++k) {
    half.push_back(sweep.values[k]);
    half.push_back(0.5 * (sweep.values[k] + sweep.values[k + 1]));
  }
  half.push_back(sweep.values.back());
  return half;
}

// Solves one sweep with every method, writes its CSV, summary rows and picture; returns the
// number of solves that did not converge or failed.
int RunSweep(const Sweep& sweep, const std::vector<std::string>& methods,
             const std::function<CaseMaker(const std::string&, double)>& make, int threads,
             const fs::path& out_dir, std::ostream& summary) {
  std::vector<Job> jobs;
  for (const std::string& m : methods) {
    for (double v : sweep.values) jobs.push_back({make(m, v), v});
  }
  const std::vector<double> half =
      sweep.check_continuity ? HalfStepValues(sweep) : std::vector<double>{};
  for (const std::string& m : methods) {
    for (double v : half) jobs.push_back({make(m, v), v});
  }
  std::cerr << "stability: " << sweep.name << " (" << jobs.size() << " solves)\n";
  const std::vector<Sample> results = RunAll(jobs, threads);
  OutputText csv(out_dir / (sweep.name + ".csv"));
  csv << "method_index,method,parameter,status,fx,fy,fz,z,contact_y,n_patches,normal_it,"
         "tangential_it,fz_it,seconds,message\n";
  csv.precision(10);
  const std::size_t n = sweep.values.size();
  int failures = 0;
  for (std::size_t m = 0; m < methods.size(); ++m) {
    std::vector<Sample> full(results.begin() + m * n, results.begin() + (m + 1) * n);
    int counts[4] = {0, 0, 0, 0};
    int max_n = 0, max_t = 0, max_f = 0;
    double seconds = 0.0;
    for (const Sample& s : full) {
      csv << m << ',' << methods[m] << ',' << s.parameter << ',' << s.status << ',' << s.fx << ','
          << s.fy << ',' << s.fz << ',' << s.z << ',' << s.contact_y << ',' << s.n_patches << ','
          << s.normal_iterations << ',' << s.tangential_iterations << ',' << s.fz_iterations << ','
          << s.seconds << ",\"" << s.message << "\"\n";
      counts[s.status == "ok"              ? 0
             : s.status == "no_contact"    ? 1
             : s.status == "not_converged" ? 2
                                           : 3]++;
      const bool finite = std::isfinite(s.fx) && std::isfinite(s.fy) && std::isfinite(s.fz);
      if (s.status == "ok" && !finite) ++counts[3];
      max_n = std::max(max_n, s.normal_iterations);
      max_t = std::max(max_t, s.tangential_iterations);
      max_f = std::max(max_f, s.fz_iterations);
      seconds += s.seconds;
    }
    failures += counts[2] + counts[3];
    std::string ratio = "–";
    if (sweep.check_continuity) {
      const std::size_t base = methods.size() * n + m * half.size();
      std::vector<Sample> fine(results.begin() + base, results.begin() + base + half.size());
      double Sample::*field =
          sweep.parameter.rfind("wheelset z", 0) == 0 ? &Sample::fz : &Sample::fy;
      const double a = LargestJump(full, field), b = LargestJump(fine, field);
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.2f", a > 0.0 ? b / a : 0.0);
      ratio = buf;
    }
    char time_buf[32];
    std::snprintf(time_buf, sizeof time_buf, "%.3f", seconds / full.size());
    summary << "| " << sweep.name << " | " << methods[m] << " | " << full.size() << " | "
            << counts[0] << " | " << counts[1] << " | " << counts[2] << " | " << counts[3] << " | "
            << max_n << " | " << max_t << " | " << max_f << " | " << ratio << " | " << time_buf
            << " |\n";
  }
  csv.Commit();
  Plot(out_dir, sweep, methods);
  return failures;
}

void WritePlotLinks(std::ostream& summary, const std::vector<Sweep>& sweeps) {
  summary << "\nData: one CSV per sweep. Plots: ";
  for (const Sweep& s : sweeps) summary << "[" << s.name << "](" << s.name << ".png) ";
  summary << "\n";
}

// `method.*` of each method name of the study; the case's combine_distance is kept.
void ApplyMethod(const std::string& name, Method* method) {
  method->reference = name == "curved" ? ReferenceSurface::kCurved : ReferenceSurface::kPlanar;
  if (name == "planar-icp") {
    method->position = ReferencePosition::kInitial;
    method->angle = ReferenceAngle::kSampled;
  } else {
    method->position = ReferencePosition::kWeighted;
    method->angle = ReferenceAngle::kWeighted;
    method->weights = ReferenceWeights::kQuadratic;
  }
}

// Quantities a user's case can be swept over, with their units.
const std::map<std::string, std::string>& SweepableQuantities() {
  static const std::map<std::string, std::string> q = {
      {"y", "mm"},    {"z", "mm"},   {"fz", "N"},        {"roll", "rad"},
      {"yaw", "rad"}, {"spin", "-"}, {"omega", "rad/s"}, {"mu", "-"}};
  return q;
}

// The case with one swept quantity set, as a table axis would set it.
void SetQuantity(const std::string& name, double value, Case* c) {
  WheelsetState& s = c->state;
  if (name == "y") s.y = value;
  if (name == "roll") s.roll = value;
  if (name == "yaw") s.yaw = value;
  if (name == "z") {
    s.z = value;
    s.fz.reset();
  }
  if (name == "fz") {
    s.fz = value;
    s.z.reset();
  }
  if (name == "spin") {
    s.spin = value;
    s.omega = OmegaFromSpin(value, s.velocity, c->wheelset.nominal_radius);
  }
  if (name == "omega") {
    s.omega = value;
    s.spin.reset();
  }
  if (name == "mu") c->friction = Friction::Constant(value);
}

// The profile files a built-in sweep reads (its name's prefix names its pair).
std::vector<std::string> SweepProfiles(const std::string& sweep) {
  if (sweep.rfind("heavy_haul", 0) == 0) return {"site_b_hr.prr", "worn_high_mileage.prw"};
  if (sweep.rfind("groove", 0) == 0) return {"groove_r1002.prr", "circ_r10.prw"};
  return {"MBench_UIC60_v3.prr", "MBench_S1002_v3.prw"};
}

// The first profile of the sweep missing from `profiles`; empty when all are there.
std::string MissingProfile(const std::string& sweep, const fs::path& profiles) {
  for (const std::string& name : SweepProfiles(sweep)) {
    if (!fs::exists(profiles / name)) return name;
  }
  return {};
}

// The built-in hard cases, every step doubled when `quick`.
std::vector<Sweep> BuiltInSweeps(bool quick) {
  const double f = quick ? 2.0 : 1.0;
  std::vector<Sweep> sweeps;
  sweeps.push_back({"mbench_y", "Manchester S1002/UIC60, lateral shift, fz = 10 kN",
                    "wheelset y, mm", Range(0.0, 10.0, 0.1 * f), false, true});
  sweeps.push_back({"mbench_yaw", "Manchester, y = 4 mm, yaw", "yaw, rad",
                    Range(-0.03, 0.03, 0.0025 * f), false, false});
  sweeps.push_back({"mbench_spin", "Manchester, y = 4 mm, spin to full slip", "spin, -",
                    Range(0.0, 0.03, 0.001 * f), false, false});
  sweeps.push_back({"mbench_load", "Manchester, y = 0 mm, load 1 N to 300 kN", "fz, N",
                    LogRange(1.0, 3e5, quick ? 11 : 21), true, false});
  sweeps.push_back({"mbench_mu0", "Manchester, frictionless (mu = 0)", "wheelset y, mm",
                    Range(0.0, 10.0, 0.25 * f), false, false});
  sweeps.push_back({"heavy_haul_z", "Heavy haul y = 14.85 mm, z through the patch merge",
                    "wheelset z, mm", Range(1.0, 1.3, 0.005 * f), false, true});
  sweeps.push_back(
      {"heavy_haul_omega",
       "Heavy haul y = 14.85 mm, fz = 100 kN, wheelset angular velocity (paper Fig. 14)",
       "omega, rad/s", Range(-33.5, -30.7, 0.1 * f), false, false});
  sweeps.push_back({"groove_load", "Ball R10 in groove R10.02 (nearly conformal), load", "fz, N",
                    LogRange(100.0, 20000.0, quick ? 6 : 11), true, false});
  return sweeps;
}

// The case text of built-in sweep `sweep` with method `m` at value `v`; grid dx for the
// Manchester cases.
std::string BuiltInCase(const fs::path& profiles, double dx, const std::string& sweep,
                        const std::string& m, double v) {
  auto method_text = [&](bool heavy) { return heavy ? HeavyHaulMethod(m) : Methods().at(m); };
  if (sweep == "mbench_y") return Manchester(profiles, method_text(false), dx, v, 0, 0, 1e4, 0.3);
  if (sweep == "mbench_yaw") return Manchester(profiles, method_text(false), dx, 4, v, 0, 1e4, 0.3);
  if (sweep == "mbench_spin")
    return Manchester(profiles, method_text(false), dx, 4, 0, v, 1e4, 0.3);
  if (sweep == "mbench_load") return Manchester(profiles, method_text(false), dx, 0, 0, 0, v, 0.3);
  if (sweep == "mbench_mu0") return Manchester(profiles, method_text(false), dx, v, 0, 0, 1e4, 0.0);
  if (sweep == "heavy_haul_z") return HeavyHaul(profiles, method_text(true), v, 0.0, -32.1);
  if (sweep == "heavy_haul_omega") return HeavyHaul(profiles, method_text(true), 0, 1e5, v);
  if (sweep == "groove_load") return Groove(profiles, method_text(false), v);
  throw std::logic_error("no case template for sweep " + sweep);
}

int RunStabilityStudy(const fs::path& out_dir, const fs::path& profiles, bool quick, int threads) {
  fs::create_directories(out_dir);
  const double dx = quick ? 0.5 : 0.25;
  const std::vector<std::string> methods = {"planar", "planar-icp", "curved"};
  OutputText summary(out_dir / "README.md");
  WriteSummaryHeader(summary, "The built-in hard cases, generated by `wrc study stability" +
                                  std::string(quick ? " --quick" : "") +
                                  " --profiles DIR`. Grid dx = ds = " + FormatSize(dx) +
                                  " mm (heavy haul 0.4 mm, groove 0.2 × 0.25 mm); combine "
                                  "distance 6 mm (heavy haul 30 mm).");
  int failures = 0;
  std::vector<Sweep> done;
  std::string skipped;
  for (const Sweep& sweep : BuiltInSweeps(quick)) {
    // A sweep whose profiles are not in the directory is left out, and the summary says so.
    const std::string missing = MissingProfile(sweep.name, profiles);
    if (!missing.empty()) {
      std::cerr << "stability: " << sweep.name << " left out: no " << missing << " in "
                << profiles.string() << '\n';
      skipped += " " + sweep.name + " (no " + missing + ")";
      continue;
    }
    done.push_back(sweep);
    const auto make = [&](const std::string& m, double v) -> CaseMaker {
      const std::string text = BuiltInCase(profiles, dx, sweep.name, m, v);
      return [text] { return ParseCase(text, fs::current_path(), "stability"); };
    };
    failures += RunSweep(sweep, methods, make, threads, out_dir, summary);
  }
  WritePlotLinks(summary, done);
  if (!skipped.empty()) summary << "\nLeft out, for want of their profiles:" << skipped << "\n";
  summary.Commit();
  SayReport("stability", out_dir / "README.md");
  return failures == 0 ? kExitOk : kExitGateFailed;
}

// A user's case swept over one quantity with each method.
struct CaseSweepOptions {
  std::string case_path;
  std::string quantity = "y";
  double from = 0.0, to = 10.0, step = 0.5;
  std::vector<std::string> methods = {"planar", "planar-icp", "curved"};
  bool check_continuity = false;
};

int RunCaseSweep(const CaseSweepOptions& o, const fs::path& out_dir, int threads) {
  const Case base = LoadCase(o.case_path);
  if (base.type != CaseType::kWheelRail) {
    throw InputError(o.case_path + ": the stability study sweeps wheel-rail cases only");
  }
  if (!(o.step > 0.0) || !(o.to > o.from) || (o.to - o.from) / o.step > 1e5) {
    throw InputError("--from " + FormatSize(o.from) + " --to " + FormatSize(o.to) + " --step " +
                     FormatSize(o.step) + ": need from < to and 0 < step, at most 1e5 steps");
  }
  fs::create_directories(out_dir);
  const std::string stem = fs::path(o.case_path).stem().string();
  const Sweep sweep{
      stem + "_" + o.quantity,
      stem + ": " + o.quantity,
      (o.quantity == "z" ? "wheelset z" : o.quantity) + ", " + SweepableQuantities().at(o.quantity),
      Range(o.from, o.to, o.step),
      false,
      o.check_continuity};
  OutputText summary(out_dir / "README.md");
  WriteSummaryHeader(summary, "`" + o.case_path + "` swept over " + o.quantity + " from " +
                                  FormatSize(o.from) + " to " + FormatSize(o.to) + " in steps of " +
                                  FormatSize(o.step) + " (`wrc study stability`).");
  const auto make = [&](const std::string& m, double v) -> CaseMaker {
    return [&base, m, v, &o] {
      Case c = base;
      ApplyMethod(m, &c.method);
      SetQuantity(o.quantity, v, &c);
      return c;
    };
  };
  const int failures = RunSweep(sweep, o.methods, make, threads, out_dir, summary);
  WritePlotLinks(summary, {sweep});
  summary.Commit();
  SayReport("stability", out_dir / "README.md");
  return failures == 0 ? kExitOk : kExitGateFailed;
}

}  // namespace

void AddStabilityStudy(CLI::App& study, int* exit_code) {
  auto* stability = study.add_subcommand(
      "stability",
      "Sweep a case over one quantity with the planar and curved methods and report (or, with "
      "--profiles and no CASE, the built-in hard cases)");
  auto sweep = std::make_shared<CaseSweepOptions>();
  auto out = std::make_shared<std::string>("study-stability");
  auto profiles = std::make_shared<std::string>();
  auto quick = std::make_shared<bool>(false);
  auto threads = std::make_shared<int>(AllCores());
  stability->add_option("CASE", sweep->case_path, "Wheel-rail case file to sweep")
      ->check(CLI::ExistingFile);
  std::vector<std::string> names;
  for (const auto& [name, unit] : SweepableQuantities()) names.push_back(name);
  stability->add_option("--sweep", sweep->quantity, "Quantity swept")
      ->check(CLI::IsMember(names))
      ->capture_default_str();
  stability->add_option("--from", sweep->from, "First value")->capture_default_str();
  stability->add_option("--to", sweep->to, "Last value")->capture_default_str();
  stability->add_option("--step", sweep->step, "Step")->capture_default_str();
  stability->add_option("--methods", sweep->methods, "Methods compared")
      ->delimiter(',')
      ->check(CLI::IsMember({"planar", "planar-icp", "curved"}))
      ->capture_default_str();
  stability->add_flag("--continuity", sweep->check_continuity,
                      "Also solve at half the step and report the jump ratio");
  AddOutOption(stability, out.get(), "Output directory (CSV, PNG, README.md)");
  stability->add_option("--profiles", *profiles,
                        "Without CASE: directory with the profiles of the built-in hard cases");
  stability->add_flag("--quick", *quick, "Built-in hard cases: double every step");
  AddThreadsOption(stability, threads.get(), false);
  OnRun(stability, exit_code, "wrc study stability", [=]() {
    if (!sweep->case_path.empty()) return RunCaseSweep(*sweep, *out, std::max(1, *threads));
    if (profiles->empty()) {
      throw InputError("give a CASE to sweep, or --profiles DIR for the built-in hard cases");
    }
    if (!fs::exists(fs::path(*profiles) / "MBench_S1002_v3.prw")) {
      throw InputError("--profiles " + *profiles + ": MBench_S1002_v3.prw not found there");
    }
    return RunStabilityStudy(*out, fs::absolute(*profiles), *quick, std::max(1, *threads));
  });
}

}  // namespace wrc::cli
