#include "wrc/core/coupled_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace wrc {
namespace {

// The grid of the steady-rolling operator: one column beyond the leading edge (x > 0), where
// p = 0, so that u' = u(x + δq) of the last column is exact.
Grid Extended(const Grid& g) {
  Grid e = g;
  e.nx = g.nx + 1;
  return e;
}

// x and y swapped. The kernels kXN, kNX evaluated on it are kYN, kNY of the original grid
// (−K/(πG)·Y/r² and +K/(πG)·Y/r²), which InfluenceComponent does not list.
Grid Transposed(const Grid& g) { return Grid{g.ny, g.nx, g.dy, g.dx, g.y0, g.x0}; }

SolverStatus Worse(SolverStatus a, SolverStatus b) {
  if (a == SolverStatus::kNotConverged || b == SolverStatus::kNotConverged) {
    return SolverStatus::kNotConverged;
  }
  if (a == SolverStatus::kNoContact || b == SolverStatus::kNoContact) {
    return SolverStatus::kNoContact;
  }
  return SolverStatus::kConverged;
}

double MaxAbsDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::fabs(a[i] - b[i]));
  return d;
}

}  // namespace

struct CoupledContactOperator::Coupling {
  Coupling(const Grid& grid, const CombinedElasticity& m)
      : ext(Extended(grid)),
        op(ext, m, {InfluenceComponent::kXN, InfluenceComponent::kNX}),
        op_t(Transposed(ext), m, {InfluenceComponent::kXN, InfluenceComponent::kNX}) {}

  // Copies `values` (grid size) into ws.in on the extended grid, or into ws.in_t on its
  // transpose, zero in the extra column.
  void Load(const Grid& g, const std::vector<double>& values, bool transposed,
            CoupledWorkspace& ws) const {
    const std::size_t ne = ext.size();
    if (!op.Fits(ws.coupling)) ws.coupling = op.MakeWorkspace();
    if (!op_t.Fits(ws.coupling_transposed)) ws.coupling_transposed = op_t.MakeWorkspace();
    std::vector<double>& in = transposed ? ws.in_t : ws.in;
    in.assign(ne, 0.0);
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) in[Index(transposed, i, j)] = values[g.index(i, j)];
    }
    (transposed ? ws.out_t : ws.out).resize(ne);
  }
  // Where element (i, j) of the extended grid is stored; transposed, it is element (j, i) of a
  // grid with ny columns.
  std::size_t Index(bool transposed, int i, int j) const {
    const auto i_ = static_cast<std::size_t>(i), j_ = static_cast<std::size_t>(j);
    return transposed ? j_ + static_cast<std::size_t>(ext.ny) * i_
                      : i_ + static_cast<std::size_t>(ext.nx) * j_;
  }
  // Element (i, j) of the extended grid in the result of the product after Load(…, transposed).
  double Out(const CoupledWorkspace& ws, bool transposed, int i, int j) const {
    return (transposed ? ws.out_t : ws.out)[Index(transposed, i, j)];
  }

  Grid ext;
  FftInfluenceOperator op;    // kXN, kNX on the extended grid
  FftInfluenceOperator op_t;  // the same on its transpose: kYN, kNY
};

CoupledContactOperator::CoupledContactOperator(const Grid& grid, const CombinedElasticity& material)
    : normal_(grid, material, {InfluenceComponent::kNN}), rolling_(grid, material) {
  if (material.kappa != 0.0) coupling_ = std::make_unique<Coupling>(grid, material);
}

CoupledContactOperator::~CoupledContactOperator() = default;

void CoupledContactOperator::AddSlipFromPressure(const std::vector<double>& p,
                                                 std::vector<double>& sx, std::vector<double>& sy,
                                                 CoupledWorkspace& ws) const {
  if (!coupling_) return;
  const Grid& g = grid();
  const Coupling& c = *coupling_;
  c.Load(g, p, false, ws);
  c.Load(g, p, true, ws);
  c.op.Apply(InfluenceComponent::kXN, ws.in.data(), ws.out.data(), ws.coupling);
  c.op_t.Apply(InfluenceComponent::kXN, ws.in_t.data(), ws.out_t.data(), ws.coupling_transposed);
  // Steady rolling in +x: s = w + (u − u')/δq with u' = u(x + δq), as for the tangential
  // tractions (tangential_solver.h); δq = dx.
  const double inv_dq = 1.0 / g.dx;
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t I = g.index(i, j);
      sx[I] += (c.Out(ws, false, i, j) - c.Out(ws, false, i + 1, j)) * inv_dq;
      sy[I] += (c.Out(ws, true, i, j) - c.Out(ws, true, i + 1, j)) * inv_dq;
    }
  }
}

void CoupledContactOperator::AddNormalFromTractions(const std::vector<double>& px,
                                                    const std::vector<double>& py,
                                                    std::vector<double>& un,
                                                    CoupledWorkspace& ws) const {
  if (!coupling_) return;
  const Grid& g = grid();
  const Coupling& c = *coupling_;
  c.Load(g, px, false, ws);
  c.Load(g, py, true, ws);
  c.op.Apply(InfluenceComponent::kNX, ws.in.data(), ws.out.data(), ws.coupling);
  c.op_t.Apply(InfluenceComponent::kNX, ws.in_t.data(), ws.out_t.data(), ws.coupling_transposed);
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      un[g.index(i, j)] += c.Out(ws, false, i, j) + c.Out(ws, true, i, j);
    }
  }
}

CoupledSummary SolveCoupled(const CoupledContactOperator& op, const CoupledProblem& pb,
                            const CoupledOptions& options, CoupledWorkspace& ws,
                            CoupledSolution& sol) {
  const std::size_t n = op.grid().size();
  if (pb.h.size() != n || pb.wx.size() != n || pb.wy.size() != n) {
    throw std::invalid_argument("coupled problem: h/rigid slip sizes differ from the grid");
  }
  if (pb.mu.size() != 1 && pb.mu.size() != n) {
    throw std::invalid_argument("coupled problem: mu must have 1 or grid-size values");
  }
  if (!(options.tolerance > 0.0) || options.max_iterations < 1) {
    throw std::invalid_argument("coupled options: tolerance and max_iterations must be positive");
  }
  auto mu_at = [&](std::size_t i) { return pb.mu.size() == 1 ? pb.mu[0] : pb.mu[i]; };

  CoupledSummary summary;
  summary.normal = SolveNormal(op.normal(), pb.h, pb.load, options.normal, ws.normal, sol.normal);
  summary.normal_iterations = summary.normal.iterations;

  TangentialProblem& tp = ws.tangential_problem;
  tp.mu = pb.mu;
  NormalSolution& next = ws.next_normal;
  // Pressure and tractions change little between outer iterations: later sub-solves start
  // from the previous ones.
  NormalOptions next_options = options.normal;
  next_options.warm_start = true;
  TangentialOptions tangential_options = options.tangential;

  for (int k = 1; k <= options.max_iterations; ++k) {
    const std::vector<double>& p = sol.normal.pressure;
    // Tangential problem with the pressure frozen; the pressure's own slip joins the rigid slip.
    tp.pressure = p;
    tp.wx = pb.wx;
    tp.wy = pb.wy;
    op.AddSlipFromPressure(p, tp.wx, tp.wy, ws);
    tangential_options.warm_start = options.tangential.warm_start || k > 1;
    summary.tangential =
        SolveTangential(op.rolling(), tp, tangential_options, ws.tangential, sol.tangential);
    summary.iterations = k;
    summary.tangential_iterations += summary.tangential.iterations;
    summary.status = Worse(summary.normal.status, summary.tangential.status);
    // K = 0: nothing couples back, this is the solution (bit for bit the uncoupled one).
    if (!op.coupled() || summary.normal.status == SolverStatus::kNoContact) break;

    double max_bound = 0.0, max_p = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      max_bound = std::max(max_bound, mu_at(i) * p[i]);
      max_p = std::max(max_p, p[i]);
    }
    const std::vector<double>& px = sol.tangential.px;
    const std::vector<double>& py = sol.tangential.py;
    summary.traction_change = k == 1            ? std::numeric_limits<double>::infinity()
                              : max_bound > 0.0 ? std::max(MaxAbsDifference(px, ws.previous_px),
                                                           MaxAbsDifference(py, ws.previous_py)) /
                                                      max_bound
                                                : 0.0;

    // Normal problem with the tractions frozen: their normal displacement adds to the
    // undeformed distance (Eq. 10b, e = h + u_n).
    ws.h = pb.h;
    op.AddNormalFromTractions(px, py, ws.h, ws);
    next.pressure = p;
    const NormalSummary next_summary =
        SolveNormal(op.normal(), ws.h, pb.load, next_options, ws.normal, next);
    summary.normal_iterations += next_summary.iterations;
    summary.pressure_change = max_p > 0.0 ? MaxAbsDifference(next.pressure, p) / max_p : 0.0;

    // Converged: the returned pair (p, p_t) has p_t solved for p exactly, and p reproduces
    // itself from p_t to within the tolerance.
    if (summary.pressure_change <= options.tolerance &&
        summary.traction_change <= options.tolerance) {
      break;
    }
    if (k == options.max_iterations) {
      summary.status = SolverStatus::kNotConverged;
      break;
    }
    ws.previous_px = px;
    ws.previous_py = py;
    std::swap(sol.normal, next);
    summary.normal = next_summary;
  }
  return summary;
}

}  // namespace wrc
