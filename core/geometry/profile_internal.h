#pragma once
/// @file profile_internal.h
/// Helpers shared by the profile sources in core/geometry/ (not part of the public API).

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace wrc::profile_detail {

/// "<source>:<line>: <message>", the compiler-style location used in every profile message.
std::string At(const std::string& source, int line, const std::string& message);

/// The whole token as a number (a leading '+' is allowed, as Simpack writes it); NaN and Inf
/// parse (the caller reports them as not finite); anything else gives nullopt.
std::optional<double> ParseNumber(std::string_view token);

/// Replaces (y_i, z_i) by the values at s_i of the weighted cubic smoothing spline with
/// wavelength `wavelength` mm (see ProfileOptions::smoothing), s_i the chord length. Needs at
/// least 3 points with distinct successive points.
void SmoothPoints(std::vector<double>& y, std::vector<double>& z, double wavelength);

}  // namespace wrc::profile_detail
