#pragma once
// Running a command line from a test and capturing what it printed.

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "tests/support/files.h"

namespace wrc::test_support {

struct CommandResult {
  int exit_code = -1;  ///< -1 when the command did not exit normally
  std::string out, err;
};

/// Runs a shell command line in the current directory; stdout and stderr go through
/// stdout.txt and stderr.txt in `capture_dir`. With `timeout_s` > 0 a hang ends as exit 124
/// (coreutils' timeout) instead of blocking the suite.
inline CommandResult RunCommand(const std::string& command,
                                const std::filesystem::path& capture_dir, int timeout_s = 0) {
  const std::filesystem::path out = capture_dir / "stdout.txt", err = capture_dir / "stderr.txt";
  // Grouped, so that the redirections take every command of a list, not only its last one.
  const std::string limited =
      timeout_s > 0 ? "timeout " + std::to_string(timeout_s) + " sh -c " + Quoted(command)
                    : "{ " + command + "\n}";
  const int status =
      std::system((limited + " >" + Quoted(out.string()) + " 2>" + Quoted(err.string())).c_str());
  CommandResult result;
  if (status != -1 && WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  result.out = ReadFile(out);
  result.err = ReadFile(err);
  return result;
}

/// The `wrc` program of this build.
inline std::filesystem::path WrcBinary() { return std::filesystem::path(WRC_BINARY_DIR) / "wrc"; }

}  // namespace wrc::test_support
