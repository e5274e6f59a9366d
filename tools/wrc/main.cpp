// wrc: wheel–rail contact. One binary, one subcommand per job.

#include <CLI/CLI.hpp>

#include "runtime/hdf5/hdf5.h"
#include "studies/studies.h"
#include "tools/wrc/commands.h"

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
  return wrc::cli::RunCommandLine(app, argc, argv, exit_code);
}
