#pragma once
// Error-driven node placement (`[table.refine]`): the grid passes of a refinement and what they
// share with a plain `wrc generate` run.
//
// A refinement starts from the scene's axes and repeats: solve the whole tensor grid (a plain
// grid run, journaled and resumable, points of earlier passes taken over), judge it at random
// states against the stop rule (the quantile of the error within the target), measure each
// axis interval's interpolation error with exact solves at its midpoint (the other coordinates
// drawn uniformly over their ranges and moved to the nearest node, so that the samples weigh the
// state space by volume, as a uniform verification does), and split the intervals whose error
// exceeds the target, those that mend the most first, within the point budget. Nodes are only ever
// added, so every node of a pass is a node of the next; the midpoint samples of a split interval
// are nodes of the next pass too. The final grid is written as one ordinary table whose refine_*
// attributes say how it was made.

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "generator/cluster.h"
#include "generator/table_data.h"
#include "wrc/generator/generator.h"

namespace wrc::gen {

/// What a refinement asks of one grid run beyond a plain `wrc generate`.
struct GridHooks {
  /// Rank 0: a point already known from an earlier pass (true, with its result), taken over
  /// and journaled instead of solved.
  std::function<bool(std::uint64_t point, PointResult* result)> known;
  /// False: stop once every point is in the journal (kept, not removed) and hand the data to
  /// data_out; no table file is written.
  bool write_table = true;
  TableData* data_out = nullptr;
  /// Root attributes written into the table after the standard ones.
  std::vector<std::pair<std::string, std::string>> attributes;
  /// Stop on SIGINT/SIGTERM handled by the caller's InterruptHandlers.
  bool watch_signals = false;
};

/// Worker threads of this process for these options (0: the cores shared out among the local
/// ranks).
int ThreadsFor(const GenerateOptions& options, const Cluster* cluster);

/// One tensor-grid run (GenerateTable without refinement). Collective under MPI.
GenerateSummary GenerateGrid(const Scene& scene, const GenerateOptions& options, Cluster* cluster,
                             const GridHooks& hooks);

/// GenerateTable for a scene with `refine` set. Collective under MPI: rank 0 decides the
/// nodes and sends every pass's axes to the other ranks, which solve their share of each grid.
GenerateSummary RefineTable(const Scene& scene, const GenerateOptions& options, Cluster* cluster);

/// An exact solve at the midpoint of interval `interval` of axis `axis`, the other coordinates
/// at the nodes `nodes` (nodes[axis] is the interval's lower node).
struct RefineSample {
  std::size_t axis = 0, interval = 0;
  std::vector<std::size_t> nodes;
  std::vector<double> point;
};

/// The midpoint samples of one pass: settings.samples per interval that may still be split,
/// the other coordinates drawn uniformly over their ranges (seeded by settings.seed and the
/// pass) and moved to the nearest node.
std::vector<RefineSample> DrawRefineSamples(const std::vector<SceneAxis>& axes,
                                            const RefineSettings& settings, int pass);

/// The states whose exact solves give the solver's slopes for `[table.refine.slope]`: for each
/// targeted axis in dimension order, the slope state minus and plus k steps, k = 1 … window/step.
std::vector<std::vector<double>> SlopeProbes(const RefineSettings::Slope& slope);

/// The table's slope error per axis at the slope state: the least-squares slope through the
/// window's samples (with one sample a side, the central difference) of the multilinear
/// interpolant against that of the exact `probes` (SlopeProbes order), worst over the refined
/// outputs, in units of the slope target. 0 for untargeted axes, NaN where a probe did not
/// solve.
std::vector<double> SlopeErrors(const Scene& scene, const std::vector<SceneAxis>& axes,
                                const TableData& data, const std::vector<PointResult>& probes);

/// What one pass decides from its grid and its samples' exact results.
struct RefineDecision {
  std::vector<SceneAxis> next;       ///< The axes of the next pass (equal: stop).
  std::size_t above_target = 0;      ///< Intervals whose sampled midpoint error exceeds the target.
  std::size_t refused = 0;           ///< Of those, intervals left unsplit by the point budget.
  double worst = 0.0;                ///< Largest sampled midpoint error, in units of the target.
  std::vector<double> slope_errors;  ///< SlopeErrors() of this grid (empty without a target).
};
/// `probes`: the exact solves at SlopeProbes() when the scene has a slope target. An axis whose
/// slope misses it gets as nodes, on each side of the state, the sample where the table strays
/// furthest from the solver (with one sample a side: the state ± step, so that the table's
/// central difference there reads solved values only). These nodes come first; the interval
/// splits get the point budget they leave.
/// `max_growth`: the most the splits may grow the grid in this pass (0: the refinement's
/// default, a doubling).
RefineDecision DecideRefinement(const Scene& scene, const std::vector<SceneAxis>& axes,
                                const TableData& data, const std::vector<RefineSample>& samples,
                                const std::vector<PointResult>& results,
                                const std::vector<PointResult>& probes = {},
                                double max_growth = 0.0);

/// Multilinear interpolation of output `k` of a finished grid at `point` (inside the axes'
/// ranges; clamped otherwise). NaN when a corner with non-zero weight is NaN.
double InterpolateLinear(const std::vector<SceneAxis>& axes, const TableData& data, std::size_t k,
                         const std::vector<double>& point);

}  // namespace wrc::gen
