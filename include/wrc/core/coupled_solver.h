#pragma once
/// @file coupled_solver.h
/// Normal and steady-rolling tangential contact of dissimilar bodies (Kalker's K != 0): the
/// pressure also displaces the surfaces tangentially and the tangential tractions displace them
/// normally (the Cerruti coupling kernels kXN / kNX of paper Eq. 17). Solved by Kalker's
/// Panagiotopoulos process, as in CONTACT: alternate the normal problem with the tangential
/// tractions frozen and the tangential problem with the pressure frozen until both settle.

#include <memory>
#include <vector>

#include "wrc/core/influence_operator.h"
#include "wrc/core/normal_solver.h"
#include "wrc/core/solver_status.h"
#include "wrc/core/tangential_solver.h"

namespace wrc {

struct CoupledWorkspace;

/// The operators of one contact grid: normal (kNN), steady rolling (xx, yy, xy) and, when
/// K != 0, the coupling between them. Built once per grid and material; const afterwards, so it
/// may be shared by threads that each use their own CoupledWorkspace.
class CoupledContactOperator {
 public:
  CoupledContactOperator(const Grid& grid, const CombinedElasticity& material);
  ~CoupledContactOperator();
  CoupledContactOperator(const CoupledContactOperator&) = delete;
  CoupledContactOperator& operator=(const CoupledContactOperator&) = delete;

  const Grid& grid() const { return rolling_.grid(); }
  const CombinedElasticity& material() const { return rolling_.material(); }
  const FftInfluenceOperator& normal() const { return normal_; }
  const SteadyRollingOperator& rolling() const { return rolling_; }
  /// False for identical (quasi-identical) bodies, K = 0: the problems decouple.
  bool coupled() const { return coupling_ != nullptr; }

  /// Adds to (sx, sy) the steady-rolling slip (u − u')/δq of the tangential displacements that
  /// the pressure p causes (kXN, and kXN turned by 90° for y). No-op when K = 0.
  void AddSlipFromPressure(const std::vector<double>& p, std::vector<double>& sx,
                           std::vector<double>& sy, CoupledWorkspace& ws) const;
  /// Adds to un the normal displacements that the tractions (px, py) cause (kNX, and kNX turned
  /// by 90° for py). No-op when K = 0.
  void AddNormalFromTractions(const std::vector<double>& px, const std::vector<double>& py,
                              std::vector<double>& un, CoupledWorkspace& ws) const;

 private:
  struct Coupling;
  FftInfluenceOperator normal_;
  SteadyRollingOperator rolling_;
  std::unique_ptr<Coupling> coupling_;  // null when K = 0
};

/// Options of the outer (Panagiotopoulos) iteration and of the two sub-solvers.
struct CoupledOptions {
  /// Stop when, between two outer iterations, the largest pressure change is below
  /// tolerance·max(p_n) and the largest tangential traction change below
  /// tolerance·max(μ·p_n) (the tangential solver's own scale). Well above the sub-solvers'
  /// tolerances, whose round-off would otherwise keep the iterates from settling.
  double tolerance = 1e-5;
  int max_iterations = 50;
  NormalOptions normal;
  TangentialOptions tangential;
};

/// Input on the operator's grid.
struct CoupledProblem {
  std::vector<double> h;       ///< Undeformed distance without the approach, mm.
  NormalLoad load;             ///< Prescribed force or approach.
  std::vector<double> mu;      ///< Coefficient of friction per element (size 1: everywhere).
  std::vector<double> wx, wy;  ///< Relative rigid slip per element, - (paper Eq. 15).
};

/// Result: a pressure and the tangential solution computed for exactly that pressure (so the
/// traction bound |p_t| <= μ·p_n holds element by element). The pressure is the normal solution
/// for the tractions of the previous outer iteration, which differ from these by less than the
/// tolerance once converged.
struct CoupledSolution {
  NormalSolution normal;          ///< `deformed` includes the normal displacement by p_t.
  TangentialSolution tangential;  ///< Slip `sx, sy` includes the slip caused by the pressure.
};

struct CoupledSummary {
  /// kConverged, kNoContact, or kNotConverged when the outer iteration hit its limit or the
  /// last sub-solve did not converge; the last iterate is returned either way.
  SolverStatus status = SolverStatus::kNotConverged;
  int iterations = 0;             ///< Outer iterations (tangential solves); 1 when K = 0.
  int normal_iterations = 0;      ///< Summed over all normal solves.
  int tangential_iterations = 0;  ///< Summed over all tangential solves.
  double pressure_change = 0.0;   ///< Last max|Δp_n| / max(p_n).
  double traction_change = 0.0;   ///< Last max|Δp_t| / max(μ·p_n).
  NormalSummary normal;           ///< Of the normal solve that gave the returned pressure.
  TangentialSummary tangential;   ///< Of the returned tangential solve.
};

/// Caller-owned scratch memory.
struct CoupledWorkspace {
  NormalWorkspace normal;
  TangentialWorkspace tangential;
  ConvolutionWorkspace coupling, coupling_transposed;
  NormalSolution next_normal;
  TangentialProblem tangential_problem;
  std::vector<double> in, out, in_t, out_t, h, previous_px, previous_py;
};

/// Solves normal and tangential problems together. For K = 0 this is exactly one normal and one
/// tangential solve (bit for bit the uncoupled result). Otherwise, outer iteration k solves
///   the tangential problem with the rigid slip w + (u_t(p_n) − u_t'(p_n))/δq, the slip that the
///   pressure causes through the coupling kernels in steady rolling, and then
///   the normal problem with the undeformed distance h + u_n(p_t) (paper Eq. 10b),
/// until neither changes any more. Throws std::invalid_argument for inconsistent sizes or
/// non-finite input; non-convergence is reported in the summary.
CoupledSummary SolveCoupled(const CoupledContactOperator& op, const CoupledProblem& problem,
                            const CoupledOptions& options, CoupledWorkspace& workspace,
                            CoupledSolution& solution);

}  // namespace wrc
