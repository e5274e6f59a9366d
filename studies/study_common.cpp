#include "studies/study_common.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "studies/shipped_files.h"
#include "tools/wrc/exit_codes.h"
#include "tools/wrc/gnuplot.h"
#include "tools/wrc/thread_option.h"
#include "wrc/core/errors.h"
#include "wrc/core/output_file.h"
#include "wrc/generator/worker_threads.h"

namespace wrc::cli {

namespace fs = std::filesystem;

void OnRun(CLI::App* command, int* exit_code, const std::string& who,
           const std::function<int()>& run) {
  command->callback([exit_code, who, run]() {
    try {
      *exit_code = run();
    } catch (...) {
      *exit_code = ReportFailure(who);
    }
  });
}

CLI::Option* AddThreadsOption(CLI::App* command, int* threads, bool zero_is_all_cores,
                              const std::string& what) {
  return command->add_option("--threads", *threads, what)
      ->check(ThreadCount(zero_is_all_cores))
      ->capture_default_str();
}

double SecondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void SayReport(const std::string& who, const fs::path& report) {
  std::cerr << who << ": report in " << report.string() << '\n';
}

const std::vector<PaperMethod>& PaperMethods() {
  using RS = ReferenceSurface;
  using RP = ReferencePosition;
  using RA = ReferenceAngle;
  using RW = ReferenceWeights;
  static const std::vector<PaperMethod> methods = {
      {"curved", "curved reference", RS::kCurved, RP::kWeighted, RA::kWeighted, RW::kQuadratic},
      {"crv-icp", "curved reference with initial contact", RS::kCurved, RP::kInitial, RA::kSampled,
       RW::kQuadratic},
      {"wgt-loc-1", "weighted center, sampled, linear", RS::kPlanar, RP::kWeighted, RA::kSampled,
       RW::kLinear},
      {"wgt-loc-2", "weighted center, sampled, squared", RS::kPlanar, RP::kWeighted, RA::kSampled,
       RW::kQuadratic},
      {"wgt-wgt-1", "weighted center, average, linear", RS::kPlanar, RP::kWeighted, RA::kWeighted,
       RW::kLinear},
      {"wgt-wgt-2", "weighted center, average, squared", RS::kPlanar, RP::kWeighted, RA::kWeighted,
       RW::kQuadratic},
      {"icp-loc", "initial contact, sampled", RS::kPlanar, RP::kInitial, RA::kSampled,
       RW::kQuadratic},
      {"icp-wgt-1", "initial contact, average, linear", RS::kPlanar, RP::kInitial, RA::kWeighted,
       RW::kLinear},
      {"icp-wgt-2", "initial contact, average, squared", RS::kPlanar, RP::kInitial, RA::kWeighted,
       RW::kQuadratic}};
  return methods;
}

const PaperMethod& PaperMethodNamed(const std::string& name) {
  for (const PaperMethod& m : PaperMethods()) {
    if (m.name == name) return m;
  }
  throw std::logic_error("no method " + name + " in Table 1");
}

void ApplyPaperMethod(const PaperMethod& m, Method* method) {
  method->reference = m.reference;
  method->position = m.position;
  method->angle = m.angle;
  method->weights = m.weights;
}

std::string MethodSection(const PaperMethod& m, double combine_distance) {
  std::ostringstream t;
  t << "[method]  # " << m.name << " (the paper's Table 1: " << m.description << ")\n"
    << "reference = \"" << (m.reference == ReferenceSurface::kCurved ? "curved" : "planar")
    << "\"\nposition = \"" << (m.position == ReferencePosition::kInitial ? "initial" : "weighted")
    << "\"\nangle = \"" << (m.angle == ReferenceAngle::kSampled ? "sampled" : "weighted")
    << "\"\nweights = \"" << (m.weights == ReferenceWeights::kLinear ? "linear" : "quadratic")
    << "\"\ncombine_distance = " << combine_distance << "\n";
  return t.str();
}

void RunParallel(std::size_t n, int threads, const std::function<void(std::size_t)>& job,
                 const std::string& who) {
  std::atomic<std::size_t> next{0};
  auto worker = [&]() {
    for (std::size_t k = next++; k < n; k = next++) job(k);
  };
  const int count = std::max(1, std::min<int>(threads, static_cast<int>(n)));
  gen::WorkerThreads pool(count, worker, who);
  pool.Join();
}

void DrawOrSay(const fs::path& dir, const std::string& script_name, const std::string& script,
               const std::string& missing) {
  if (!RunGnuplot(dir, script_name, script)) std::cerr << missing << '\n';
}

void RunGnuplot(const fs::path& dir, const std::string& name, const std::string& script,
                const std::string& who) {
  DrawOrSay(
      dir, name + ".gp", script,
      who + ": gnuplot is not installed (Debian: gnuplot-nox): no picture from " + name + ".gp");
}

std::string GnuplotLiteral(const std::string& text) {
  std::string escaped;
  for (const char c : text) {
    if (std::string("_^@&~{}").find(c) != std::string::npos) escaped += '\\';
    escaped += c;
  }
  return escaped;
}

std::string Fixed(double v, int digits) {
  if (std::isnan(v)) return "–";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, v);
  return buffer;
}

double LateralTrackY(const PatchResult& patch, int j) {
  if (static_cast<int>(patch.curve_y.size()) == patch.grid.ny) return patch.curve_y[j];
  return patch.reference_T(1) + patch.grid.y(j) * std::cos(patch.contact_angle);
}

// The patch that carries most of the load names the contact's angle and friction.
void SummarizePatches(const Case& c, SolveSummary* s) {
  const std::vector<PatchResult>& patches = s->result.patches;
  s->n_patches = static_cast<int>(patches.size());
  s->fs = 0.0;
  const PatchResult* main = nullptr;
  for (const PatchResult& p : patches) {
    s->fs += p.fs;
    if (!main || p.fn > main->fn) main = &p;
  }
  if (main) {
    s->contact_angle = main->contact_angle;
    s->mu = c.friction.MuAt(main->contact_angle);
  }
}

void RecordSolveError(const std::function<void()>& solve, std::string* status,
                      std::string* message) {
  try {
    solve();
  } catch (const InputError& e) {  // the case does not solve; a bug propagates
    *status = "error";
    *message = e.what();
  } catch (const NumericalError& e) {
    *status = "error";
    *message = e.what();
  }
}

SolveSummary SolveAndSummarize(const Case& c, const WheelRailOptions& options) {
  SolveSummary s;
  RecordSolveError(
      [&]() {
        s.result = SolveWheelRail(c, options);
        s.status = ToString(s.result.status);
        s.message = s.result.message;
        s.fx = s.result.force_T(0);
        s.fy = s.result.force_T(1);
        s.fz = s.result.force_T(2);
        s.z = s.result.z;
        s.lv = s.fz != 0.0 ? s.fy / s.fz : NAN;
        SummarizePatches(c, &s);
      },
      &s.status, &s.message);
  return s;
}

std::vector<SolveSummary> SolveAll(const std::vector<Case>& cases, int threads,
                                   const WheelRailOptions& options) {
  std::vector<SolveSummary> out(cases.size());
  RunParallel(cases.size(), threads,
              [&](std::size_t k) { out[k] = SolveAndSummarize(cases[k], options); });
  return out;
}

std::vector<fs::path> WriteShippedFiles(const fs::path& dir,
                                        const std::vector<std::string>& names) {
  std::vector<fs::path> written;
  for (const std::string& name : names) {
    const auto& files = ShippedFiles();
    const auto it = std::find_if(files.begin(), files.end(),
                                 [&](const ShippedFile& f) { return f.name == name; });
    if (it == files.end()) throw std::logic_error("no shipped file " + name);
    const fs::path path = dir / name;
    fs::create_directories(path.parent_path());
    WriteFileAtomically(path, std::string_view(it->bytes.data(), it->bytes.size()));
    written.push_back(path);
  }
  return written;
}

}  // namespace wrc::cli
