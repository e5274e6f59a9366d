// wrc: the front end of the command-line tool. `wrc solve` runs here, in a process that loads
// only the solver's libraries; every other command is handed to wrc-tables (see
// tools/CMakeLists.txt for why there are two executables).

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>

#include "tools/wrc/commands.h"

namespace {

// wrc-tables next to this executable (build tree and install tree alike).
std::filesystem::path TablesExecutable() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return "wrc-tables";  // execvp then searches PATH
  return self.parent_path() / "wrc-tables";
}

int RunSolve(int argc, char** argv) {
  CLI::App app{"wrc: wheel-rail contact solver, table generator and verifier"};
  app.require_subcommand(1);
  int exit_code = wrc::cli::kExitOk;
  wrc::cli::AddSolveCommand(app, &exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11 prints help/usage errors itself; bad command lines are bad input (exit 2).
    const int code = app.exit(e);
    return code == 0 ? 0 : wrc::cli::kExitBadInput;
  }
  return exit_code;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && std::string(argv[1]) == "solve") return RunSolve(argc, argv);
  // Same pid, arguments and environment: an MPI launcher's rank variables reach wrc-tables.
  const std::string tables = TablesExecutable().string();
  // argv[0] stays "wrc" so that usage and error lines name the command the user typed.
  execvp(tables.c_str(), argv);
  std::cerr << "wrc: cannot start " << tables << " (needed for '" << (argc >= 2 ? argv[1] : "")
            << "'): " << std::strerror(errno) << "\n";
  return 1;
}
