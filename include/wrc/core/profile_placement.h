#pragma once
/// @file profile_placement.h
/// The undeformed wheel and rail of a wheel–rail case placed at a wheelset pose, as pictures and
/// checks need them: both surfaces in the track frame and the gap between them along the rail.
/// Poses are those of the right-side equivalent case (a left case is mirrored in y, as the
/// solver does).

#include <vector>

#include "wrc/core/case.h"

namespace wrc {

/// Wheelset pose relative to the track: lateral position and height (mm), roll and yaw (rad).
struct WheelsetPlacement {
  double y = 0.0, z = 0.0, roll = 0.0, yaw = 0.0;
};

/// The gap at one rail point: the smallest vertical distance over x between the undeformed
/// surfaces (negative where they interpenetrate), and where along x it is.
struct GapSample {
  double y = 0.0;    ///< rail point, track frame, mm
  double gap = 0.0;  ///< mm
  double x = 0.0;    ///< contact locus, mm
};

struct PlacedProfiles {
  std::vector<double> rail_y, rail_z;    ///< rail surface, track frame (z down), mm
  std::vector<double> wheel_y, wheel_z;  ///< wheel profile in the wheelset's principal plane
  std::vector<GapSample> gap;            ///< along the rail, where the wheel is above it
};

/// Surfaces sampled every `step` mm of arc length (at least 2 intervals each) and the gap along
/// the rail at the same step. Throws InputError for a profile that cannot be read.
PlacedProfiles PlaceProfiles(const Case& c, const WheelsetPlacement& pose, double step);

/// The wheelset height at which the profiles first touch at pose's y, roll and yaw (pose.z is
/// not used): the smallest gap at height 0. Infinity when the wheel is never above the rail.
double FirstContactHeight(const Case& c, const WheelsetPlacement& pose, double step);

/// Where the wheel first touches the rail as the wheelset is lowered at pose's y, roll and yaw
/// (pose.z is not used): the rigid contact point of the undeformed profiles.
struct RigidContact {
  bool found = false;   ///< False when the wheel is nowhere above the rail.
  double height = 0.0;  ///< Wheelset z of first touch, mm (z down).
  double rail_y = 0.0;  ///< The point on the rail, track frame, mm.
  double rail_z = 0.0;
  double contact_angle = 0.0;   ///< Rail inclination there, rad (CONTACT's convention).
  double wheel_y = 0.0;         ///< The point in wheel profile coordinates, mm.
  double rolling_radius = 0.0;  ///< Wheel radius there, mm.
  /// The point lies within a sampling step of either profile's end: the profiles end there,
  /// and the figures are those of their edges, not of a contact the profiles describe.
  bool at_profile_end = false;
};

/// The rigid contact at `pose`, the gap sampled every `step` mm of rail arc length and its
/// minimum placed between the samples by a parabola. Throws InputError for a profile that
/// cannot be read.
RigidContact RigidContactAt(const Case& c, const WheelsetPlacement& pose, double step);

/// The wheelset roll at lateral shift y at which both wheels touch their rails together, the
/// right wheel from `right`, the left from `left` as its right-side equivalent (at −y, −roll):
/// the first-touch heights equal, found by GSL's Brent solver to 1e-9 rad within ±50 mrad.
/// NaN when no roll in that range brings both wheels down together.
double WheelsetRollAt(const Case& right, const Case& left, double y, double step);

}  // namespace wrc
