#include "wrc/core/normal_solver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <thread>
#include <utility>
#include <vector>

#include "tests/support/near.h"
#include "wrc/core/influence_operator.h"

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
      EXPECT_TRUE(test_support::AllNear(a, b, 1e-12 * test_support::LargestMagnitude(b)))
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

// A normal-only operator's workspace holds one spectrum, too few for the tangential block's
// product; the other way round it fits.
TEST(FftInfluenceOperator, WorkspaceFitsOnlyWhatItCanServe) {
  const Grid g{12, 10, 0.2, 0.2, 0.0, 0.0};
  const FftInfluenceOperator normal(g, Steel(), {InfluenceComponent::kNN});
  const FftInfluenceOperator tangential(
      g, Steel(), {InfluenceComponent::kXX, InfluenceComponent::kYY, InfluenceComponent::kXY});
  ConvolutionWorkspace small = normal.MakeWorkspace();
  EXPECT_TRUE(normal.Fits(small));
  EXPECT_FALSE(tangential.Fits(small));
  std::vector<double> p(g.size(), 1.0), ux(g.size()), uy(g.size());
  EXPECT_THROW(tangential.ApplyTangential(p.data(), p.data(), ux.data(), uy.data(), small),
               std::logic_error);
  EXPECT_TRUE(normal.Fits(tangential.MakeWorkspace()));
}

// The plan and the spectra are made at the first product or workspace, once, also when two
// threads ask at the same time: both get the dense operator's product.
TEST(FftInfluenceOperator, PreparesOnceOnFirstUseFromAnyThread) {
  const Grid g{24, 18, 0.2, 0.3, 0.0, 0.0};
  const FftInfluenceOperator fft(g, Steel(), {InfluenceComponent::kNN});
  const std::size_t points = fft.transform_points();  // known before any plan
  EXPECT_GE(points, 35u * 47u);                       // padded to 2n - 1 at least
  std::vector<double> in(g.size());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (double& v : in) v = uni(rng);
  std::vector<double> expected(g.size());
  DenseInfluenceOperator(g, Steel()).Apply(InfluenceComponent::kNN, in.data(), expected.data());
  std::vector<std::vector<double>> out(2, std::vector<double>(g.size()));
  std::vector<std::thread> threads;
  for (auto& o : out) {
    threads.emplace_back([&fft, &in, &o] {
      ConvolutionWorkspace ws = fft.MakeWorkspace();
      fft.Apply(InfluenceComponent::kNN, in.data(), o.data(), ws);
    });
  }
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(fft.transform_points(), points);
  const double scale = *std::max_element(expected.begin(), expected.end());
  for (const auto& o : out) {
    for (std::size_t i = 0; i < o.size(); ++i) EXPECT_NEAR(o[i], expected[i], 1e-12 * scale);
  }
}

// The stencil is an approximate inverse: convolved with the kernel it leaves a few % of the
// centre at the neighbouring offsets, where the kernel itself has 30–50 %. Square and elongated
// cells alike (the heavy-haul and Manchester grids are square; others need not be).
TEST(FftInfluenceOperator, LocalInverseIsAnApproximateInverse) {
  for (const auto& [dx, dy] : std::vector<std::pair<double, double>>{
           {0.4, 0.4}, {0.2, 0.4}, {0.4, 0.2}, {0.1, 0.4}, {0.5, 0.125}}) {
    const Grid g{24, 24, dx, dy, 0.0, 0.0};
    const FftInfluenceOperator op(g, Steel(), {InfluenceComponent::kNN});
    const std::optional<LocalInverseStencil> m = op.LocalInverse(InfluenceComponent::kNN);
    ASSERT_TRUE(m.has_value()) << dx << " x " << dy;
    const InfluenceCoefficients a(g, Steel(), InfluenceComponent::kNN);
    auto product = [&](int di, int dj) {  // (M ∗ A)(di, dj)
      double sum = 0.0;
      for (int k = -1; k <= 1; ++k) {
        for (int l = -1; l <= 1; ++l) {
          const double w = k == 0 && l == 0 ? m->centre
                           : l == 0         ? m->x
                           : k == 0         ? m->y
                                            : m->diagonal;
          sum += w * a.at(di - k, dj - l);
        }
      }
      return sum;
    };
    const double centre = product(0, 0);
    double worst = 0.0, kernel_neighbour = 0.0;
    for (int dj = -3; dj <= 3; ++dj) {
      for (int di = -3; di <= 3; ++di) {
        if (di == 0 && dj == 0) continue;
        worst = std::max(worst, std::fabs(product(di, dj)) / centre);
        if (std::abs(di) + std::abs(dj) == 1) {
          kernel_neighbour = std::max(kernel_neighbour, a.at(di, dj) / a.at(0, 0));
        }
      }
    }
    // Measured: 0.036 against 0.29 (square), 0.075 against 0.48 (aspect 4).
    EXPECT_LT(worst, 0.2 * kernel_neighbour) << dx << " x " << dy;
    EXPECT_LT(worst, 0.08) << dx << " x " << dy;
    // Mirror symmetry: swapping dx and dy swaps the x and y weights.
    const FftInfluenceOperator swapped(Grid{24, 24, dy, dx, 0.0, 0.0}, Steel(),
                                       {InfluenceComponent::kNN});
    const auto ms = swapped.LocalInverse(InfluenceComponent::kNN);
    ASSERT_TRUE(ms.has_value());
    EXPECT_NEAR(ms->x, m->y, 1e-12);
    EXPECT_NEAR(ms->y, m->x, 1e-12);
    EXPECT_NEAR(ms->diagonal, m->diagonal, 1e-12);
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

// At ~40 elements across the contact diameter pmax and approach within 1 % of Hertz.
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

// Two bumps 3 mm apart on one grid (the shape of a combined heavy-haul patch): the
// preconditioned CG reaches the same solution as the plain one, at the default tolerance within
// it of a 1e-13 solve, in fewer iterations; under approach and under force control.
std::vector<double> TwoBumps(const Grid& g) {
  std::vector<double> h(g.size());
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const double x = g.x(i), y = g.y(j);
      const double first = (x * x + 3.0 * y * y) / 920.0;
      const double second = 0.003 + (x * x + 0.5 * (y - 3.0) * (y - 3.0)) / 600.0;
      h[g.index(i, j)] = std::min(first, second);
    }
  }
  return h;
}

TEST(NormalSolver, PreconditionedSolveMatchesPlainSolve) {
  const Grid g = Grid::Covering(-3.0, 3.0, -3.0, 5.0, 0.1, 0.1);
  const FftInfluenceOperator op(g, Steel(), {InfluenceComponent::kNN});
  const std::vector<double> h = TwoBumps(g);
  for (const NormalLoad load : {NormalLoad::Approach(0.012), NormalLoad::Force(4000.0)}) {
    auto solve = [&](bool precondition, double tolerance, int* iterations) {
      NormalOptions options;
      options.precondition = precondition;
      options.deflate = false;  // DeflatedSolveMatchesPlainSolve
      options.tolerance = tolerance;
      NormalWorkspace ws;
      NormalSolution sol;
      const NormalSummary s = SolveNormal(op, h, load, options, ws, sol);
      EXPECT_EQ(s.status, SolverStatus::kConverged);
      if (iterations) *iterations = s.iterations;
      return sol;
    };
    const NormalSolution exact = solve(true, 1e-13, nullptr);
    const NormalSolution exact_plain = solve(false, 1e-13, nullptr);
    int plain_iterations = 0, iterations = 0;
    const NormalSolution plain = solve(false, 1e-8, &plain_iterations);
    const NormalSolution fast = solve(true, 1e-8, &iterations);
    double plain_error = 0.0, error = 0.0, agreement = 0.0;
    for (std::size_t i = 0; i < h.size(); ++i) {
      agreement = std::max(agreement, std::fabs(exact.pressure[i] - exact_plain.pressure[i]));
      plain_error = std::max(plain_error, std::fabs(plain.pressure[i] - exact.pressure[i]));
      error = std::max(error, std::fabs(fast.pressure[i] - exact.pressure[i]));
    }
    const bool force = load.kind == NormalLoad::Kind::kForce;
    EXPECT_GT(exact.n_contact, 100);
    EXPECT_LT(agreement, 1e-10 * exact.pmax) << force;
    EXPECT_LT(error, 1e-7 * exact.pmax) << force;
    EXPECT_LT(plain_error, 1e-7 * exact.pmax) << force;
    EXPECT_NEAR(fast.force, exact.force, 1e-8 * exact.force) << force;
    EXPECT_LT(iterations, 0.8 * plain_iterations)
        << force << ": " << iterations << " against " << plain_iterations;
  }
}

// The deflated last phase (approach control) reaches the solution of the active-set iteration
// alone, at the default tolerance within it of a 1e-13 solve, in fewer iterations. On a coarse
// and a fine grid of the two bumps (about 250 and 1000 elements in contact).
// A converged solve under approach control, with or without the deflated last phase.
NormalSolution SolveAtApproach(const FftInfluenceOperator& op, const std::vector<double>& h,
                               double approach, bool deflate, double tolerance,
                               int* iterations = nullptr) {
  NormalOptions options;
  options.deflate = deflate;
  options.tolerance = tolerance;
  NormalWorkspace ws;
  NormalSolution sol;
  const NormalSummary s = SolveNormal(op, h, NormalLoad::Approach(approach), options, ws, sol);
  EXPECT_EQ(s.status, SolverStatus::kConverged);
  if (iterations) *iterations = s.iterations;
  return sol;
}

TEST(NormalSolver, DeflatedSolveMatchesPlainSolve) {
  for (const double d : {0.1, 0.05}) {
    const Grid g = Grid::Covering(-3.0, 3.0, -3.0, 5.0, d, d);
    const FftInfluenceOperator op(g, Steel(), {InfluenceComponent::kNN});
    const std::vector<double> h = TwoBumps(g);
    auto solve = [&](bool deflate, double tolerance, int* iterations) {
      return SolveAtApproach(op, h, 0.012, deflate, tolerance, iterations);
    };
    const NormalSolution exact = solve(false, 1e-13, nullptr);
    int plain_iterations = 0, iterations = 0;
    const NormalSolution plain = solve(false, 1e-8, &plain_iterations);
    const NormalSolution deflated = solve(true, 1e-8, &iterations);
    double plain_error = 0.0, error = 0.0;
    for (std::size_t i = 0; i < h.size(); ++i) {
      plain_error = std::max(plain_error, std::fabs(plain.pressure[i] - exact.pressure[i]));
      error = std::max(error, std::fabs(deflated.pressure[i] - exact.pressure[i]));
    }
    EXPECT_GT(exact.n_contact, 200) << d;
    EXPECT_EQ(deflated.n_contact, exact.n_contact) << d;
    EXPECT_LT(error, 1e-7 * exact.pmax) << d;
    EXPECT_LT(plain_error, 1e-7 * exact.pmax) << d;
    EXPECT_NEAR(deflated.force, exact.force, 1e-8 * exact.force) << d;
    // Complementarity of the deflated result: no interpenetration anywhere.
    for (std::size_t i = 0; i < h.size(); ++i) {
      ASSERT_GE(deflated.deformed[i], -1e-8 * 0.012) << d << " " << i;
    }
    EXPECT_LT(iterations, plain_iterations) << d;
  }
}

// Two small contacts 10 mm apart in one long box, as on the combined heavy-haul patches: the
// deflated phase then sums its products over the contact set directly instead of by FFT
// (cheaper where the set is small against the padded grid) and refreshes the displacement once
// at the end. The result is the exact solution's, with open gaps everywhere else.
TEST(NormalSolver, DeflatedSolveOfASparseContactMatchesPlainSolve) {
  const Grid g = Grid::Covering(-3.0, 3.0, -3.0, 13.0, 0.1, 0.1);
  const FftInfluenceOperator op(g, Steel(), {InfluenceComponent::kNN});
  std::vector<double> h(g.size());
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const double x = g.x(i), y = g.y(j);
      h[g.index(i, j)] = std::min((x * x + 2.0 * y * y) / 400.0,
                                  0.001 + (2.0 * x * x + (y - 10.0) * (y - 10.0)) / 300.0);
    }
  }
  const NormalSolution exact = SolveAtApproach(op, h, 0.006, false, 1e-13);
  const NormalSolution deflated = SolveAtApproach(op, h, 0.006, true, 1e-8);
  ASSERT_GT(exact.n_contact, 200);
  ASSERT_LT(exact.n_contact, 1000);  // 1.4·n² < 0.7 of an FFT product: the direct way
  EXPECT_EQ(deflated.n_contact, exact.n_contact);
  double error = 0.0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    error = std::max(error, std::fabs(deflated.pressure[i] - exact.pressure[i]));
  }
  EXPECT_LT(error, 1e-7 * exact.pmax);
  EXPECT_NEAR(deflated.force, exact.force, 1e-8 * exact.force);
  for (std::size_t i = 0; i < h.size(); ++i) {
    // The refreshed displacement: deformed distance zero on the contact, open off it.
    if (deflated.pressure[i] > 0.0) {
      ASSERT_NEAR(deflated.deformed[i], 0.0, 1e-6 * 0.006) << i;
    } else {
      ASSERT_GE(deflated.deformed[i], -1e-8 * 0.006) << i;
    }
  }
}

// A warm start from a deeper approach carries pressure where the gap is now open for good
// (outside the interpenetration, which the solver no longer visits): the solution is still the
// cold one, to the tolerance.
TEST(NormalSolver, WarmStartFromADeeperApproachGivesTheColdSolution) {
  const Grid g = Grid::Covering(-2.0, 2.0, -2.0, 2.0, 0.1, 0.1);
  const FftInfluenceOperator op(g, Steel(), {InfluenceComponent::kNN});
  std::vector<double> h(g.size());
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) h[g.index(i, j)] = (g.x(i) * g.x(i) + g.y(j) * g.y(j)) / 920.0;
  }
  NormalWorkspace ws;
  NormalSolution warm, cold;
  NormalOptions options;
  ASSERT_EQ(SolveNormal(op, h, NormalLoad::Approach(0.004), options, ws, warm).status,
            SolverStatus::kConverged);
  options.warm_start = true;
  ASSERT_EQ(SolveNormal(op, h, NormalLoad::Approach(0.001), options, ws, warm).status,
            SolverStatus::kConverged);
  options.warm_start = false;
  ASSERT_EQ(SolveNormal(op, h, NormalLoad::Approach(0.001), options, ws, cold).status,
            SolverStatus::kConverged);
  EXPECT_EQ(warm.n_contact, cold.n_contact);
  for (std::size_t i = 0; i < h.size(); ++i) {
    ASSERT_NEAR(warm.pressure[i], cold.pressure[i], 1e-7 * cold.pmax) << i;
  }
  EXPECT_NEAR(warm.force, cold.force, 1e-8 * cold.force);
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
