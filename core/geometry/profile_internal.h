#pragma once
/// @file profile_internal.h
/// Functions shared by the profile sources in core/geometry/ (not part of the public API).

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "wrc/core/profile.h"

namespace wrc::profile_detail {

/// "<source>:<line>: <message>", the compiler-style location used in every profile message.
std::string At(const std::string& source, int line, const std::string& message);

/// The whole token as a number (a leading '+' is allowed, as Simpack writes it); NaN and Inf
/// parse (the caller reports them as not finite); anything else gives nullopt.
std::optional<double> ParseNumber(std::string_view token);

/// Replaces (y_i, z_i) by the values at s_i of the weighted cubic smoothing spline with
/// wavelength `wavelength` mm (see ProfileOptions::smoothing), s_i the chord length. Needs at
/// least 3 points with distinct successive points. `pin_first` / `pin_last` keep that end
/// point where it is (infinite weight), so that parts smoothed separately still meet there.
void SmoothPoints(std::vector<double>& y, std::vector<double>& z, double wavelength,
                  bool pin_first = false, bool pin_last = false);

/// SmoothPoints on each part between successive kinks (indices ascending, interior), with the
/// kink points held fixed; parts of two points are straight and stay as they are. Without
/// kinks this is SmoothPoints on all points.
void SmoothPointsBetweenKinks(std::vector<double>& y, std::vector<double>& z, double wavelength,
                              const std::vector<std::size_t>& kinks);

/// The kink threshold that applies: ProfileOptions::kink_low_rad, or kink_high_rad / 5 when
/// that is negative.
double KinkLowThreshold(const ProfileOptions& options);

/// Indices of the true kinks of the polyline (y_i, z_i) by CONTACT's rule (see
/// ProfileOptions::kink_high_rad), ascending; empty when kink_high_rad >= π. The options must
/// have been validated (RepairProfile does).
std::vector<std::size_t> FindKinks(const std::vector<double>& y, const std::vector<double>& z,
                                   const ProfileOptions& options);

/// Access to ProfileSpline's internals for tests.
struct SplineAccess {
  /// SAtY by trying every knot interval, without the y table: the reference the table must
  /// reproduce exactly.
  static std::vector<double> SAtYTryingEveryInterval(const ProfileSpline& spline, double y);
};

}  // namespace wrc::profile_detail
