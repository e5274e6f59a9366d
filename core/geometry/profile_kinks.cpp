// Kink detection as described for CONTACT's KINKHIGH / KINKLOW / KINKWID: isolated sharp
// corners of the profile that the spline and the smoothing must keep.

#include <cmath>
#include <cstddef>
#include <vector>

#include "core/common/numbers.h"
#include "core/geometry/profile_internal.h"
#include "wrc/core/profile.h"

namespace wrc::profile_detail {
namespace {

/// |δα_i|: the angle between segment (i−1, i) and segment (i, i+1), in [0, π].
double AbsoluteTurn(const std::vector<double>& y, const std::vector<double>& z, std::size_t i) {
  const double ay = y[i] - y[i - 1];
  const double az = z[i] - z[i - 1];
  const double by = y[i + 1] - y[i];
  const double bz = z[i + 1] - z[i];
  return std::abs(std::atan2(ay * bz - az * by, ay * by + az * bz));
}

}  // namespace

double KinkLowThreshold(const ProfileOptions& options) {
  return options.kink_low_rad < 0.0 ? options.kink_high_rad / 5.0 : options.kink_low_rad;
}

std::vector<std::size_t> FindKinks(const std::vector<double>& y, const std::vector<double>& z,
                                   const ProfileOptions& options) {
  std::vector<std::size_t> kinks;
  const std::size_t n = y.size();
  // A turn can never exceed π, so a threshold of π or more finds nothing (CONTACT's switch).
  if (n < 3 || !(options.kink_high_rad < kPi)) return kinks;
  const double low = KinkLowThreshold(options);

  // The ends have no inclination change; interior turns and the summed chord length s.
  std::vector<double> turn(n, 0.0);
  std::vector<double> s(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) {
    s[i] = s[i - 1] + std::hypot(y[i] - y[i - 1], z[i] - z[i - 1]);
    if (i + 1 < n) turn[i] = AbsoluteTurn(y, z, i);
  }
  for (std::size_t i = 1; i + 1 < n; ++i) {
    if (!(turn[i] > options.kink_high_rad)) continue;
    // Isolated: every other point within kink_width (along the profile) on either side turns by
    // at most the low threshold. Two large turns close together are roughness, not a corner.
    bool isolated = true;
    for (std::size_t j = i; isolated && j > 0 && s[i] - s[j - 1] <= options.kink_width; --j) {
      isolated = turn[j - 1] <= low;
    }
    for (std::size_t j = i + 1; isolated && j < n && s[j] - s[i] <= options.kink_width; ++j) {
      isolated = turn[j] <= low;
    }
    if (isolated) kinks.push_back(i);
  }
  return kinks;
}

}  // namespace wrc::profile_detail
