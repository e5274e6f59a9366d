// `wrc generate --estimate`: what a run will cost, from a few solves of its grid.

#include <algorithm>
#include <limits>
#include <random>

#include "wrc/core/scene.h"
#include "wrc/generator/generator.h"

namespace wrc {

GenerateEstimate EstimateGeneration(const Scene& scene, int runs, int run_length,
                                    std::uint64_t seed) {
  GenerateEstimate estimate;
  estimate.start_points = scene.PointCount();
  estimate.max_points = scene.refine ? scene.refine->max_points : estimate.start_points;
  const std::vector<std::size_t> shape = scene.Shape();
  if (shape.empty()) return estimate;
  std::mt19937_64 rng(seed);
  double total = 0.0;
  for (int run = 0; run < runs; ++run) {
    // A place on the grid; the run goes along the last axis, as the generator's segments do,
    // so that the warm start of z and the segment's cache count as they will.
    std::vector<std::size_t> indices(shape.size());
    for (std::size_t a = 0; a < shape.size(); ++a) {
      indices[a] = std::uniform_int_distribution<std::size_t>(0, shape[a] - 1)(rng);
    }
    const std::size_t last = shape.size() - 1;
    const std::size_t length =
        std::min<std::size_t>(static_cast<std::size_t>(run_length), shape[last]);
    indices[last] = std::min(indices[last], shape[last] - length);
    double z_guess = std::numeric_limits<double>::quiet_NaN();
    WheelRailCache cache;
    for (std::size_t k = 0; k < length; ++k, ++indices[last]) {
      const PointResult r = SolveScenePoint(scene, indices, z_guess, &cache);
      z_guess = r.z;
      ++estimate.solves;
      if (r.status == PointStatus::kNotConverged || r.status == PointStatus::kError) {
        ++estimate.failed;
      }
      total += r.solve_time_s;
      estimate.max_solve_s = std::max(estimate.max_solve_s, static_cast<double>(r.solve_time_s));
    }
  }
  estimate.mean_solve_s = estimate.solves > 0 ? total / estimate.solves : 0.0;
  return estimate;
}

}  // namespace wrc
