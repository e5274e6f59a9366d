// Cost of one normal solve (SolveNormal, force prescribed) for the Hertzian circle of a
// 460 mm wheel on a plane (a1 = b1 = 1/920 mm⁻¹, fn = 10 kN, steel), on square potential-contact
// grids of 32², 64², 128² and 256² elements. The contact diameter is 80 % of the grid width at
// every size, so the element count in contact grows with the grid (about half of it).
//
// Timed: SolveNormal alone, from a cold (uniform) start each time. Not timed: the FFT
// operator's kernel spectra and the workspace, which a sweep builds once per grid.
// Counters: iterations per solve, elements in contact.
//
//   build-h5/bench/bench_normal --benchmark_min_time=0.2

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <iostream>
#include <vector>

#include "wrc/core/grid.h"
#include "wrc/core/hertz.h"
#include "wrc/core/influence_operator.h"
#include "wrc/core/material.h"
#include "wrc/core/normal_solver.h"

namespace {

constexpr double kCurvature = 1.0 / (2.0 * 460.0);  // a1 = b1, 1/mm: wheel radius 460 mm.
constexpr double kNormalForce = 10000.0;            // N.
constexpr double kContactShareOfWidth = 0.8;

wrc::CombinedElasticity Steel() { return wrc::CombinedElasticity::Identical({82000.0, 0.28}); }

// The n × n grid centred on the origin whose width is the Hertz diameter / 0.8.
wrc::Grid HertzGrid(int n) {
  const wrc::HertzContact hertz(kCurvature, kCurvature, Steel().EffectiveModulus());
  const double width = 2.0 * hertz.ForForce(kNormalForce).semi_axis_x / kContactShareOfWidth;
  const double cell = width / n;
  return wrc::Grid::Covering(-0.5 * width, 0.5 * width, -0.5 * width, 0.5 * width, cell, cell);
}

void BM_NormalSolveHertzCircle(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const wrc::Grid grid = HertzGrid(n);
  const wrc::FftInfluenceOperator op(grid, Steel(), {wrc::InfluenceComponent::kNN});
  std::vector<double> h(grid.size());
  for (int j = 0; j < grid.ny; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      h[grid.index(i, j)] = kCurvature * (grid.x(i) * grid.x(i) + grid.y(j) * grid.y(j));
    }
  }
  wrc::NormalWorkspace workspace;
  wrc::NormalSolution solution;
  wrc::NormalSummary summary;
  for (auto _ : state) {
    summary = SolveNormal(op, h, wrc::NormalLoad::Force(kNormalForce), wrc::NormalOptions{},
                          workspace, solution);
    benchmark::DoNotOptimize(solution.pressure.data());
  }
  if (summary.status != wrc::SolverStatus::kConverged) {
    // A figure for a solve that stopped at its iteration limit would mean nothing.
    std::cerr << "bench_normal: solve on " << n << "² did not converge\n";
    std::abort();
  }
  state.counters["iterations"] = summary.iterations;
  state.counters["n_contact"] = solution.n_contact;
}

BENCHMARK(BM_NormalSolveHertzCircle)
    ->Arg(32)
    ->Arg(64)
    ->Arg(128)
    ->Arg(256)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
