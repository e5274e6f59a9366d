#pragma once
/// @file errors.h
/// Exception types shared by wrc's libraries and tools.

#include <stdexcept>

namespace wrc {

/// Bad user input: a case or scene file that cannot be parsed, or a value outside its allowed
/// range. The message is meant for the user as is; tools print it and exit with code 2.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace wrc
