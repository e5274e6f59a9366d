#include "wrc/normal_solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "wrc/influence_operator.h"

namespace wrc {
namespace {

constexpr double kPi = 3.14159265358979323846;

CombinedElasticity Steel() { return CombinedElasticity::Identical({82000.0, 0.28}); }

// FFT convolution and dense products agree up to FFT round-off, which for these sizes is
// ~1e-15 relative to the largest term; 1e-12 leaves ample margin.
TEST(FftInfluenceOperator, EqualsDenseOperator) {
  const CombinedElasticity m = CombinedElasticity::FromBodies({82000.0, 0.28}, {70000.0, 0.33});
  for (const Grid g : {Grid{7, 5, 0.3, 0.2, -1.0, -0.5}, Grid{16, 9, 0.1, 0.25, 0.0, 0.0},
                       Grid{1, 6, 0.2, 0.2, 0.0, 0.0}}) {
    const std::vector<InfluenceComponent> all = {InfluenceComponent::kNN, InfluenceComponent::kXX,
                                                 InfluenceComponent::kYY, InfluenceComponent::kXY,
                                                 InfluenceComponent::kXN, InfluenceComponent::kNX};
    FftInfluenceOperator fft(g, m, all);
    DenseInfluenceOperator dense(g, m);
    ConvolutionWorkspace ws = fft.MakeWorkspace();
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    std::vector<double> in(g.size()), a(g.size()), b(g.size());
    for (double& v : in) v = uni(rng);
    for (InfluenceComponent c : all) {
      fft.Apply(c, in.data(), a.data(), ws);
      dense.Apply(c, in.data(), b.data());
      double scale = 0.0, err = 0.0;
      for (std::size_t i = 0; i < a.size(); ++i) {
        scale = std::max(scale, std::fabs(b[i]));
        err = std::max(err, std::fabs(a[i] - b[i]));
      }
      EXPECT_LE(err, 1e-12 * scale)
          << "component " << static_cast<int>(c) << " grid " << g.nx << "x" << g.ny;
    }
    // The tangential block equals the separate products.
    std::vector<double> in2(g.size()), ux(g.size()), uy(g.size()), t1(g.size()), t2(g.size());
    for (double& v : in2) v = uni(rng);
    fft.ApplyTangential(in.data(), in2.data(), ux.data(), uy.data(), ws);
    dense.Apply(InfluenceComponent::kXX, in.data(), t1.data());
    dense.Apply(InfluenceComponent::kXY, in2.data(), t2.data());
    for (std::size_t i = 0; i < ux.size(); ++i) EXPECT_NEAR(ux[i], t1[i] + t2[i], 1e-12 * 1e-3);
  }
}

struct HertzCircle {
  double a, p0, approach;
};
// Hertz for a sphere-like contact with h = (x² + y²)/(2R): a³ = 3FR/(4E*), δ = a²/R,
// p0 = 3F/(2πa²) (Johnson, Contact Mechanics, §4.2).
HertzCircle Hertz(double fn, double radius, double estar) {
  const double a = std::cbrt(3.0 * fn * radius / (4.0 * estar));
  return {a, 3.0 * fn / (2.0 * kPi * a * a), a * a / radius};
}

NormalSolution SolveCircle(double radius, double fn, int across, NormalSummary* summary,
                           NormalLoad::Kind kind = NormalLoad::Kind::kForce) {
  const CombinedElasticity m = Steel();
  const HertzCircle hz = Hertz(fn, radius, m.EffectiveModulus());
  const double d = 2.0 * hz.a / across;
  const Grid g = Grid::Covering(-1.3 * hz.a, 1.3 * hz.a, -1.3 * hz.a, 1.3 * hz.a, d, d);
  FftInfluenceOperator op(g, m, {InfluenceComponent::kNN});
  std::vector<double> h(g.size());
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      h[g.index(i, j)] = (g.x(i) * g.x(i) + g.y(j) * g.y(j)) / (2.0 * radius);
    }
  }
  NormalWorkspace ws;
  NormalSolution sol;
  const NormalLoad load =
      kind == NormalLoad::Kind::kForce ? NormalLoad::Force(fn) : NormalLoad::Approach(hz.approach);
  *summary = SolveNormal(op, h, load, NormalOptions{}, ws, sol);
  return sol;
}

// Issue 2: at ~40 elements across the contact diameter pmax and approach within 1 % of Hertz.
TEST(NormalSolver, HertzCircleAtFortyElements) {
  NormalSummary summary;
  const NormalSolution sol = SolveCircle(460.0, 10000.0, 40, &summary);
  const HertzCircle hz = Hertz(10000.0, 460.0, Steel().EffectiveModulus());
  ASSERT_EQ(summary.status, SolverStatus::kConverged) << summary.iterations;
  EXPECT_NEAR(sol.force, 10000.0, 1e-9 * 10000.0);
  EXPECT_NEAR(sol.pmax, hz.p0, 0.01 * hz.p0);
  EXPECT_NEAR(sol.approach, hz.approach, 0.01 * hz.approach);
  // Contact area πa² to within the ring of boundary elements: 2πa·d/πa² = 2d/a = 10 %.
  const double area = sol.n_contact * std::pow(2.0 * hz.a / 40, 2);
  EXPECT_NEAR(area, kPi * hz.a * hz.a, 0.1 * kPi * hz.a * hz.a);
}

TEST(NormalSolver, HertzCircleConvergesUnderRefinement) {
  // The pmax error falls about fourfold per halving (second order) once the grid resolves the
  // contact; the approach error changes sign near 10 elements, so it is bounded, not ranked.
  const HertzCircle hz = Hertz(10000.0, 460.0, Steel().EffectiveModulus());
  double previous_error = 1e9;
  for (int across : {20, 40, 80}) {
    NormalSummary summary;
    const NormalSolution sol = SolveCircle(460.0, 10000.0, across, &summary);
    ASSERT_EQ(summary.status, SolverStatus::kConverged);
    const double error = std::fabs(sol.pmax - hz.p0) / hz.p0;
    EXPECT_LT(error, 0.5 * previous_error) << across;
    previous_error = error;
    EXPECT_LT(std::fabs(sol.approach - hz.approach) / hz.approach, 1e-3) << across;
  }
  EXPECT_LT(previous_error, 3e-4);
}

TEST(NormalSolver, PrescribedApproachGivesHertzForce) {
  NormalSummary summary;
  const NormalSolution sol = SolveCircle(460.0, 10000.0, 40, &summary, NormalLoad::Kind::kApproach);
  ASSERT_EQ(summary.status, SolverStatus::kConverged) << summary.iterations;
  // F ∝ δ^{3/2}: a 1 % approach error would be a 1.5 % force error; we ask for 1.5 %.
  EXPECT_NEAR(sol.force, 10000.0, 0.015 * 10000.0);
  // Complementarity: no interpenetration anywhere, no gap under pressure, to the solver's
  // relative tolerance (NormalOptions::tolerance = 1e-8).
  for (std::size_t i = 0; i < sol.pressure.size(); ++i) {
    EXPECT_GE(sol.deformed[i], -1e-8 * sol.approach);
    if (sol.pressure[i] > 0.0) {
      EXPECT_NEAR(sol.deformed[i], 0.0, 1e-6 * sol.approach);
    }
  }
}

TEST(NormalSolver, NoContactWhenApproachIsNegative) {
  const Grid g{8, 8, 0.5, 0.5, -2.0, -2.0};
  FftInfluenceOperator op(g, Steel(), {InfluenceComponent::kNN});
  std::vector<double> h(g.size(), 0.01);
  NormalWorkspace ws;
  NormalSolution sol;
  const NormalSummary s = SolveNormal(op, h, NormalLoad::Approach(0.005), NormalOptions{}, ws, sol);
  EXPECT_EQ(s.status, SolverStatus::kNoContact);
  EXPECT_EQ(sol.force, 0.0);
  EXPECT_EQ(sol.n_contact, 0);
}

TEST(NormalSolver, RejectsBadInput) {
  const Grid g{4, 4, 0.5, 0.5, 0.0, 0.0};
  FftInfluenceOperator op(g, Steel(), {InfluenceComponent::kNN});
  NormalWorkspace ws;
  NormalSolution sol;
  std::vector<double> h(g.size(), 0.0);
  EXPECT_THROW(SolveNormal(op, h, NormalLoad::Force(-1.0), {}, ws, sol), std::invalid_argument);
  h[3] = std::nan("");
  EXPECT_THROW(SolveNormal(op, h, NormalLoad::Force(1.0), {}, ws, sol), std::invalid_argument);
  h.resize(3);
  EXPECT_THROW(SolveNormal(op, h, NormalLoad::Force(1.0), {}, ws, sol), std::invalid_argument);
}

}  // namespace
}  // namespace wrc
