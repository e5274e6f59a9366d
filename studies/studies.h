#pragma once
// The studies of wrc (accuracy, cost, stability, dynamics, the paper's results) as the
// `wrc study` command of the command-line tool.

#include <CLI/CLI.hpp>

namespace wrc::cli {

/// Registers `wrc study` and its subcommands on `app`; each callback stores its exit code in
/// *exit_code.
void AddStudyCommand(CLI::App& app, int* exit_code);

}  // namespace wrc::cli
