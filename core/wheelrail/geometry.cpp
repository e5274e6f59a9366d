#include "core/wheelrail/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "wrc/core/errors.h"

namespace wrc::wr {
namespace {

Eigen::Matrix2d RotationYZ(double angle) {
  // Rotation about the x axis (right-hand rule) acting on (y, z).
  Eigen::Matrix2d r;
  r << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  return r;
}

Eigen::Vector2d ToEigen(const ProfileVector& v) { return {v.y, v.z}; }

// Arc-length samples fine enough to locate extremes and crossings of a profile: 0.05 mm is
// below any element size used and far below the profiles' radii of curvature (> 5 mm).
constexpr double kScanStep = 0.05;

}  // namespace

PlacedRail::PlacedRail(Profile profile, const Track& track)
    : PlacedRail(std::make_shared<const ProfileSpline>(profile), track) {}

PlacedRail::PlacedRail(std::shared_ptr<const ProfileSpline> spline, const Track& track)
    : spline_(std::move(spline)) {
  rotation_ = -track.cant;  // the right rail leans towards the track centre
  R_TR_ = RotationYZ(rotation_);
  if (track.absolute_placement()) {
    p_TRo_T_ = {track.rail_y, track.rail_z};
    return;
  }
  // Gauge point computation: after the rotation, shift the rail up until its highest point
  // touches the track plane (z = 0) and sideways until its inner face, at gauge_height below
  // the track plane, lies at gauge_width/2.
  const int n = std::max(2, static_cast<int>(std::ceil(spline_->length() / kScanStep)));
  std::vector<double> s_scan(n + 1), z_scan(n + 1);  // the rotated profile's z at the scan
  for (int k = 0; k <= n; ++k) s_scan[k] = spline_->length() * k / n;
  const std::vector<ProfileVector> scan = spline_->PositionsAt(s_scan);
  double zmin = std::numeric_limits<double>::infinity();
  double y_top = 0.0;
  for (int k = 0; k <= n; ++k) {
    const Eigen::Vector2d rotated = R_TR_ * ToEigen(scan[k]);
    z_scan[k] = rotated(1);
    if (z_scan[k] < zmin) y_top = rotated(0);
    zmin = std::min(zmin, z_scan[k]);
  }
  const double z_shift = -zmin;
  double y_gauge = std::numeric_limits<double>::infinity();
  auto height = [&](double s) {
    return (R_TR_ * ToEigen(spline_->PositionAt(s)))(1) + z_shift - track.gauge_height;
  };
  for (int k = 0; k < n; ++k) {
    double a = spline_->length() * k / n, b = spline_->length() * (k + 1) / n;
    double fa = z_scan[k] + z_shift - track.gauge_height;
    const double fb = z_scan[k + 1] + z_shift - track.gauge_height;
    if ((fa > 0.0) == (fb > 0.0)) continue;
    for (int it = 0; it < 60; ++it) {  // bisection to 1e-18 of the step: exact enough
      const double m = 0.5 * (a + b), fm = height(m);
      if ((fm > 0.0) == (fa > 0.0)) {
        a = m;
        fa = fm;
      } else {
        b = m;
      }
    }
    y_gauge = std::min(y_gauge, (R_TR_ * ToEigen(spline_->PositionAt(0.5 * (a + b))))(0));
  }
  if (!std::isfinite(y_gauge)) {
    throw InputError("rail profile " + spline_->source() + " does not reach the gauge height " +
                     FormatNumber(track.gauge_height) + " mm below its top: set " +
                     "track.gauge_height <= 0 and place the rail with rail_y/rail_z");
  }
  // The gauge face belongs on the track-centre side of the top. Reaching the gauge height only
  // on the field side means the profile is mirrored (a MiniProf rail read without mirror_y):
  // placing it would put the field side against the flange and give a plausible-looking but
  // wrong contact.
  if (y_gauge > y_top) {
    // An upside-down rail also fails here; its own doubt then names the key to change.
    std::string fix;
    for (const std::string& doubt : spline_->orientation_doubts()) fix += "; " + doubt;
    if (fix.empty()) {
      fix =
          "; the profile looks mirrored in y: set rail.mirror_y = true (MiniProf rail files "
          "usually need it) or rail.mirror_y = \"auto\"";
    }
    throw InputError("rail profile " + spline_->source() + " reaches the gauge height " +
                     FormatNumber(track.gauge_height) +
                     " mm below its top only on its field side (larger y)" + fix);
  }
  p_TRo_T_ = {0.5 * track.gauge_width - y_gauge, z_shift};
}

Eigen::Vector2d PlacedRail::PositionAt(double s) const {
  return p_TRo_T_ + R_TR_ * ToEigen(spline_->PositionAt(s));
}

std::vector<Eigen::Vector2d> PlacedRail::PositionsAt(const std::vector<double>& s) const {
  const std::vector<ProfileVector> local = spline_->PositionsAt(s);
  std::vector<Eigen::Vector2d> out(local.size());
  for (std::size_t k = 0; k < local.size(); ++k) out[k] = p_TRo_T_ + R_TR_ * ToEigen(local[k]);
  return out;
}

Eigen::Vector2d PlacedRail::TangentAt(double s) const {
  return R_TR_ * ToEigen(spline_->TangentAt(s));
}

double PlacedRail::InclinationAt(double s) const {
  const Eigen::Vector2d t = TangentAt(s);
  return std::atan(t(1) / t(0));
}

Eigen::Vector2d PlacedRail::ToRail(const Eigen::Vector2d& p_T) const {
  return R_TR_.transpose() * (p_T - p_TRo_T_);
}

std::optional<double> PlacedRail::IntersectLine(const Eigen::Vector2d& p0, const Eigen::Vector2d& n,
                                                double s_guess) const {
  // f(s) = (P(s) − p0) × n = 0, Newton with f'(s) = t(s) × n. A start or a step that is not a
  // number (a guess off the profile's y range) ends it without an intersection, as one that
  // leaves the profile does.
  if (!std::isfinite(s_guess)) return std::nullopt;
  double s = std::clamp(s_guess, 0.0, spline_->length());
  for (int it = 0; it < 50; ++it) {
    const Eigen::Vector2d d = PositionAt(s) - p0;
    const Eigen::Vector2d t = TangentAt(s);
    const double f = d(0) * n(1) - d(1) * n(0);
    const double df = t(0) * n(1) - t(1) * n(0);
    if (std::fabs(df) < 1e-12) return std::nullopt;
    const double step = -f / df;
    s += step;
    if (!(s >= 0.0 && s <= spline_->length())) return std::nullopt;
    if (std::fabs(step) < 1e-11) return s;
  }
  return std::nullopt;
}

PlacedWheel::PlacedWheel(std::shared_ptr<const ProfileSpline> spline, const Wheelset& wheelset,
                         const WheelsetKinematics& state)
    : spline_(std::move(spline)) {
  profile_offset_ = 0.5 * wheelset.flange_back_distance - wheelset.flange_back_position;
  nominal_radius_ = wheelset.nominal_radius;
  // Roll about the track x axis, then yaw about the rolled vertical axis (CONTACT's order).
  const Eigen::Matrix3d roll = Eigen::AngleAxisd(state.roll, Eigen::Vector3d::UnitX()).matrix();
  const Eigen::Matrix3d yaw = Eigen::AngleAxisd(state.yaw, Eigen::Vector3d::UnitZ()).matrix();
  R_TW_ = roll * yaw;
  p_TWo_T_ = {0.0, state.y, state.z - nominal_radius_};
  v_TWo_T_ = {0.0, state.vy, 0.0};
  w_TW_T_ = state.vroll * Eigen::Vector3d::UnitX() +
            state.vyaw * (roll * Eigen::Vector3d::UnitZ()) +
            state.omega * (R_TW_ * Eigen::Vector3d::UnitY());
}

std::optional<std::pair<double, double>> PlacedWheel::Radius(double y_w) const {
  const ProfileHeight h = spline_->ZAtY(y_w);
  if (!h.found()) return std::nullopt;
  return std::make_pair(nominal_radius_ + h.z, h.dz_dy);
}

std::optional<double> PlacedWheel::IntersectLine(const Eigen::Vector3d& p0,
                                                 const Eigen::Vector3d& d, double t_guess) const {
  // In wheelset coordinates q(t) = a + t·b; on the surface where the distance to the axle,
  // ρ = |(q_x, q_z)|, equals r(q_y − offset), on the lower half (q_z > 0).
  const Eigen::Vector3d a = R_TW_.transpose() * (p0 - p_TWo_T_);
  const Eigen::Vector3d b = R_TW_.transpose() * d;
  double t = t_guess;
  for (int it = 0; it < 50; ++it) {
    const Eigen::Vector3d q = a + t * b;
    const auto r = Radius(q(1) - profile_offset_);
    if (!r || q(2) <= 0.0) return std::nullopt;
    // Distances of ~500 mm: no overflow, so the plain root (std::hypot's rescaling is ~20 ns).
    const double rho = std::sqrt(q(0) * q(0) + q(2) * q(2));
    const double f = rho - r->first;
    const double df = (q(0) * b(0) + q(2) * b(2)) / rho - r->second * b(1);
    if (std::fabs(df) < 1e-12) return std::nullopt;
    const double step = -f / df;
    t += step;
    // Newton converges quadratically: after a step Δ the error is about C·Δ² with
    // C = |f''/2f'| below 1 /mm (profile radii above 0.5 mm), so a step below 1e-6 mm leaves
    // less than 1e-12 mm, without the extra evaluation that only confirms it.
    if (std::fabs(step) < 1e-6) return t;
  }
  return std::nullopt;
}

std::optional<double> PlacedWheel::SurfaceZ(double x, double y) const {
  // Start from the unrotated wheel: z = z_centre + r(y − y_centre − offset).
  const auto r = Radius(y - p_TWo_T_(1) - profile_offset_);
  const double z0 = p_TWo_T_(2) + (r ? r->first : nominal_radius_);
  return IntersectLine({x, y, 0.0}, Eigen::Vector3d::UnitZ(), z0);
}

Eigen::Vector2d PlacedWheel::ToWheelProfile(const Eigen::Vector3d& p_T) const {
  const Eigen::Vector3d q = R_TW_.transpose() * (p_T - p_TWo_T_);
  return {q(1) - profile_offset_, std::hypot(q(0), q(2)) - nominal_radius_};
}

Eigen::Vector3d PlacedWheel::MaterialVelocity(const Eigen::Vector3d& p_T) const {
  return v_TWo_T_ + w_TW_T_.cross(p_T - p_TWo_T_);
}

}  // namespace wrc::wr
