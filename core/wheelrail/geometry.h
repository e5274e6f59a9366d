#pragma once
// Wheel and rail surfaces placed in the track frame (paper §3.1, step 0; CONTACT's user guide,
// "Track and roller geometry" and "Wheelset geometry & state").
//
// Frames (monogram notation): T track (x along the track, y lateral, z down), R rail profile,
// W wheelset (origin at the wheelset centre, y along the axle). All cases are solved as a right
// wheel on a right rail; a left case is mirrored in y before and after (as CONTACT does).

#include <Eigen/Dense>
#include <memory>
#include <optional>

#include "wrc/core/case.h"
#include "wrc/core/profile.h"

namespace wrc::wr {

/// The rail: prismatic, its profile rotated by the installation angle and shifted to its
/// position in the track frame: p_T = p_TRo_T + R_TR·p_R (in the y–z plane).
class PlacedRail {
 public:
  PlacedRail(Profile profile, const Track& track);
  PlacedRail(std::shared_ptr<const ProfileSpline> spline, const Track& track);

  const ProfileSpline& spline() const { return *spline_; }
  double length() const { return spline_->length(); }
  /// Rail origin in the track frame (y, z), mm.
  const Eigen::Vector2d& origin() const { return p_TRo_T_; }
  /// Installation rotation about x, rad (−cant for the right rail).
  double rotation() const { return rotation_; }

  /// Point of the rail surface at arc length s, in the track frame (y, z).
  Eigen::Vector2d PositionAt(double s) const;
  /// PositionAt for ascending arc lengths (ProfileSpline::PositionsAt).
  std::vector<Eigen::Vector2d> PositionsAt(const std::vector<double>& s) const;
  /// Unit tangent at s in the track frame, in the direction of increasing s (towards +y).
  Eigen::Vector2d TangentAt(double s) const;
  /// Surface inclination in the track frame, rad: atan of dz/dy (negative on the gauge face of
  /// the right rail), CONTACT's contact angle convention.
  double InclinationAt(double s) const;
  /// Rail profile coordinates of a track-frame point (y, z).
  Eigen::Vector2d ToRail(const Eigen::Vector2d& p_T) const;
  /// Arc length where the line p0 + t·n (y–z plane) crosses the rail surface, by Newton from
  /// s_guess; nullopt when it leaves the profile or does not converge.
  std::optional<double> IntersectLine(const Eigen::Vector2d& p0, const Eigen::Vector2d& n,
                                      double s_guess) const;

 private:
  std::shared_ptr<const ProfileSpline> spline_;
  double rotation_ = 0.0;
  Eigen::Matrix2d R_TR_;
  Eigen::Vector2d p_TRo_T_;
};

/// Pose and velocities of the wheelset relative to the track frame, which moves along the track
/// with the forward velocity.
struct WheelsetKinematics {
  double y = 0.0, z = 0.0, roll = 0.0, yaw = 0.0;  // mm, mm, rad, rad
  double velocity = 0.0;                           // forward velocity V, mm/s
  double omega = 0.0;                              // pitch rate about the axle, rad/s
  double vy = 0.0, vroll = 0.0, vyaw = 0.0;        // mm/s, rad/s, rad/s
};

/// The wheel: a body of revolution about the wheelset axle, its profile giving the radius
/// r(y_w) = r_nom + z_w(y_w) at axial position y_w from the profile origin, which sits at
/// [0, d_flng/2 − y_fbpos, r_nom] in the wheelset frame.
class PlacedWheel {
 public:
  /// The spline is shared: one wheel profile serves every pose of a sweep or an fz iteration.
  PlacedWheel(std::shared_ptr<const ProfileSpline> spline, const Wheelset& wheelset,
              const WheelsetKinematics& state);

  const ProfileSpline& spline() const { return *spline_; }
  const Eigen::Matrix3d& R_TW() const { return R_TW_; }
  /// Wheelset centre in the track frame.
  const Eigen::Vector3d& p_TWo_T() const { return p_TWo_T_; }
  double profile_offset() const { return profile_offset_; }
  double nominal_radius() const { return nominal_radius_; }

  /// Parameter t where the line p0 + t·d meets the lower wheel surface (Newton from t_guess);
  /// nullopt outside the profile or without convergence.
  std::optional<double> IntersectLine(const Eigen::Vector3d& p0, const Eigen::Vector3d& d,
                                      double t_guess) const;
  /// Lowest wheel surface point at track position (x, y): its z, or nullopt.
  std::optional<double> SurfaceZ(double x, double y) const;
  /// Wheel profile coordinates (y_w, z_w) of a track-frame point: axial position and radius
  /// minus r_nom.
  Eigen::Vector2d ToWheelProfile(const Eigen::Vector3d& p_T) const;
  /// Velocity of the wheel material point at p_T relative to the track frame, mm/s.
  Eigen::Vector3d MaterialVelocity(const Eigen::Vector3d& p_T) const;
  /// Angular velocity of the wheelset in the track frame, rad/s.
  const Eigen::Vector3d& AngularVelocity() const { return w_TW_T_; }

 private:
  // Radius and dr/dy_w at axial position y_w; nullopt outside the profile.
  std::optional<std::pair<double, double>> Radius(double y_w) const;

  std::shared_ptr<const ProfileSpline> spline_;
  double profile_offset_ = 0.0;
  double nominal_radius_ = 0.0;
  Eigen::Matrix3d R_TW_;
  Eigen::Vector3d p_TWo_T_;
  Eigen::Vector3d v_TWo_T_;
  Eigen::Vector3d w_TW_T_;
};

}  // namespace wrc::wr
