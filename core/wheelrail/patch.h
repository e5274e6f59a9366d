#pragma once
// Solution of one contact patch: reference, potential contact area, undeformed distance, rigid
// slip, normal and tangential problems, and the resulting forces (paper Fig. 3, steps 1–3).

#include "core/wheelrail/contact_search.h"
#include "wrc/wheelrail.h"

namespace wrc::wr {

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
};

/// Solves one patch with the planar contact approach (paper §2.6, Table 1 methods 2–8).
PatchResult SolvePlanarPatch(const PatchContext& ctx, const PatchExtent& extent);

/// Solves one patch with the curved reference surface (paper §3).
PatchResult SolveCurvedPatch(const PatchContext& ctx, const PatchExtent& extent);

}  // namespace wrc::wr
