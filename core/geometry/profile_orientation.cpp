// Which way round a profile lies laterally, judged from its shape: the gauge face of a rail and
// the flange of a wheel belong on the track-centre side (smaller y in the profile's own
// coordinates). Used to tell the user when mirror_y looks wrong, and for mirror_y = "auto".

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "wrc/core/profile.h"

namespace wrc {
namespace {

// A rail side is a gauge face when it reaches this far (mm) below the highest point: the gauge
// is measured 14 mm below the top (or 10–16 mm on other networks), so a MiniProf rail
// measurement always goes at least that deep on the gauge side.
constexpr double kMinGaugeFaceDepth = 10.0;
// The other side counts as clearly shallower below this fraction of the deep side's depth.
// Full rail sections (both sides down to the foot) and the roller-rig profiles of the test
// bank stay above it, so only a one-sided measurement is judged.
constexpr double kShallowFraction = 1.0 / 3.0;
// A wheel's flange stands at least this far (mm) below the middle of the profile (the tread):
// real flanges are 25–37 mm high; circles and rollers have no such point.
constexpr double kMinFlangeHeight = 5.0;
// Narrower profiles (mm) have no shape to judge.
constexpr double kMinJudgedWidth = 5.0;

std::string Mm(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f mm", value);
  return buffer;
}

LateralOrientation JudgeRail(const std::vector<double>& y, const std::vector<double>& z) {
  const std::size_t top =
      static_cast<std::size_t>(std::min_element(z.begin(), z.end()) - z.begin());
  double depth_smaller_y = 0.0;  // how far below the top the profile reaches on either side
  double depth_larger_y = 0.0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    const double depth = z[i] - z[top];
    if (y[i] < y[top]) depth_smaller_y = std::max(depth_smaller_y, depth);
    if (y[i] > y[top]) depth_larger_y = std::max(depth_larger_y, depth);
  }
  const double deep = std::max(depth_smaller_y, depth_larger_y);
  const double shallow = std::min(depth_smaller_y, depth_larger_y);
  if (deep < kMinGaugeFaceDepth || shallow >= kShallowFraction * deep) {
    return {LateralVerdict::kUndecided, "the sides reach " + Mm(depth_smaller_y) +
                                            " (smaller y) and " + Mm(depth_larger_y) +
                                            " (larger y) below the top: no one-sided gauge face"};
  }
  const bool as_expected = depth_smaller_y > depth_larger_y;
  const std::string reason = "the profile reaches " + Mm(deep) + " below its top at " +
                             (as_expected ? "smaller" : "larger") + " y (a gauge face) but only " +
                             Mm(shallow) + " at " + (as_expected ? "larger" : "smaller") + " y";
  return {as_expected ? LateralVerdict::kAsExpected : LateralVerdict::kMirrored, reason};
}

LateralOrientation JudgeWheel(const std::vector<double>& y, const std::vector<double>& z) {
  const auto [low, high] = std::minmax_element(y.begin(), y.end());
  const double width = *high - *low;
  const double middle = 0.5 * (*low + *high);
  const std::size_t tip =
      static_cast<std::size_t>(std::max_element(z.begin(), z.end()) - z.begin());
  std::size_t centre = 0;
  for (std::size_t i = 1; i < y.size(); ++i) {
    if (std::abs(y[i] - middle) < std::abs(y[centre] - middle)) centre = i;
  }
  if (tip == 0 || tip + 1 == z.size()) {
    return {LateralVerdict::kUndecided, "the lowest point is an end of the profile, no flange"};
  }
  const double height = z[tip] - z[centre];
  if (height < kMinFlangeHeight) {
    return {LateralVerdict::kUndecided, "no flange: the lowest point is only " + Mm(height) +
                                            " below the middle of the profile"};
  }
  const std::string where = "the flange (" + Mm(height) + " below the middle of the profile) ";
  if (y[tip] <= *low + width / 3.0) {
    return {LateralVerdict::kAsExpected, where + "lies at the smaller-y end"};
  }
  if (y[tip] >= *high - width / 3.0) {
    return {LateralVerdict::kMirrored, where + "lies at the larger-y end"};
  }
  return {LateralVerdict::kUndecided, where + "lies in the middle third of the profile"};
}

}  // namespace

LateralOrientation JudgeLateralOrientation(const std::vector<double>& y,
                                           const std::vector<double>& z, ProfileKind kind) {
  if (y.size() < 4 || z.size() != y.size()) {
    return {LateralVerdict::kUndecided, "too few points"};
  }
  const auto [low, high] = std::minmax_element(y.begin(), y.end());
  if (!(*high - *low >= kMinJudgedWidth)) {
    return {LateralVerdict::kUndecided, "the profile is narrower than " + Mm(kMinJudgedWidth)};
  }
  return kind == ProfileKind::kRail ? JudgeRail(y, z) : JudgeWheel(y, z);
}

std::optional<double> FlangeBackY(const ProfileSpline& wheel) {
  if (wheel.kind() != ProfileKind::kWheel) return std::nullopt;
  const std::vector<ProfileVector> points = wheel.PositionsAt(wheel.knots());
  std::vector<double> y(points.size()), z(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    y[i] = points[i].y;
    z[i] = points[i].z;
  }
  if (JudgeLateralOrientation(y, z, ProfileKind::kWheel).verdict != LateralVerdict::kAsExpected) {
    return std::nullopt;
  }
  // The flange tip is on the smaller-y side, so the smallest y lies on its back.
  return *std::min_element(y.begin(), y.end());
}

}  // namespace wrc
