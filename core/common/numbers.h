#pragma once
/// @file numbers.h
/// Mathematical constants shared by the core (C++17 has no std::numbers).

namespace wrc {

inline constexpr double kPi = 3.14159265358979323846;

}  // namespace wrc
