#include "wrc/core/halfspace.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "wrc/core/coupled_solver.h"
#include "wrc/core/errors.h"
#include "wrc/core/hertz.h"

namespace wrc {
namespace {

void FillNormal(NormalSolution&& ns, HalfspaceResult& r) {
  r.status = r.normal_summary.status;
  r.fn = ns.force;
  r.pmax = ns.pmax;
  r.approach = ns.approach;
  r.n_contact = ns.n_contact;
  r.area = ns.n_contact * r.grid.element_area();
  r.pressure = std::move(ns.pressure);
}

}  // namespace

namespace {

// The grid around the Hertz estimate of the contact; throws std::invalid_argument when the
// estimate or the grid it asks for is beyond what can be solved.
Grid HertzGrid(const Case& c) {
  const GridSettings& gs = c.grid;
  const CombinedElasticity m = CombinedElasticity::FromBodies(c.rail_material, c.wheel_material);
  const HertzContact hertz(c.geometry.a1, c.geometry.b1, m.EffectiveModulus());
  const HalfspaceState& st = c.halfspace_state;
  const HertzSolution hz =
      st.fn ? hertz.ForForce(*st.fn) : hertz.ForApproach(std::max(*st.approach, 0.0));
  // 25 % margin: the half-space solution stays inside the Hertz ellipse for these smooth
  // quadratic gaps, and tangential loading does not change the contact area when K = 0 (with
  // K != 0 the coupling moves its edge by an element or so).
  // A whole number of cells centred on the origin, so that symmetric problems stay symmetric.
  const double ax =
      0.5 * gs.dx * std::ceil(2.0 * std::max(1.25 * hz.semi_axis_x, 2.0 * gs.dx) / gs.dx);
  const double ay =
      0.5 * gs.dy * std::ceil(2.0 * std::max(1.25 * hz.semi_axis_y, 2.0 * gs.dy) / gs.dy);
  const Interval x = gs.x.value_or(Interval{-ax, ax});
  const Interval y = gs.y.value_or(Interval{-ay, ay});
  return Grid::Covering(x.min, x.max, y.min, y.max, gs.dx, gs.dy);
}

}  // namespace

Grid HalfspaceGrid(const Case& c) {
  const GridSettings& gs = c.grid;
  if (gs.x && gs.y) return Grid::Covering(gs.x->min, gs.x->max, gs.y->min, gs.y->max, gs.dx, gs.dy);
  try {
    return HertzGrid(c);
  } catch (const std::invalid_argument& e) {
    // The grid follows from these keys; the user changes one of them, not the library's call.
    const HalfspaceState& st = c.halfspace_state;
    throw InputError(c.source_name + ": the grid around the Hertz contact of geometry.a1 = " +
                     FormatNumber(c.geometry.a1) +
                     ", geometry.b1 = " + FormatNumber(c.geometry.b1) + " 1/mm and " +
                     (st.fn ? "state.fn = " + FormatNumber(*st.fn) + " N"
                            : "state.approach = " + FormatNumber(*st.approach) + " mm") +
                     " with grid.dx = " + FormatNumber(gs.dx) +
                     ", grid.dy = " + FormatNumber(gs.dy) + " mm cannot be built (" + e.what() +
                     "); give grid.x and grid.y, coarser elements or another load");
  }
}

namespace {

HalfspaceResult SolveUnchecked(const Case& c, const NormalOptions& normal_options,
                               const TangentialOptions& tangential_options) {
  HalfspaceResult r;
  r.grid = HalfspaceGrid(c);
  const Grid& g = r.grid;
  const CombinedElasticity m = CombinedElasticity::FromBodies(c.rail_material, c.wheel_material);

  r.h.resize(g.size());
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      r.h[g.index(i, j)] = c.geometry.a1 * g.x(i) * g.x(i) + c.geometry.b1 * g.y(j) * g.y(j);
    }
  }
  const HalfspaceState& st = c.halfspace_state;
  const NormalLoad load = st.fn ? NormalLoad::Force(*st.fn) : NormalLoad::Approach(*st.approach);

  if (!c.effects.tangential) {
    FftInfluenceOperator normal_op(g, m, {InfluenceComponent::kNN});
    NormalWorkspace nws;
    NormalSolution ns;
    r.normal_summary = SolveNormal(normal_op, r.h, load, normal_options, nws, ns);
    FillNormal(std::move(ns), r);
    return r;
  }

  // With friction: the normal and tangential problems together. For identical bodies (K = 0)
  // SolveCoupled is one normal and one tangential solve; for dissimilar ones it iterates
  // between them through the coupling kernels (coupled_solver.h).
  const CoupledContactOperator op(g, m);
  CoupledProblem pb;
  pb.h = r.h;
  pb.load = load;
  pb.mu = {c.friction.MuAt(0.0)};
  pb.wx.resize(g.size());
  pb.wy.resize(g.size());
  // CONTACT's rigid slip for steady rolling in +x (user guide Eq. rig_shift_roll): the spin
  // term is evaluated at x + δq/6, compensating for the distance rolled in one step.
  const double dq = g.dx;
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      pb.wx[g.index(i, j)] = st.cksi - st.cphi * g.y(j);
      pb.wy[g.index(i, j)] = st.ceta + st.cphi * (g.x(i) + dq / 6.0);
    }
  }
  CoupledOptions options;
  options.normal = normal_options;
  options.tangential = tangential_options;
  CoupledWorkspace ws;
  CoupledSolution sol;
  const CoupledSummary cs = SolveCoupled(op, pb, options, ws, sol);
  // The reported iterations are the totals over the outer iterations (equal to the single
  // solves' for K = 0); residuals and status are those of the returned solves.
  r.normal_summary = cs.normal;
  r.normal_summary.iterations = cs.normal_iterations;
  FillNormal(std::move(sol.normal), r);
  if (r.status == SolverStatus::kNoContact) return r;  // nothing to report tangentially
  r.tangential_summary = cs.tangential;
  r.tangential_summary.iterations = cs.tangential_iterations;
  r.tangential_solved = true;
  r.status = cs.status;
  const TangentialSolution& ts = sol.tangential;
  r.fx = ts.fx;
  r.fy = ts.fy;
  r.mz = ts.mz;
  r.n_slip = ts.n_slip;
  r.n_adhesion = ts.n_adhesion;
  r.px = std::move(sol.tangential.px);
  r.py = std::move(sol.tangential.py);
  r.sx = std::move(sol.tangential.sx);
  r.sy = std::move(sol.tangential.sy);
  r.state = std::move(sol.tangential.state);
  return r;
}

// Fewest elements across a contact patch, in x and in y, for a result worth trusting: with four
// the pressure's peak and edges are each resolved by about one element, and the force error is
// of the order of 10 % (CONTACT's user guide advises ten or more).
constexpr int kMinElementsAcross = 4;

// Whether any element in contact lies on the edge of the potential contact area: the contact
// would then extend beyond it, and what lies outside is not in the result.
bool ContactTouchesEdge(const HalfspaceResult& r) {
  const Grid& g = r.grid;
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const bool edge = i == 0 || j == 0 || i == g.nx - 1 || j == g.ny - 1;
      if (edge && r.pressure[g.index(i, j)] > 0.0) return true;
    }
  }
  return false;
}

// Elements in contact along x and along y: the extent of the contact columns and rows.
std::pair<int, int> ElementsAcross(const HalfspaceResult& r) {
  const Grid& g = r.grid;
  int i_min = g.nx, i_max = -1, j_min = g.ny, j_max = -1;
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      if (!(r.pressure[g.index(i, j)] > 0.0)) continue;
      i_min = std::min(i_min, i);
      i_max = std::max(i_max, i);
      j_min = std::min(j_min, j);
      j_max = std::max(j_max, j);
    }
  }
  return {i_max - i_min + 1, j_max - j_min + 1};
}

// What the numbers cannot show by themselves: a solution that is not finite (status not
// converged), a contact cut off by the potential contact area, a patch too coarsely resolved.
void CheckResult(HalfspaceResult& r) {
  const bool finite = std::isfinite(r.fn) && std::isfinite(r.fx) && std::isfinite(r.fy) &&
                      std::isfinite(r.mz) && std::isfinite(r.pmax) && std::isfinite(r.approach);
  if (!finite) {
    r.status = SolverStatus::kNotConverged;
    r.warnings.push_back(
        "the solution is not finite (forces or approach overflowed): check the magnitudes of "
        "state.fn, state.approach, the creepages and friction.mu");
    return;
  }
  if (r.status == SolverStatus::kNoContact || r.n_contact == 0) return;
  if (ContactTouchesEdge(r)) {
    r.warnings.push_back(
        "the contact reaches the edge of the potential contact area (grid.x, grid.y): it "
        "extends beyond it and the forces are those of a cut-off patch; enlarge grid.x/grid.y "
        "or leave them out");
  }
  const auto [across_x, across_y] = ElementsAcross(r);
  if (across_x < kMinElementsAcross || across_y < kMinElementsAcross) {
    r.warnings.push_back("only " + std::to_string(across_x) + " x " + std::to_string(across_y) +
                         " elements across the contact patch (fewer than " +
                         std::to_string(kMinElementsAcross) +
                         "): grid.dx/grid.dy are too coarse for this patch");
  }
}

}  // namespace

HalfspaceResult SolveHalfspace(const Case& c, const NormalOptions& normal_options,
                               const TangentialOptions& tangential_options) {
  if (c.type != CaseType::kHalfspace) throw InputError("not a half-space case");
  HalfspaceResult r = SolveUnchecked(c, normal_options, tangential_options);
  CheckResult(r);
  return r;
}

}  // namespace wrc
