#pragma once
/// @file tangential_solver.h
/// Steady-rolling tangential contact with Coulomb friction (paper Eq. 11–12): find tangential
/// tractions p_t on the contact area with actual slip s = w + (u − u')/δq, |p_t| <= μ·p_n,
/// s = 0 where |p_t| < μ·p_n (adhesion) and p_t = −μ·p_n·s/|s| where it slips.

#include <cstdint>
#include <memory>
#include <vector>

#include "wrc/core/influence_operator.h"
#include "wrc/core/solver_status.h"

namespace wrc {

/// Element states of the tangential solution (CONTACT's IGS numbering).
enum class ElementState : std::uint8_t { kExterior = 0, kAdhesion = 1, kSlip = 2 };

/// The steady-rolling slip operator of one contact grid, rolling in +x with the leading edge at
/// x > 0 (material flows towards −x): s_I = w_I + (u_I − u'_I)/δq, where u'_I = u(x_I + δq) is
/// the displacement the particle had one step upstream. δq = dx, so u' is u one element
/// upstream; the influence coefficients are prepared on the grid extended by one column at the
/// leading edge so that u' of the first column is exact, not truncated.
class SteadyRollingOperator {
 public:
  SteadyRollingOperator(const Grid& grid, const CombinedElasticity& material);
  const Grid& grid() const { return grid_; }
  const CombinedElasticity& material() const { return material_; }
  const FftInfluenceOperator& extended() const { return *extended_; }
  /// Influence coefficients on the extended grid (offsets |di| <= nx, |dj| < ny).
  const InfluenceCoefficients& xx() const { return *xx_; }
  const InfluenceCoefficients& yy() const { return *yy_; }
  const InfluenceCoefficients& xy() const { return *xy_; }

 private:
  Grid grid_;
  CombinedElasticity material_;
  std::unique_ptr<FftInfluenceOperator> extended_;
  std::unique_ptr<InfluenceCoefficients> xx_, yy_, xy_;
};

/// Options of the tangential solver.
struct TangentialOptions {
  /// Stop when the largest traction change in a sweep is below tolerance·max(μ·p_n). Measured
  /// on the reference case halfspace/ab3_cksi0.001: 1e-7 leaves fx within 1e-9 relative of a
  /// 1e-11 solve (CONTACT prints 4 digits) with 25 % fewer sweeps than 1e-9.
  double tolerance = 1e-7;
  int max_iterations = 5000;
  /// Sweeps combined by Anderson acceleration (0: plain Gauss–Seidel). Convergence is still
  /// judged on a plain sweep, so the result meets the same tolerance either way. Measured on
  /// the Manchester curved cases (partial slip): 8 takes the final solves from 17–22 sweeps to
  /// 13–16; depths beyond 8 gain nothing, 1–3 about half as much; full slip is unchanged.
  int acceleration_depth = 8;
  /// Let fast-converging sweeps keep every slip current by direct updates instead of an FFT
  /// product per sweep, where that is cheaper (small contact in a large box; see
  /// SolveTangential). Same iterates up to round-off; off for comparisons in tests.
  bool direct_refresh = true;
  /// Start from the tractions already in TangentialSolution::px/py when their size fits the
  /// grid (set to zero outside the contact), e.g. the previous solve of a force iteration;
  /// otherwise from zero tractions.
  bool warm_start = false;
  /// Compute the slip field from a fresh product of the final tractions (one product, an
  /// eighth of a full-slip heavy-haul solve). Off when nobody reads the field: the slips are
  /// then the ones the last sweep used inside the contact's box (current to the tolerance) and
  /// the rigid slip outside it. Tractions, forces and states are the same either way.
  bool final_slip = true;
};

/// Input of a tangential solve on the operator's grid.
struct TangentialProblem {
  std::vector<double> pressure;  ///< Normal pressure p_n per element, N/mm² (>= 0).
  std::vector<double> mu;        ///< Coefficient of friction per element (size 1: everywhere).
  std::vector<double> wx, wy;    ///< Relative rigid slip per element, -.
};

/// Result of a tangential solve.
struct TangentialSolution {
  std::vector<double> px, py;  ///< Tangential tractions on body 1, N/mm².
  std::vector<double> sx, sy;  ///< Relative actual slip, -.
  std::vector<ElementState> state;
  double fx = 0.0, fy = 0.0;  ///< Total tangential forces, N.
  double mz = 0.0;            ///< Σ (x·p_y − y·p_x)·dA about the grid origin, N·mm.
  int n_adhesion = 0;
  int n_slip = 0;
};

struct TangentialSummary {
  SolverStatus status = SolverStatus::kNotConverged;
  int iterations = 0;
  double residual = 0.0;
};

/// Scratch memory for SolveTangential, caller-owned so that repeated solves reuse its buffers
/// the size of the grid. The contact box of the sweep (rows, bounds) and the Anderson history
/// are made per solve, in memory that grows with the contact, not the grid. What it holds is
/// the solver's own (opaque); move-only.
class TangentialWorkspace {
 public:
  TangentialWorkspace();
  ~TangentialWorkspace();
  TangentialWorkspace(TangentialWorkspace&&) noexcept;
  TangentialWorkspace& operator=(TangentialWorkspace&&) noexcept;
  struct Scratch;  ///< Defined by the solver.
  Scratch& scratch() { return *scratch_; }

 private:
  std::unique_ptr<Scratch> scratch_;
};

/// Solves the steady-rolling problem for identical (quasi-identical) materials; the normal
/// pressure is given. Method: Gauss–Seidel over the elements in the order of Kalker's SteadyGS
/// (row by row, each row from the leading edge downstream, following the material), in the
/// variables d_i = p_i − p_(i+1), the traction differences along the row: updating element i
/// shifts the tractions of all elements downstream of it in its row alike. In these variables
/// the steady-rolling slip operator s = w + (u − u')/δq becomes s = w + A·d/δq (the rolling
/// derivative moves from u onto p), whose diagonal dominates; Gauss–Seidel on p itself cycles,
/// because its upstream coupling equals minus its own stiffness. Every element update solves
/// its local Coulomb problem exactly (adhesion, or slip with the traction on the bound, opposite
/// to the slip), and the slip of the contact elements still to be visited in the sweep is
/// corrected after each update (in later rows the part common to a row's updates once per row);
/// once per sweep all slips are recomputed by FFT, which also stops round-off drift. Throws
/// std::invalid_argument for inconsistent sizes or non-finite input.
TangentialSummary SolveTangential(const SteadyRollingOperator& op, const TangentialProblem& problem,
                                  const TangentialOptions& options, TangentialWorkspace& workspace,
                                  TangentialSolution& solution);

}  // namespace wrc
