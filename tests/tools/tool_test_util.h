#pragma once
// What the tests of the `wrc` subcommands share: where the program and the sources are, reading
// a file, and running `wrc` in a user's directory.

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/support/files.h"

namespace wrc::tool_test {

inline const std::filesystem::path kWrc = std::filesystem::path(WRC_BINARY_DIR) / "wrc";
inline const std::filesystem::path kSource = WRC_SOURCE_DIR;

using test_support::ReadFile;

/// Runs `wrc ARGS` in `dir` with a time limit (s); stdout and stderr go to stdout.txt and
/// stderr.txt there. The exit code, or -1 when it did not exit.
inline int RunWrcIn(const std::filesystem::path& dir, const std::string& args, int timeout_s) {
  const std::string command = "cd '" + dir.string() + "' && timeout " + std::to_string(timeout_s) +
                              " '" + kWrc.string() + "' " + args + " >stdout.txt 2>stderr.txt";
  const int status = std::system(command.c_str());
  return status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace wrc::tool_test
