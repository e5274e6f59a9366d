// wrc: wheel–rail contact. One binary, one subcommand per job.

#include <CLI/CLI.hpp>

#include <iostream>

#include "runtime/hdf5/hdf5.h"
#include "studies/studies.h"
#include "tools/wrc/commands.h"
#include "wrc/core/output_file.h"

int main(int argc, char** argv) {
  wrc::h5::SkipLibraryTermination();  // every file is closed explicitly (hdf5.h)
  CLI::App app{"wrc: wheel-rail contact solver, table generator and verifier"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "wrc 0.1.0");
  int exit_code = wrc::cli::kExitOk;
  wrc::cli::AddSolveCommand(app, &exit_code);
  wrc::cli::AddGenerateCommand(app, &exit_code);
  wrc::cli::AddInfoCommand(app, &exit_code);
  wrc::cli::AddUpgradeCommand(app, &exit_code);
  wrc::cli::AddExportCommand(app, &exit_code);
  wrc::cli::AddFmuCommand(app, &exit_code);
  wrc::cli::AddGeometryCommand(app, &exit_code);
  wrc::cli::AddVerifyCommand(app, &exit_code);
  wrc::cli::AddStudyCommand(app, &exit_code);
  wrc::cli::AddPlotCommand(app, &exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (app.get_subcommands().empty() && !app.remaining().empty()) {
      std::cerr << "wrc: unknown subcommand '" << app.remaining().front()
                << "'; run 'wrc --help' for the list\n";
      return wrc::cli::kExitBadInput;
    }
    // CLI11 prints help/usage errors itself; bad command lines are bad input (exit 2).
    const int code = app.exit(e);
    return code == 0 ? 0 : wrc::cli::kExitBadInput;
  }
  try {
    wrc::FinishStandardOutput();
  } catch (...) {
    return wrc::cli::ReportFailure("wrc");
  }
  return exit_code;
}
