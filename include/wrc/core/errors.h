#pragma once
/// @file errors.h
/// Exception types shared by wrc's libraries and tools, and the number format of their messages.

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>

namespace wrc {

/// Bad user input: a case or scene file that cannot be parsed, or a value outside its allowed
/// range. The message is meant for the user as is; tools print it and exit with code 2.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A number for messages, as a user would type it: the shortest text that reads back as the
/// same double ("500", "0.5", "-0.002", "1e+12", "nan", "inf", "-inf"), unlike std::to_string's
/// fixed six decimals ("500.000000", "0.000000" for 1e-9).
inline std::string FormatNumber(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[32];  // the longest shortest form, "-2.2250738585072014e-308", has 24 characters
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

}  // namespace wrc
