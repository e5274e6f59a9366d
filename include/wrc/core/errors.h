#pragma once
/// @file errors.h
/// Exception types shared by wrc's libraries and tools, and the number format of their messages.

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>

namespace wrc {

// The exceptions that cross a library boundary (docs/design.md, Error policy). A numerical
// outcome the caller can act on is a status in the result, not an exception; a broken invariant
// is a std::logic_error, a bug in wrc.

/// Bad user input: a case or scene file that cannot be parsed, a value outside its allowed
/// range, and a file of the user's that cannot be read or written or is damaged (a journal, a
/// table, an output). The message is meant for the user as is and names the file; tools print
/// it and exit with code 2.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The machine refused what a run needs (memory, a worker thread). No property of the input
/// file, but the user's to fix (fewer threads, more memory), so it counts as bad input (exit 2);
/// the message says what was kept. The table generator stops on it rather than store a point.
class ResourceError : public InputError {
 public:
  using InputError::InputError;
};

/// A numerical routine failed where no status can carry the outcome (a GSL routine, a
/// factorisation): the input was valid, the computation did not succeed. Tools exit with
/// code 3; the table generator stores the point as failed.
class NumericalError : public std::runtime_error {
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
