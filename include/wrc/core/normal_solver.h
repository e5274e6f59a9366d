#pragma once
/// @file normal_solver.h
/// The normal contact problem on a grid (paper Eq. 12a–b): find pressures p >= 0 with deformed
/// distance e = h + A·p >= 0 and p·e = 0, for prescribed approach or prescribed total force.

#include <cstddef>
#include <memory>
#include <vector>

#include "wrc/core/influence_operator.h"
#include "wrc/core/solver_status.h"

namespace wrc {

/// Options of the normal solver.
struct NormalOptions {
  /// Stop when the relative change of the pressures in one iteration, Σ|Δp| / Σp, drops below
  /// this. Measured on Hertz at 32²–128² grids: 1e-8 leaves the approach within 2e-10 (and pmax
  /// within 1e-8) of a 1e-12 solve, two orders below CONTACT's EPS = 1e-6, and saves ~20 % of
  /// the iterations of 1e-10.
  double tolerance = 1e-8;
  int max_iterations = 2000;
  /// Start from the pressures already in NormalSolution::pressure when their size fits the grid
  /// (e.g. a neighbouring point of a sweep); otherwise from a uniform pressure.
  bool warm_start = false;
  /// Precondition the CG with the 3 × 3 centre of the inverse influence matrix
  /// (FftInfluenceOperator::LocalInverse). Same fixed point and stopping rule; measured on the
  /// heavy-haul cases: 44–55 iterations become 25–29. Off only to compare.
  bool precondition = true;
  /// Under approach control, finish with deflated PCG once the contact set has settled
  /// (SolveOnContactSet in normal_solver.cpp): measured on heavy haul, 22/27/29 products become
  /// 17/20/22. Off only to compare.
  bool deflate = true;
};

/// What is prescribed: the total normal force or the approach.
struct NormalLoad {
  enum class Kind { kForce, kApproach };
  Kind kind = Kind::kForce;
  double value = 0.0;  ///< N for kForce, mm for kApproach.

  static NormalLoad Force(double fn) { return {Kind::kForce, fn}; }
  static NormalLoad Approach(double approach) { return {Kind::kApproach, approach}; }
};

/// Result of a normal solve.
struct NormalSolution {
  std::vector<double> pressure;  ///< N/mm² per element, i fastest.
  std::vector<double> deformed;  ///< Deformed distance e = h − approach + A·p per element, mm.
  double approach = 0.0;         ///< mm (prescribed or found).
  double force = 0.0;            ///< Σ p·dA, N.
  double pmax = 0.0;             ///< N/mm².
  int n_contact = 0;             ///< Elements with p > 0.
};

/// Iterations, residual and status of a solve.
struct NormalSummary {
  SolverStatus status = SolverStatus::kNotConverged;
  int iterations = 0;
  double residual = 0.0;  ///< Last relative pressure change.
};

/// Scratch memory for SolveNormal, caller-owned: it keeps every buffer the size of the grid, so
/// repeated solves on grids of the same size do not allocate those. The deflated phase still
/// builds its coarse space (prefix sums, element blocks, their Cholesky factor) per solve, in
/// memory that grows with the contact set, not the grid (docs/design.md, "Memory in a solve").
/// What it holds is the solver's own (opaque); move-only.
class NormalWorkspace {
 public:
  NormalWorkspace();
  ~NormalWorkspace();
  NormalWorkspace(NormalWorkspace&&) noexcept;
  NormalWorkspace& operator=(NormalWorkspace&&) noexcept;
  struct Scratch;  ///< Defined by the solver.
  Scratch& scratch() { return *scratch_; }

 private:
  std::unique_ptr<Scratch> scratch_;
};

/// Solves the normal problem for undeformed distance `h` (excluding the approach: the gap is
/// h − approach + A·p) by the active-set conjugate gradient method of Polonsky & Keer (1999),
/// which is also the basis of CONTACT's NormCG. Throws std::invalid_argument for bad input
/// (size mismatch, non-finite h, negative force); non-convergence is reported in the summary.
NormalSummary SolveNormal(const FftInfluenceOperator& op, const std::vector<double>& h,
                          const NormalLoad& load, const NormalOptions& options,
                          NormalWorkspace& workspace, NormalSolution& solution);

}  // namespace wrc
