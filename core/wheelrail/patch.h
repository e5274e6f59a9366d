#pragma once
// Solution of one contact patch: reference, potential contact area, undeformed distance, rigid
// slip, normal and tangential problems, and the resulting forces (paper Fig. 3, steps 1–3).

#include <memory>
#include <vector>

#include "core/wheelrail/contact_search.h"
#include "wrc/core/wheelrail.h"

namespace wrc::wr {

/// What one patch keeps between the solves of a vertical force iteration (the same patch at
/// slightly different wheelset heights): the influence operators of its solve box, which are
/// reused while the box keeps its size, and the last solution as a warm start.
struct PatchCache {
  std::unique_ptr<FftInfluenceOperator> normal_operator;
  std::unique_ptr<SteadyRollingOperator> rolling_operator;
  NormalWorkspace normal_workspace;
  TangentialWorkspace tangential_workspace;
  /// The last converged solutions, each with the solve box (relative to its patch reference)
  /// it was found on.
  Grid normal_box, tangential_box;
  NormalSolution normal;
  TangentialSolution tangential;
  /// The pressure the tangential solution was found with (on tangential_box): its tractions are
  /// scaled by the change of pressure for the next warm start.
  std::vector<double> tangential_pressure;
  bool has_normal = false, has_tangential = false;
};

/// Everything a patch needs besides its extent.
struct PatchContext {
  const Case* c = nullptr;
  const PlacedRail* rail = nullptr;
  const PlacedWheel* wheel = nullptr;  ///< At the wheelset height being solved.
  const ContactSearch* search = nullptr;
  double dz = 0.0;  ///< Wheelset height relative to the search.
  double velocity = 0.0;
  CombinedElasticity material;
  const WheelRailOptions* options = nullptr;
  /// Solve the tangential problem (the case asks for it and this is not a normal-only pass of
  /// the vertical force iteration).
  bool tangential = true;
  /// Stage timings are added here (not owned).
  WheelRailTimings* timings = nullptr;
  /// Operators and warm starts carried over from the previous solve of this patch (not owned;
  /// null solves from scratch).
  PatchCache* cache = nullptr;
};

/// Solves one patch with the planar contact approach (paper §2.6, Table 1 methods 2–8).
PatchResult SolvePlanarPatch(const PatchContext& ctx, const PatchExtent& extent);

/// Solves one patch with the curved reference surface (paper §3).
PatchResult SolveCurvedPatch(const PatchContext& ctx, const PatchExtent& extent);

}  // namespace wrc::wr
