#pragma once
// Contact search (paper §3.1, Fig. 4b): the vertical gap between wheel and rail along the rail
// profile, at the contact locus (for each lateral position the x where the gap is smallest,
// shifted by yaw), and the interpenetration regions grouped into contact patches.

#include <limits>
#include <vector>

#include "core/wheelrail/geometry.h"

namespace wrc::wr {

/// The gap along the rail profile at the contact locus, for one wheelset pose. Moving the
/// wheelset down by dz lowers every vertical gap by exactly dz, so one search serves every z
/// of an fz iteration (gap_at(dz) = gap − dz).
struct LocusSample {
  double s = 0.0;           ///< Rail arc length, mm.
  double y = 0.0, z = 0.0;  ///< Rail surface point, track frame.
  double alpha = 0.0;       ///< Rail inclination, rad (0 where the wheel was not located).
  double x = 0.0;           ///< Contact locus: x of the smallest gap, mm.
  double gap = 0.0;         ///< Smallest vertical gap at this lateral position, mm.
  double curvature = 0.0;   ///< d²gap/dx² at the locus, 1/mm (> 0).
  bool valid = false;       ///< The wheel lies above this rail point and comes within the
                            ///< search's reach of the rail (gap = +inf otherwise).
  bool off_wheel = false;   ///< Searched, but the wheel profile does not lie above this point.
};

struct ContactSearch {
  std::vector<LocusSample> samples;  ///< At equal arc-length steps along the rail.
  double step = 0.0;                 ///< Arc-length step, mm.
};

/// Samples the rail at `step` and finds the contact locus against the wheel wherever the gap
/// comes within `reach` (mm) of the smallest gap and below `z_limit` (the largest wheelset
/// shift that will be asked for, when known); samples further away are left invalid.
ContactSearch SearchContact(const PlacedRail& rail, const PlacedWheel& wheel, double step,
                            double reach, double z_limit = std::numeric_limits<double>::infinity());

/// A contact patch: a run of samples [first, last] (indices into the search) that holds one or
/// more interpenetration regions closer than the combine distance.
struct PatchExtent {
  int first = 0, last = 0;
  double x_min = 0.0, x_max = 0.0;  ///< Longitudinal extent of the interpenetration, mm.
};

/// The interpenetration regions at wheelset shift dz (gap − dz < 0), combined when closer than
/// combine_distance (distance between their ends in the y–z plane, or their x extents),
/// ordered field side first (descending rail arc length).
std::vector<PatchExtent> FindPatches(const ContactSearch& search, double dz,
                                     double combine_distance);

/// Interpenetration depth ∫ w(g) dx across x at one sample, for g = gap − dz < 0 with the
/// locus parabola g(x) = g0 + ½κ(x − x0)²: linear weights give (4/3)·a·|g0| and quadratic
/// weights (16/15)·a·g0², with a = √(2|g0|/κ) the half-length (paper Eq. 13/14 along x).
double LocusWeight(const LocusSample& sample, double dz, bool quadratic);
/// Half-length a of the interpenetration across x at one sample (0 without interpenetration).
double LocusHalfLength(const LocusSample& sample, double dz);

}  // namespace wrc::wr
