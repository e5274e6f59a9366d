#pragma once
// Angles as the command line and the studies write them: radians inside, degrees in reports
// and pictures. C++17 has no std::numbers, and the core's own constant is internal to it.

namespace wrc::tools {

inline constexpr double kPi = 3.14159265358979323846;

/// An angle in radians written in degrees (multiplied, then divided, as every report has it).
inline double Degrees(double radians) { return radians * 180.0 / kPi; }

}  // namespace wrc::tools
