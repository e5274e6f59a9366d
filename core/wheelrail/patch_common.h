#pragma once
// Steps shared by the planar and curved patch solutions.

#include <vector>

#include "core/wheelrail/patch.h"

namespace wrc::wr {

/// Undeformed distance given to elements where wheel or rail is missing along the normal (the
/// line leaves a profile): far enough that such elements never carry pressure.
constexpr double kNoContactDistance = 1.0;

/// Contact reference of a patch (paper §2.6, Eq. 13/14, Table 1).
struct PatchReference {
  double s = 0.0;      ///< Rail arc length of the reference.
  double x = 0.0;      ///< Longitudinal position, mm.
  double angle = 0.0;  ///< Reference angle δ, rad.
};
PatchReference FindReference(const PatchContext& ctx, const PatchExtent& extent);

/// Grid of elements dx × ds with centres at multiples of dx, ds from the reference, covering
/// [x_min, x_max] × [s_min, s_max] (relative to the reference) plus one element on each side.
Grid PatchGrid(double dx, double ds, double x_min, double x_max, double s_min, double s_max);
/// PatchGrid with the case's grid.dx/grid.ds, refused (InputError naming the grid keys) before
/// anything is allocated when it would exceed WheelRailOptions::max_patch_elements.
Grid CheckedPatchGrid(const PatchContext& ctx, double x_min, double x_max, double s_min,
                      double s_max);

/// Solves the normal problem (approach 0: h holds the interpenetration) and, when the case
/// asks for it, the steady-rolling tangential problem; fills the fields and counts of result.
void SolveOnGrid(const PatchContext& ctx, const Grid& grid, const std::vector<double>& h,
                 const std::vector<double>& wx, const std::vector<double>& wy,
                 const std::vector<double>& mu, PatchResult& result);

/// Reference location outputs (track, rail and wheel coordinates, contact angle).
void FillReferenceOutputs(const PatchContext& ctx, const PatchReference& ref,
                          const Eigen::Vector3d& p_T, PatchResult& result);

/// Drops the per-element fields (when the caller did not ask to keep them).
void ClearFields(PatchResult& result);

}  // namespace wrc::wr
