#include "wrc/core/tangential_solver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "wrc/core/normal_solver.h"

namespace wrc {
namespace {

CombinedElasticity Steel() { return CombinedElasticity::Identical({82000.0, 0.28}); }

struct Strip {
  Grid grid;
  std::vector<double> pressure;
};

// Normal solution for h = a1·x² + b1·y² on the given grid and force.
Strip SolveNormalOn(const Grid& g, double a1, double b1, double fn) {
  FftInfluenceOperator op(g, Steel(), {InfluenceComponent::kNN});
  std::vector<double> h(g.size());
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) h[g.index(i, j)] = a1 * g.x(i) * g.x(i) + b1 * g.y(j) * g.y(j);
  }
  NormalWorkspace ws;
  NormalSolution sol;
  const NormalSummary s = SolveNormal(op, h, NormalLoad::Force(fn), {}, ws, sol);
  EXPECT_EQ(s.status, SolverStatus::kConverged);
  return {g, sol.pressure};
}

// The problem of a strip rolling with creepages (cksi, ceta) everywhere and friction mu.
TangentialProblem UniformCreepage(const Strip& strip, double mu, double cksi, double ceta) {
  TangentialProblem pb;
  pb.pressure = strip.pressure;
  pb.mu = {mu};
  pb.wx.assign(strip.grid.size(), cksi);
  pb.wy.assign(strip.grid.size(), ceta);
  return pb;
}

TangentialSolution Roll(const Strip& strip, double mu, double cksi, double ceta,
                        TangentialSummary* summary) {
  const SteadyRollingOperator op(strip.grid, Steel());
  const TangentialProblem pb = UniformCreepage(strip, mu, cksi, ceta);
  TangentialWorkspace ws;
  TangentialSolution sol;
  *summary = SolveTangential(op, pb, {}, ws, sol);
  return sol;
}

// At large creepage the whole contact slips, |F_t| = μ·F_n to 1e-6 relative, and the
// force is opposite to the rigid slip (Eq. 12e with s ≈ w).
TEST(TangentialSolver, FullSlipSaturatesOppositeToRigidSlip) {
  const Grid g = Grid::Covering(-4.0, 4.0, -4.0, 4.0, 0.25, 0.25);
  const Strip strip = SolveNormalOn(g, 0.001087, 0.001087, 10000.0);
  TangentialSummary summary;
  const double cksi = 0.3, ceta = -0.4;  // ~100x the saturation creepage
  const TangentialSolution sol = Roll(strip, 0.3, cksi, ceta, &summary);
  ASSERT_EQ(summary.status, SolverStatus::kConverged);
  const double ft = std::hypot(sol.fx, sol.fy);
  EXPECT_NEAR(ft, 0.3 * 10000.0, 1e-6 * 3000.0);
  EXPECT_NEAR(sol.fx / ft, -cksi / std::hypot(cksi, ceta), 1e-3);
  EXPECT_NEAR(sol.fy / ft, -ceta / std::hypot(cksi, ceta), 1e-3);
  EXPECT_EQ(sol.n_adhesion, 0);
}

TEST(TangentialSolver, ZeroFrictionGivesZeroTractions) {
  const Grid g = Grid::Covering(-4.0, 4.0, -4.0, 4.0, 0.5, 0.5);
  const Strip strip = SolveNormalOn(g, 0.001087, 0.001087, 10000.0);
  TangentialSummary summary;
  const TangentialSolution sol = Roll(strip, 0.0, 0.001, 0.0, &summary);
  EXPECT_EQ(summary.status, SolverStatus::kConverged);
  EXPECT_EQ(sol.fx, 0.0);
  EXPECT_EQ(sol.fy, 0.0);
}

// Carter (1926): in 2-D rolling with creepage ξ, the adhesion zone is [a − 2c, a] at the
// leading edge with c = a(1 − κ), κ = |ξ|R/(μa), and F = −μP·(1 − (1 − κ)²) per unit length.
// A long strip (h independent of y) approximates the 2-D problem in its middle row.
TEST(TangentialSolver, CarterTwoDimensionalRolling) {
  const double radius = 460.0, a1 = 1.0 / (2.0 * radius), mu = 0.3;
  const double dx = 0.05;
  const Grid g = Grid::Covering(-3.0, 3.0, -15.0, 15.0, dx, 1.0);
  const Strip strip = SolveNormalOn(g, a1, 0.0, 30.0 * 1000.0);  // ~1 kN/mm
  const int mid = g.ny / 2;
  double load = 0.0;
  int first = -1, last = -1;
  for (int i = 0; i < g.nx; ++i) {
    const double p = strip.pressure[g.index(i, mid)];
    load += p * dx;
    if (p > 0.0) {
      if (first < 0) first = i;
      last = i;
    }
  }
  // Half-width of the middle row's contact from its line load (2-D Hertz: a² = 4PR/(πE*)).
  const double a = std::sqrt(4.0 * load * radius / (3.14159265358979 * Steel().EffectiveModulus()));
  ASSERT_NEAR(2.0 * a, (last - first + 1) * dx, 2.0 * dx);
  for (double kappa : {0.25, 0.5, 0.75}) {
    const double cksi = kappa * mu * a / radius;
    TangentialSummary summary;
    const TangentialSolution sol = Roll(strip, mu, cksi, 0.0, &summary);
    ASSERT_EQ(summary.status, SolverStatus::kConverged) << kappa;
    double force = 0.0;
    for (int i = 0; i < g.nx; ++i) force += sol.px[g.index(i, mid)] * dx;
    const double carter = -mu * load * (1.0 - (1.0 - kappa) * (1.0 - kappa));
    // The solver's promise is 1 % of the analytic force.
    EXPECT_NEAR(force, carter, 0.01 * std::fabs(carter)) << "kappa " << kappa;
  }
}

// Anderson acceleration changes the path, not the answer: on a Hertzian circle in partial slip
// (creepage and spin), the accelerated and the plain Gauss–Seidel solutions agree to the
// solver's tolerance, and the accelerated one takes fewer sweeps (34 against 25 when written).
// Each solve stops when a sweep changes no traction by more than 1e-7·μ·pmax; at the plain
// sweep's contraction (~0.7) the remaining error is a few times that, so 1e-5·μ·pmax per
// element and 1e-6 of μ·Fn in the forces leave room for both errors.
TEST(TangentialSolver, AccelerationKeepsTheSolutionAndSavesSweeps) {
  const Grid g = Grid::Covering(-4.0, 4.0, -4.0, 4.0, 0.2, 0.2);
  const double fn = 10000.0, mu = 0.3;
  const Strip strip = SolveNormalOn(g, 0.001087, 0.001087, fn);
  const SteadyRollingOperator op(g, Steel());
  TangentialProblem pb;
  pb.pressure = strip.pressure;
  pb.mu = {mu};
  pb.wx.resize(g.size());
  pb.wy.resize(g.size());
  const double cksi = 0.0008, ceta = -0.0004, cphi = 0.0005;  // spin in 1/mm
  double pmax = 0.0;
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      pb.wx[g.index(i, j)] = cksi - cphi * g.y(j);
      pb.wy[g.index(i, j)] = ceta + cphi * g.x(i);
      pmax = std::max(pmax, strip.pressure[g.index(i, j)]);
    }
  }
  TangentialSolution plain, accelerated;
  TangentialWorkspace ws;
  TangentialOptions options;
  options.acceleration_depth = 0;
  const TangentialSummary s_plain = SolveTangential(op, pb, options, ws, plain);
  options.acceleration_depth = 8;
  const TangentialSummary s_fast = SolveTangential(op, pb, options, ws, accelerated);
  ASSERT_EQ(s_plain.status, SolverStatus::kConverged);
  ASSERT_EQ(s_fast.status, SolverStatus::kConverged);
  EXPECT_GT(plain.n_adhesion, 0);
  EXPECT_GT(plain.n_slip, 0);
  EXPECT_LT(s_fast.iterations, s_plain.iterations);
  for (std::size_t k = 0; k < g.size(); ++k) {
    ASSERT_NEAR(accelerated.px[k], plain.px[k], 1e-5 * mu * pmax) << k;
    ASSERT_NEAR(accelerated.py[k], plain.py[k], 1e-5 * mu * pmax) << k;
  }
  EXPECT_NEAR(accelerated.fx, plain.fx, 1e-6 * mu * fn);
  EXPECT_NEAR(accelerated.fy, plain.fy, 1e-6 * mu * fn);
  EXPECT_NEAR(accelerated.mz, plain.mz, 1e-6 * mu * fn * 4.0);  // lever arm up to the 4 mm grid
}

// Sweeps that keep every slip current by direct updates (no FFT product per sweep; chosen when
// the contact is small against its box, here ~200 elements in a 32 x 32 grid) give the
// solution of sweeps that refresh the slips by FFT and correct only the 8 rows after an update
// directly (the contact is 16 rows tall, so far rows lag a sweep), to the solver's tolerance
// (see AccelerationKeepsTheSolutionAndSavesSweeps for the bounds), in full and partial slip.
TEST(TangentialSolver, DirectSlipUpdatesKeepTheSolution) {
  const Grid g = Grid::Covering(-4.0, 4.0, -4.0, 4.0, 0.25, 0.25);
  const double fn = 3000.0, mu = 0.3;
  const Strip strip = SolveNormalOn(g, 0.001087, 0.001087, fn);
  const SteadyRollingOperator op(g, Steel());
  double pmax = 0.0;
  for (double p : strip.pressure) pmax = std::max(pmax, p);
  for (const double creepage : {0.05, 0.0004}) {  // full slip, partial slip
    const TangentialProblem pb = UniformCreepage(strip, mu, creepage, -0.5 * creepage);
    TangentialSolution by_fft, direct;
    TangentialWorkspace ws;
    TangentialOptions options;
    options.acceleration_depth = 0;  // plain sweeps: the direct mode is used throughout
    options.direct_refresh = false;
    ASSERT_EQ(SolveTangential(op, pb, options, ws, by_fft).status, SolverStatus::kConverged);
    options.direct_refresh = true;
    ASSERT_EQ(SolveTangential(op, pb, options, ws, direct).status, SolverStatus::kConverged);
    for (std::size_t k = 0; k < g.size(); ++k) {
      ASSERT_NEAR(direct.px[k], by_fft.px[k], 1e-5 * mu * pmax) << creepage << " " << k;
      ASSERT_NEAR(direct.py[k], by_fft.py[k], 1e-5 * mu * pmax) << creepage << " " << k;
    }
    EXPECT_NEAR(direct.fx, by_fft.fx, 1e-6 * mu * fn) << creepage;
    EXPECT_NEAR(direct.fy, by_fft.fy, 1e-6 * mu * fn) << creepage;
  }
}

// Partial slip on a contact ~60 rows tall, too large for direct slip updates, so that every
// sweep starts from an FFT product, with Anderson mixing: it converges in a few dozen sweeps
// (39 measured). Letting only the next 8 rows take an update directly while mixing, as the
// full-slip sweeps do, stalled the combination: 561 sweeps here, and 24 -> 323 on Manchester
// at 300 kN.
TEST(TangentialSolver, TallPartialSlipContactConvergesWithProductsPerSweep) {
  const Grid g = Grid::Covering(-4.0, 4.0, -4.0, 4.0, 0.125, 0.125);
  const double fn = 60000.0, mu = 0.3;
  const Strip strip = SolveNormalOn(g, 0.001087, 0.001087, fn);
  const SteadyRollingOperator op(g, Steel());
  const TangentialProblem pb = UniformCreepage(strip, mu, 0.0004, -0.0002);
  int rows = 0;
  for (int j = 0; j < g.ny; ++j) {
    bool any = false;
    for (int i = 0; i < g.nx; ++i) any = any || strip.pressure[g.index(i, j)] > 0.0;
    rows += any;
  }
  ASSERT_GT(rows, 40);
  TangentialWorkspace ws;
  TangentialSolution sol;
  const TangentialSummary s = SolveTangential(op, pb, {}, ws, sol);
  ASSERT_EQ(s.status, SolverStatus::kConverged);
  EXPECT_GT(sol.n_adhesion, 0);
  EXPECT_GT(sol.n_slip, 0);
  EXPECT_LE(s.iterations, 60);
}

// Without the final product the tractions, forces and states are the same, and the slips in
// contact are those of the last sweep: in partial slip within the tolerance's reach of the
// fresh product's (a traction change below 1e-7·μ·p moves the slip by the elastic compliance,
// ~1e-7 of the creepage here).
TEST(TangentialSolver, SkippingTheFinalProductKeepsTheSolution) {
  const Grid g = Grid::Covering(-4.0, 4.0, -4.0, 4.0, 0.2, 0.2);
  const double fn = 10000.0, mu = 0.3;
  const Strip strip = SolveNormalOn(g, 0.001087, 0.001087, fn);
  const SteadyRollingOperator op(g, Steel());
  const TangentialProblem pb = UniformCreepage(strip, mu, 0.0008, -0.0004);
  TangentialWorkspace ws;
  TangentialOptions options;
  TangentialSolution fresh, last_sweep;
  ASSERT_EQ(SolveTangential(op, pb, options, ws, fresh).status, SolverStatus::kConverged);
  options.final_slip = false;
  ASSERT_EQ(SolveTangential(op, pb, options, ws, last_sweep).status, SolverStatus::kConverged);
  EXPECT_GT(fresh.n_adhesion, 0);
  EXPECT_EQ(last_sweep.fx, fresh.fx);
  EXPECT_EQ(last_sweep.fy, fresh.fy);
  EXPECT_EQ(last_sweep.state, fresh.state);
  for (std::size_t k = 0; k < g.size(); ++k) {
    EXPECT_EQ(last_sweep.px[k], fresh.px[k]);
    if (fresh.state[k] != ElementState::kExterior) {
      ASSERT_NEAR(last_sweep.sx[k], fresh.sx[k], 1e-6 * 0.0008) << k;
      ASSERT_NEAR(last_sweep.sy[k], fresh.sy[k], 1e-6 * 0.0008) << k;
    }
  }
}

TEST(TangentialSolver, RejectsBadInput) {
  const Grid g{4, 4, 0.5, 0.5, 0.0, 0.0};
  const SteadyRollingOperator op(g, Steel());
  TangentialProblem pb;
  pb.pressure.assign(g.size(), 1.0);
  pb.wx.assign(g.size(), 0.0);
  pb.wy.assign(g.size(), 0.0);
  pb.mu = {-0.1};
  TangentialWorkspace ws;
  TangentialSolution sol;
  EXPECT_THROW(SolveTangential(op, pb, {}, ws, sol), std::invalid_argument);
  pb.mu = {0.3};
  pb.wx[2] = std::nan("");
  EXPECT_THROW(SolveTangential(op, pb, {}, ws, sol), std::invalid_argument);
  // Dissimilar bodies are accepted (the coupling enters through SolveCoupled).
  EXPECT_NO_THROW(
      SteadyRollingOperator(g, CombinedElasticity::FromBodies({82000.0, 0.28}, {70000.0, 0.33})));
}

}  // namespace
}  // namespace wrc
