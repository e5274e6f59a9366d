#pragma once
// What the studies that reproduce the paper share: the methods of the paper's Table 1, a
// worker pool, gnuplot, number formatting.

#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "wrc/core/case.h"
#include "wrc/core/wheelrail.h"

namespace wrc::cli {

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

/// Calls job(k) for k = 0 … n−1 on `threads` threads. An exception a job lets out ends its
/// thread's share of the jobs and is rethrown once every thread has finished.
void RunParallel(std::size_t n, int threads, const std::function<void(std::size_t)>& job);

/// Writes `script` as dir/name.gp and runs gnuplot on it in `dir`; says so on stderr (with
/// `who` as prefix) when gnuplot fails or is missing, the data being written already.
void RunGnuplot(const std::filesystem::path& dir, const std::string& name,
                const std::string& script, const std::string& who);

/// The text with gnuplot's enhanced-text marks (_ ^ @ & ~ { }) escaped.
std::string GnuplotLiteral(const std::string& text);

/// v with `digits` decimals; "–" for NaN.
std::string Fixed(double v, int digits);

/// A force in N written in kN with `digits` decimals.
inline std::string Kn(double newton, int digits = 1) { return Fixed(newton / 1000.0, digits); }

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

/// Solves `c`; an exception becomes status "error" with its message.
SolveSummary SolveAndSummarize(const Case& c, const WheelRailOptions& options = {});

/// Solves every case on `threads` threads, in order.
std::vector<SolveSummary> SolveAll(const std::vector<Case>& cases, int threads,
                                   const WheelRailOptions& options = {});

}  // namespace wrc::cli
