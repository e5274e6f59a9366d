#pragma once
// The wheelset FMU's binary as built with this wrc, and the FMI platform tuple it was built for
// (its folder under binaries/ in an FMU, "x86_64-linux").

#include <string_view>

namespace wrc::cli {

std::string_view FmuBinary();
const char* FmuPlatform();

}  // namespace wrc::cli
