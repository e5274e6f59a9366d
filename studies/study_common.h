#pragma once
// The scaffold of the studies: what each `wrc study` command does around its computation (its
// options and callback, timing, parallel runs, the report line, gnuplot, number formats), and
// what the studies that reproduce the paper share (the methods of its Table 1, the solve summary).

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "tools/angles.h"
#include "wrc/core/case.h"
#include "wrc/core/wheelrail.h"

namespace wrc::cli {

using tools::Degrees;

// ---- running a study ----------------------------------------------------------------------

/// Makes `run` the callback of `command`: its result is the exit code; an exception it lets out
/// is reported as `who`'s failure (ReportFailure, tools/wrc/exit_codes.h) and sets that code.
void OnRun(CLI::App* command, int* exit_code, const std::string& who,
           const std::function<int()>& run);

/// Adds --out DIR (a string or a path) with `what` as its help text and the default shown.
template <class Directory>
CLI::Option* AddOutOption(CLI::App* command, Directory* out, const std::string& what) {
  return command->add_option("--out", *out, what)->capture_default_str();
}

/// Adds --threads N (1 … the limit, or also 0 for all cores where `zero_is_all_cores`) with the
/// default shown.
CLI::Option* AddThreadsOption(CLI::App* command, int* threads, bool zero_is_all_cores,
                              const std::string& what = "Worker threads");

/// Seconds since `t0` on the steady clock.
double SecondsSince(std::chrono::steady_clock::time_point t0);

/// Says on stderr where the study's report is: "<who>: report in FILE".
void SayReport(const std::string& who, const std::filesystem::path& report);

// ---- the paper's methods ------------------------------------------------------------------

/// One method of the paper's Table 1: reference surface, reference position and angle, weights.
struct PaperMethod {
  std::string name;         ///< The paper's name ("icp-loc").
  std::string description;  ///< In words, as Table 3 names it.
  ReferenceSurface reference;
  ReferencePosition position;
  ReferenceAngle angle;
  ReferenceWeights weights;
};

/// Table 1 in its order: 0 curved, 1 crv-icp, 2 wgt-loc-1 … 8 icp-wgt-2.
const std::vector<PaperMethod>& PaperMethods();

/// The method of Table 1 called `name`; throws std::logic_error for another name.
const PaperMethod& PaperMethodNamed(const std::string& name);

/// `method` set to `m`; combine_distance is left as it is.
void ApplyPaperMethod(const PaperMethod& m, Method* method);

/// The `[method]` section of a case file for `m`.
std::string MethodSection(const PaperMethod& m, double combine_distance);

// ---- parallel runs and pictures -----------------------------------------------------------

/// Calls job(k) for k = 0 … n−1 on `threads` threads (at most n, at least one), named `who` in
/// a failure to start them. An exception a job lets out ends its thread's share of the jobs and
/// is rethrown once every thread has finished.
void RunParallel(std::size_t n, int threads, const std::function<void(std::size_t)>& job,
                 const std::string& who = "wrc study");

/// Writes `script` as dir/script_name and runs gnuplot on it in `dir` (RunGnuplot,
/// tools/wrc/gnuplot.h); prints the line `missing` on stderr when gnuplot is not installed, what
/// is lost being the picture, never the data.
void DrawOrSay(const std::filesystem::path& dir, const std::string& script_name,
               const std::string& script, const std::string& missing);

/// Writes `script` as dir/name.gp and runs gnuplot on it in `dir`; says so on stderr (with
/// `who` as prefix) when gnuplot is missing, the data being written already.
void RunGnuplot(const std::filesystem::path& dir, const std::string& name,
                const std::string& script, const std::string& who);

/// The text with gnuplot's enhanced-text marks (_ ^ @ & ~ { }) escaped.
std::string GnuplotLiteral(const std::string& text);

// ---- numbers and solves as the reports write them ----------------------------------------

/// v with `digits` decimals; "–" for NaN.
std::string Fixed(double v, int digits);

/// A force in N written in kN with `digits` decimals.
inline std::string Kn(double newton, int digits = 1) { return Fixed(newton / 1000.0, digits); }

/// The lateral track position of grid row j of a patch: on the curved reference the row's curve
/// point, on a plane the row's offset s along the plane from the reference.
double LateralTrackY(const PatchResult& patch, int j);

/// One wheel–rail solve as the studies report it: status, total forces in the track frame,
/// L/V, the patches' resultants.
struct SolveSummary {
  std::string status = "error";
  std::string message;
  double fx = NAN, fy = NAN, fz = NAN, z = NAN;
  double fs = NAN;  ///< Σ of the patches' lateral tangential forces (in their own frames).
  double lv = NAN;  ///< fy / fz.
  int n_patches = 0;
  double contact_angle = NAN;  ///< Reference angle δ of the patch with the largest fn, rad.
  double mu = NAN;             ///< Friction coefficient at that angle.
  WheelRailResult result;      ///< The whole result (fields when asked for).
};

/// Runs `solve`; an InputError or NumericalError it throws (the case does not solve) becomes
/// *status "error" and *message its text. Any other exception (a bug) propagates.
void RecordSolveError(const std::function<void()>& solve, std::string* status,
                      std::string* message);

/// Solves `c`; an exception becomes status "error" with its message.
SolveSummary SolveAndSummarize(const Case& c, const WheelRailOptions& options = {});

/// Solves every case on `threads` threads, in order.
std::vector<SolveSummary> SolveAll(const std::vector<Case>& cases, int threads,
                                   const WheelRailOptions& options = {});

}  // namespace wrc::cli
