// Cost of one steady-rolling tangential solve (SolveTangential) for the Hertzian circle of a
// 460 mm wheel on a plane (a1 = b1 = 1/920 mm⁻¹, fn = 10 kN, μ = 0.3, steel), on square
// potential-contact grids of 32², 64² and 128² elements, the contact diameter being 80 % of the
// grid width. Longitudinal creepage only, at half the saturation creepage, so that the contact
// is in partial slip: adhesion at the leading edge, slip at the trailing edge.
//
// Timed: SolveTangential alone, from a cold start each time. Not timed: the normal solve (its
// pressures are the input) and the steady-rolling operator (influence coefficients and FFT
// spectra), which a sweep builds once per grid.
// Counters: iterations (Gauss–Seidel sweeps), elements in contact and in slip, fx / (μ·fn).
//
//   build-h5/bench/bench_tangential --benchmark_min_time=0.2

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <iostream>
#include <vector>

#include "wrc/core/grid.h"
#include "wrc/core/hertz.h"
#include "wrc/core/influence_operator.h"
#include "wrc/core/material.h"
#include "wrc/core/normal_solver.h"
#include "wrc/core/tangential_solver.h"

namespace {

constexpr double kCurvature = 1.0 / (2.0 * 460.0);  // a1 = b1, 1/mm: wheel radius 460 mm.
constexpr double kNormalForce = 10000.0;            // N.
constexpr double kFriction = 0.3;
constexpr double kContactShareOfWidth = 0.8;
// Kalker's creepage coefficient C11 for a circular contact, interpolated linearly in ν between
// his tabulated 4.12 (ν = 0.25) and 5.20 (ν = 0.5) to ν = 0.28.
constexpr double kKalkerC11 = 4.12 + (0.28 - 0.25) / (0.5 - 0.25) * (5.20 - 4.12);

wrc::CombinedElasticity Steel() { return wrc::CombinedElasticity::Identical({82000.0, 0.28}); }

struct RollingInput {
  wrc::Grid grid;
  double creepage = 0.0;
  std::vector<double> pressure;
};

// Grid of n × n elements around the Hertz circle and its normal pressures. The creepage is half
// of the Johnson–Vermeulen saturation creepage ξ_s = 3·μ·fn / (G·a·b·C11), where their cubic
// law F = μ·fn·[1 − (1 − ξ/ξ_s)³] leaves Kalker's linear theory and reaches full slip.
RollingInput PrepareRolling(int n) {
  const wrc::CombinedElasticity steel = Steel();
  const wrc::HertzSolution hertz =
      wrc::HertzContact(kCurvature, kCurvature, steel.EffectiveModulus()).ForForce(kNormalForce);
  const double width = 2.0 * hertz.semi_axis_x / kContactShareOfWidth;
  const double cell = width / n;
  RollingInput input;
  input.grid =
      wrc::Grid::Covering(-0.5 * width, 0.5 * width, -0.5 * width, 0.5 * width, cell, cell);
  const double saturation =
      3.0 * kFriction * kNormalForce /
      (steel.shear_modulus * hertz.semi_axis_x * hertz.semi_axis_y * kKalkerC11);
  input.creepage = 0.5 * saturation;

  const wrc::Grid& g = input.grid;
  std::vector<double> h(g.size());
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      h[g.index(i, j)] = kCurvature * (g.x(i) * g.x(i) + g.y(j) * g.y(j));
    }
  }
  const wrc::FftInfluenceOperator op(g, steel, {wrc::InfluenceComponent::kNN});
  wrc::NormalWorkspace workspace;
  wrc::NormalSolution solution;
  const wrc::NormalSummary summary = SolveNormal(op, h, wrc::NormalLoad::Force(kNormalForce),
                                                 wrc::NormalOptions{}, workspace, solution);
  if (summary.status != wrc::SolverStatus::kConverged) {
    std::cerr << "bench_tangential: normal solve on " << n << "² did not converge\n";
    std::abort();
  }
  input.pressure = std::move(solution.pressure);
  return input;
}

void BM_TangentialSolveSteadyRolling(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const RollingInput input = PrepareRolling(n);
  const wrc::SteadyRollingOperator op(input.grid, Steel());
  wrc::TangentialProblem problem;
  problem.pressure = input.pressure;
  problem.mu = {kFriction};
  problem.wx.assign(input.grid.size(), input.creepage);
  problem.wy.assign(input.grid.size(), 0.0);
  wrc::TangentialWorkspace workspace;
  wrc::TangentialSolution solution;
  wrc::TangentialSummary summary;
  for (auto _ : state) {
    summary = SolveTangential(op, problem, wrc::TangentialOptions{}, workspace, solution);
    benchmark::DoNotOptimize(solution.px.data());
  }
  if (summary.status != wrc::SolverStatus::kConverged) {
    std::cerr << "bench_tangential: solve on " << n << "² did not converge\n";
    std::abort();
  }
  state.counters["iterations"] = summary.iterations;
  state.counters["n_contact"] = solution.n_adhesion + solution.n_slip;
  state.counters["n_slip"] = solution.n_slip;
  state.counters["fx_over_mu_fn"] = solution.fx / (kFriction * kNormalForce);
  state.counters["cksi"] = input.creepage;
}

BENCHMARK(BM_TangentialSolveSteadyRolling)
    ->Arg(32)
    ->Arg(64)
    ->Arg(128)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
