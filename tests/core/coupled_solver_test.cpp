// Normal–tangential coupling of dissimilar bodies (K != 0) by the Panagiotopoulos process.

#include "wrc/core/coupled_solver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "wrc/core/case.h"
#include "wrc/core/halfspace.h"
#include "wrc/core/influence.h"

namespace wrc {
namespace {

constexpr double kA1 = 0.001087;  // a wheel of radius 460 mm
constexpr double kForce = 10000.0;

struct Contact {
  Grid grid;
  CoupledProblem problem;
};

// Circular Hertz contact under 10 kN on the square [−half, half]² with longitudinal creepage.
Contact Circle(double half, double dx, double cksi, double mu) {
  Contact s;
  s.grid = Grid::Covering(-half, half, -half, half, dx, dx);
  const Grid& g = s.grid;
  s.problem.h.resize(g.size());
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      s.problem.h[g.index(i, j)] = kA1 * (g.x(i) * g.x(i) + g.y(j) * g.y(j));
    }
  }
  s.problem.wx.assign(g.size(), cksi);
  s.problem.wy.assign(g.size(), 0.0);
  s.problem.load = NormalLoad::Force(kForce);
  s.problem.mu = {mu};
  return s;
}

// Combined G = 40 000 N/mm², ν = 0.28 (contact radius ≈ 4 mm) with a chosen K, so that only
// the coupling changes between solves.
CombinedElasticity WithKappa(double kappa) { return {40000.0, 0.28, kappa}; }
Contact CircleFor40k(double cksi, double mu) { return Circle(5.1, 0.3, cksi, mu); }

CoupledSummary Solve(const Contact& s, const CombinedElasticity& m, CoupledSolution& sol,
                     const CoupledOptions& options = {}) {
  const CoupledContactOperator op(s.grid, m);
  CoupledWorkspace ws;
  return SolveCoupled(op, s.problem, options, ws, sol);
}

double MaxAbs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::fabs(x));
  return m;
}

// (1) Identical bodies: K = 0 exactly, no coupling operators, and one outer iteration that is
// bit for bit the plain normal solve followed by the plain tangential solve.
TEST(CoupledSolver, IdenticalBodiesGiveTheUncoupledSolveInOneIteration) {
  const CombinedElasticity m = CombinedElasticity::Identical({82000.0, 0.28});
  ASSERT_EQ(m.kappa, 0.0);
  const Contact s = Circle(4.2, 0.3, 0.001, 0.3);
  const CoupledContactOperator op(s.grid, m);
  EXPECT_FALSE(op.coupled());
  CoupledWorkspace ws;
  CoupledSolution sol;
  const CoupledSummary summary = SolveCoupled(op, s.problem, {}, ws, sol);
  EXPECT_EQ(summary.status, SolverStatus::kConverged);
  EXPECT_EQ(summary.iterations, 1);

  NormalWorkspace nws;
  NormalSolution ns;
  SolveNormal(op.normal(), s.problem.h, s.problem.load, {}, nws, ns);
  TangentialProblem tp{ns.pressure, s.problem.mu, s.problem.wx, s.problem.wy};
  TangentialWorkspace tws;
  TangentialSolution ts;
  const TangentialSummary t = SolveTangential(op.rolling(), tp, {}, tws, ts);
  EXPECT_EQ(sol.normal.pressure, ns.pressure);
  EXPECT_EQ(sol.normal.approach, ns.approach);
  EXPECT_EQ(sol.tangential.px, ts.px);
  EXPECT_EQ(sol.tangential.py, ts.py);
  EXPECT_EQ(sol.tangential.sx, ts.sx);
  EXPECT_EQ(summary.normal_iterations, summary.normal.iterations);
  EXPECT_EQ(summary.tangential_iterations, t.iterations);
}

// The FFT products against direct sums of the element kernels. y-components come from the
// x-kernels on the transposed grid: kYN(X, Y; hx, hy) = kXN(Y, X; hy, hx), likewise kNY.
TEST(CoupledSolver, CouplingProductsMatchTheKernels) {
  const Grid g{5, 4, 0.3, 0.2, -0.6, -0.3};
  const CombinedElasticity m{60000.0, 0.3, 0.2};
  const CoupledContactOperator op(g, m);
  ASSERT_TRUE(op.coupled());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  std::vector<double> p(g.size()), px(g.size()), py(g.size());
  for (std::size_t i = 0; i < g.size(); ++i) {
    p[i] = 500.0 * (1.0 + uni(rng));
    px[i] = 100.0 * uni(rng);
    py[i] = 100.0 * uni(rng);
  }
  CoupledWorkspace ws;
  std::vector<double> sx(g.size(), 0.0), sy(g.size(), 0.0), un(g.size(), 0.0);
  op.AddSlipFromPressure(p, sx, sy, ws);
  op.AddNormalFromTractions(px, py, un, ws);

  const double hx = 0.5 * g.dx, hy = 0.5 * g.dy;
  using C = InfluenceComponent;
  // Displacements at (x, y) by the grid's tractions.
  auto displacement = [&](double x, double y, C c, bool turned, const std::vector<double>& t) {
    double u = 0.0;
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        const double X = x - g.x(i), Y = y - g.y(j);
        u += (turned ? RectangleInfluence(c, m, Y, X, hy, hx)
                     : RectangleInfluence(c, m, X, Y, hx, hy)) *
             t[g.index(i, j)];
      }
    }
    return u;
  };
  double scale = 0.0;
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t I = g.index(i, j);
      const double x = g.x(i), y = g.y(j);
      // Steady rolling: s = (u(x) − u(x + δq))/δq, with u(x + δq) beyond the leading edge too.
      const double ex =
          (displacement(x, y, C::kXN, false, p) - displacement(x + g.dx, y, C::kXN, false, p)) /
          g.dx;
      const double ey =
          (displacement(x, y, C::kXN, true, p) - displacement(x + g.dx, y, C::kXN, true, p)) / g.dx;
      const double en =
          displacement(x, y, C::kNX, false, px) + displacement(x, y, C::kNX, true, py);
      scale = std::max({scale, std::fabs(ex), std::fabs(ey)});
      EXPECT_NEAR(sx[I], ex, 1e-10 * std::fabs(ex) + 1e-14) << i << ", " << j;
      EXPECT_NEAR(sy[I], ey, 1e-10 * std::fabs(ey) + 1e-14) << i << ", " << j;
      EXPECT_NEAR(un[I], en, 1e-10 * MaxAbs(un)) << i << ", " << j;
    }
  }
  EXPECT_GT(scale, 0.0);
}

// (2) Steel on a much softer body (K ≈ −0.25): converges in a few outer iterations, the
// solution is finite, satisfies the load and the Coulomb bound, and differs from the
// uncoupled one.
TEST(CoupledSolver, DissimilarBodiesConverge) {
  const CombinedElasticity m = CombinedElasticity::FromBodies({82000.0, 0.28}, {8200.0, 0.2});
  ASSERT_NEAR(m.kappa, -0.253, 0.001);
  const Contact s = Circle(7.2, 0.48, 0.001, 0.3);  // Hertz radius ≈ 5.7 mm
  CoupledSolution sol;
  const CoupledSummary summary = Solve(s, m, sol);
  ASSERT_EQ(summary.status, SolverStatus::kConverged);
  EXPECT_GT(summary.iterations, 1);
  EXPECT_LT(summary.iterations, 20);
  EXPECT_LE(summary.pressure_change, CoupledOptions{}.tolerance);
  EXPECT_LE(summary.traction_change, CoupledOptions{}.tolerance);

  const Grid& g = s.grid;
  const NormalSolution& ns = sol.normal;
  const TangentialSolution& ts = sol.tangential;
  double fn = 0.0, fx = 0.0, fy = 0.0;
  for (std::size_t i = 0; i < g.size(); ++i) {
    ASSERT_TRUE(std::isfinite(ns.pressure[i]) && std::isfinite(ts.px[i]) &&
                std::isfinite(ts.py[i]));
    fn += ns.pressure[i] * g.element_area();
    fx += ts.px[i] * g.element_area();
    fy += ts.py[i] * g.element_area();
    // Coulomb (Eq. 12d–e) with the returned pressure.
    EXPECT_LE(std::hypot(ts.px[i], ts.py[i]), 0.3 * ns.pressure[i] * (1.0 + 1e-12) + 1e-12);
  }
  EXPECT_NEAR(fn, kForce, 1e-9 * kForce);
  EXPECT_NEAR(ts.fx, fx, 1e-9 * kForce);
  EXPECT_NEAR(ts.fy, fy, 1e-9 * kForce);
  EXPECT_LT(std::hypot(fx, fy), 0.3 * kForce);
  // The pressure's slip from the coupling is even in y: no lateral force.
  EXPECT_LT(std::fabs(fy), 1e-4 * 0.3 * kForce);

  CombinedElasticity uncoupled = m;
  uncoupled.kappa = 0.0;
  CoupledSolution plain;
  Solve(s, uncoupled, plain);
  EXPECT_GT(std::fabs(ts.fx - plain.tangential.fx), 0.01 * std::fabs(plain.tangential.fx));
}

// Free rolling (no creepage) of dissimilar bodies. The x-slip caused by the pressure,
// −∂u_x/∂x, is even in x: under K > 0 surface points move towards the load, so u_x falls along
// x inside the contact and the slip acts like a positive creepage, opposed by a force Fx < 0
// (the effect of Bentall & Johnson's dissimilar rollers). It is even in y too, whereas the
// y-slip is odd in y: p_y is odd in y, Fy = 0 while p_y itself is not zero. (A static
// compression would give tractions odd in x and Fx = 0; steady rolling convects them.)
// Swapping the bodies (K → −K) leaves the pressure and negates the tractions.
TEST(CoupledSolver, FreeRollingOfDissimilarBodies) {
  const Contact s = CircleFor40k(0.0, 0.3);
  const Grid& g = s.grid;
  CoupledSolution pos, neg;
  ASSERT_EQ(Solve(s, WithKappa(0.2), pos).status, SolverStatus::kConverged);
  ASSERT_EQ(Solve(s, WithKappa(-0.2), neg).status, SolverStatus::kConverged);
  const double bound = 0.3 * pos.normal.pmax;
  const TangentialSolution& t = pos.tangential;
  EXPECT_LT(t.fx, -0.05 * 0.3 * kForce);
  EXPECT_GT(MaxAbs(t.py), 0.05 * bound);
  double sum_abs_py = 0.0;
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t I = g.index(i, j), M = g.index(i, g.ny - 1 - j);
      EXPECT_NEAR(t.py[I], -t.py[M], 1e-4 * bound);
      EXPECT_NEAR(t.px[I], t.px[M], 1e-4 * bound);
      sum_abs_py += std::fabs(t.py[I]) * g.element_area();
    }
  }
  EXPECT_LT(std::fabs(t.fy), 1e-4 * sum_abs_py);
  for (std::size_t I = 0; I < g.size(); ++I) {
    EXPECT_NEAR(neg.normal.pressure[I], pos.normal.pressure[I], 1e-4 * pos.normal.pmax);
    EXPECT_NEAR(neg.tangential.px[I], -t.px[I], 1e-4 * bound);
    EXPECT_NEAR(neg.tangential.py[I], -t.py[I], 1e-4 * bound);
  }
}

// (2) The coupling's share of Fx vanishes with K, linearly for small K.
TEST(CoupledSolver, CouplingEffectVanishesWithKappa) {
  const Contact s = CircleFor40k(0.001, 0.3);
  CoupledSolution sol;
  Solve(s, WithKappa(0.0), sol);
  const double fx0 = sol.tangential.fx;
  double previous = 0.0;
  for (double kappa : {0.04, 0.02, 0.01}) {
    ASSERT_EQ(Solve(s, WithKappa(kappa), sol).status, SolverStatus::kConverged) << kappa;
    const double delta = sol.tangential.fx - fx0;
    EXPECT_LT(delta, 0.0) << "K > 0 adds a positive creepage";
    if (previous != 0.0) {
      EXPECT_NEAR(delta / previous, 0.5, 0.1) << kappa;
    }
    previous = delta;
  }
  EXPECT_LT(std::fabs(previous), 0.05 * std::fabs(fx0));
}

// Non-convergence is a status with the last iterate, not an exception.
TEST(CoupledSolver, IterationLimitIsReportedAsStatus) {
  const Contact s = CircleFor40k(0.001, 0.3);
  CoupledOptions options;
  options.max_iterations = 2;
  CoupledSolution sol;
  const CoupledSummary summary = Solve(s, WithKappa(0.3), sol, options);
  EXPECT_EQ(summary.status, SolverStatus::kNotConverged);
  EXPECT_EQ(summary.iterations, 2);
  EXPECT_GT(summary.pressure_change, options.tolerance);
  EXPECT_TRUE(std::isfinite(sol.tangential.fx));
  EXPECT_NEAR(sol.normal.force, kForce, 1e-9 * kForce);
}

TEST(CoupledSolver, RejectsBadInput) {
  Contact s = CircleFor40k(0.001, 0.3);
  CoupledSolution sol;
  s.problem.wx.pop_back();
  EXPECT_THROW(Solve(s, WithKappa(0.1), sol), std::invalid_argument);
  s = CircleFor40k(0.001, 0.3);
  CoupledOptions options;
  options.tolerance = 0.0;
  EXPECT_THROW(Solve(s, WithKappa(0.1), sol, options), std::invalid_argument);
}

// A half-space case file with different rail and wheel materials is solved with coupling.
TEST(CoupledSolver, HalfspaceCaseWithDissimilarMaterials) {
  const Case c = ParseCase(R"(
[problem]
type = "halfspace"
[geometry]
a1 = 0.001087
b1 = 0.001087
[material]
poisson = [0.28, 0.2]
shear_modulus = [82000.0, 8200.0]
[friction]
mu = 0.3
[grid]
dx = 0.48
dy = 0.48
[state]
fn = 10000.0
cksi = 0.001
ceta = 0.0005
cphi = 0.0
)",
                           ".", "dissimilar.toml");
  const HalfspaceResult r = SolveHalfspace(c);
  ASSERT_EQ(r.status, SolverStatus::kConverged);
  ASSERT_TRUE(r.tangential_solved);
  EXPECT_NEAR(r.fn, kForce, 1e-6 * kForce);

  // The same problem through SolveCoupled, with and without K.
  const CombinedElasticity m = CombinedElasticity::FromBodies(c.rail_material, c.wheel_material);
  const Grid& g = r.grid;
  Contact s;
  s.grid = g;
  s.problem.h = r.h;
  s.problem.wx.assign(g.size(), 0.001);
  s.problem.wy.assign(g.size(), 0.0005);
  s.problem.load = NormalLoad::Force(kForce);
  s.problem.mu = {0.3};
  CoupledSolution coupled, plain;
  Solve(s, m, coupled);
  EXPECT_EQ(r.fx, coupled.tangential.fx);
  EXPECT_EQ(r.fy, coupled.tangential.fy);
  EXPECT_EQ(r.pressure, coupled.normal.pressure);
  CombinedElasticity uncoupled = m;
  uncoupled.kappa = 0.0;
  Solve(s, uncoupled, plain);
  EXPECT_GT(std::fabs(r.fx - plain.tangential.fx), 0.01 * std::fabs(plain.tangential.fx));
}

}  // namespace
}  // namespace wrc
