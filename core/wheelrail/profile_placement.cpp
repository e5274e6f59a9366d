#include "wrc/core/profile_placement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "core/gsl/roots.h"
#include "core/wheelrail/contact_search.h"
#include "core/wheelrail/geometry.h"
#include "wrc/core/profile.h"

namespace wrc {
namespace {

// A reach far beyond any profile's height locates the wheel above every rail point.
constexpr double kEverywhere = 1e3;

wr::WheelsetKinematics Kinematics(const WheelsetPlacement& pose) {
  wr::WheelsetKinematics kin;
  kin.y = pose.y;
  kin.z = pose.z;
  kin.roll = pose.roll;
  kin.yaw = pose.yaw;
  return kin;
}

std::vector<double> Steps(double length, double step) {
  const int n = std::max(2, static_cast<int>(std::ceil(length / step)));
  std::vector<double> s(n + 1);
  for (int k = 0; k <= n; ++k) s[k] = length * k / n;
  return s;
}

}  // namespace

PlacedProfiles PlaceProfiles(const Case& c, const WheelsetPlacement& pose, double step) {
  const wr::PlacedRail rail(SplineOf(c.rail, ProfileKind::kRail), c.track);
  const wr::PlacedWheel wheel(SplineOf(c.wheel, ProfileKind::kWheel), c.wheelset, Kinematics(pose));
  PlacedProfiles placed;
  for (const Eigen::Vector2d& p : rail.PositionsAt(Steps(rail.length(), step))) {
    placed.rail_y.push_back(p(0));
    placed.rail_z.push_back(p(1));
  }
  // The principal plane x_w = 0 holds the lowest points of the wheel:
  // p_T = p_TWo + R_TW·(0, offset + y_w, r_nom + z_w).
  const ProfileSpline& spline = wheel.spline();
  for (const ProfileVector& pw : spline.PositionsAt(Steps(spline.length(), step))) {
    const Eigen::Vector3d q(0.0, wheel.profile_offset() + pw.y, wheel.nominal_radius() + pw.z);
    const Eigen::Vector3d p = wheel.p_TWo_T() + wheel.R_TW() * q;
    placed.wheel_y.push_back(p(1));
    placed.wheel_z.push_back(p(2));
  }
  for (const wr::LocusSample& s : wr::SearchContact(rail, wheel, step, kEverywhere).samples) {
    if (s.valid && std::isfinite(s.gap)) placed.gap.push_back({s.y, s.gap, s.x});
  }
  return placed;
}

namespace {

// The wheel at pose's y, roll and yaw with the wheelset at height 0, where first-touch heights
// are measured from.
wr::PlacedWheel WheelAtZeroHeight(const Case& c, const WheelsetPlacement& pose) {
  WheelsetPlacement at_zero = pose;
  at_zero.z = 0.0;
  return wr::PlacedWheel(SplineOf(c.wheel, ProfileKind::kWheel), c.wheelset, Kinematics(at_zero));
}

// The case with its profiles read and splined, so that repeated placements do not read them
// again (a case built in code carries none).
Case WithSplines(Case c) {
  c.rail.spline = SplineOf(c.rail, ProfileKind::kRail);
  c.wheel.spline = SplineOf(c.wheel, ProfileKind::kWheel);
  return c;
}

}  // namespace

double FirstContactHeight(const Case& c, const WheelsetPlacement& pose, double step) {
  const wr::PlacedRail rail(SplineOf(c.rail, ProfileKind::kRail), c.track);
  const wr::PlacedWheel wheel = WheelAtZeroHeight(c, pose);
  double first = std::numeric_limits<double>::infinity();
  for (const wr::LocusSample& s : wr::SearchContact(rail, wheel, step, 0.0).samples) {
    if (s.valid) first = std::min(first, s.gap);
  }
  return first;
}

RigidContact RigidContactAt(const Case& c, const WheelsetPlacement& pose, double step) {
  const wr::PlacedRail rail(SplineOf(c.rail, ProfileKind::kRail), c.track);
  const wr::PlacedWheel wheel = WheelAtZeroHeight(c, pose);
  // A reach of a few steps keeps the smallest gap's neighbours located, for the parabola.
  const auto samples = wr::SearchContact(rail, wheel, step, 4.0 * step).samples;
  std::size_t k = samples.size();
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (samples[i].valid && (k == samples.size() || samples[i].gap < samples[k].gap)) k = i;
  }
  RigidContact contact;
  if (k == samples.size()) return contact;
  // The gap's minimum between the samples: the parabola through k − 1, k, k + 1.
  double s = samples[k].s, gap = samples[k].gap;
  if (k > 0 && k + 1 < samples.size() && samples[k - 1].valid && samples[k + 1].valid) {
    const double lo = samples[k - 1].gap, mid = samples[k].gap, hi = samples[k + 1].gap;
    const double curvature = lo - 2.0 * mid + hi;
    if (curvature > 0.0) {
      const double shift = std::clamp(0.5 * (lo - hi) / curvature, -0.5, 0.5);
      s += shift * (samples[k + 1].s - samples[k].s);
      gap = mid - 0.25 * (lo - hi) * shift;
    }
  }
  const Eigen::Vector2d p = rail.PositionAt(s);
  // The wheel touches where it lies `gap` above that rail point (z down).
  const Eigen::Vector2d on_wheel =
      wheel.ToWheelProfile(Eigen::Vector3d(samples[k].x, p(0), p(1) - gap));
  contact.found = true;
  contact.height = gap;
  contact.rail_y = p(0);
  contact.rail_z = p(1);
  contact.contact_angle = rail.InclinationAt(s);
  contact.wheel_y = on_wheel(0);
  contact.rolling_radius = wheel.nominal_radius() + on_wheel(1);
  const ProfileSpline& w = wheel.spline();
  const double w_first = w.PositionAt(0.0).y, w_last = w.PositionAt(w.length()).y;
  contact.at_profile_end = s < 2.0 * step || s > rail.length() - 2.0 * step ||
                           std::fabs(on_wheel(0) - w_first) < 2.0 * step ||
                           std::fabs(on_wheel(0) - w_last) < 2.0 * step;
  return contact;
}

double WheelsetRollAt(const Case& right_case, const Case& left_case, double y, double step) {
  const Case right = WithSplines(right_case), left = WithSplines(left_case);
  const auto height_difference = [&](double roll) {
    return RigidContactAt(right, {y, 0.0, roll, 0.0}, step).height -
           RigidContactAt(left, {-y, 0.0, -roll, 0.0}, step).height;
  };
  // ±50 mrad: ten times the roll of a wheelset on its flanges (a 1500 mm base, 15 mm of Δr).
  constexpr double kMaxRoll = 0.05;
  const double lo = height_difference(-kMaxRoll), hi = height_difference(kMaxRoll);
  if (!std::isfinite(lo) || !std::isfinite(hi) || (lo > 0.0) == (hi > 0.0)) return NAN;
  gsl::RootOptions options;
  options.abs_tolerance = 1e-9;  // rad: 1.5 µm across the wheelset, far below the profiles'
  return gsl::FindRootBrent(height_difference, -kMaxRoll, kMaxRoll, options).root;
}

}  // namespace wrc
