#pragma once
// Subcommands of the `wrc` command-line tool.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>
#include <system_error>

#include "tools/wrc/exit_codes.h"

namespace wrc::cli {

/// Parses the command line and runs the chosen command (whose callback sets `exit_code`), then
/// flushes standard output: a command line CLI11 refuses, or an unknown subcommand, is bad input
/// (CLI11 prints its own message); a failed flush goes through ReportFailure. Returns the
/// process's exit code.
int RunCommandLine(CLI::App& app, int argc, char** argv, const int& exit_code);

/// Option checks that say in words what a value must be: CLI11's PositiveNumber and
/// NonNegativeNumber state their range as "0.000000 to 1797693...(309 digits).000000".
/// The message reads "--samples: must be greater than 0, is 0".
template <class Accept>
CLI::Validator NumberCheck(Accept accept, const std::string& must, const std::string& name) {
  return CLI::Validator(
      [accept, must](std::string& text) {
        double value = 0.0;
        const bool number = CLI::detail::lexical_cast(text, value);
        return number && accept(value) ? std::string() : "must be " + must + ", is " + text;
      },
      name);
}
inline CLI::Validator GreaterThanZero() {
  return NumberCheck([](double v) { return v > 0.0; }, "greater than 0", "> 0");
}
inline CLI::Validator ZeroOrMore() {
  return NumberCheck([](double v) { return v >= 0.0; }, "0 or more", ">= 0");
}

/// Where a user finds a page of the user reference (`relative` to docs/), for --help texts: the
/// installed copy beside an installed wrc (PREFIX/bin/wrc: PREFIX/share/doc/wrc/...), the
/// checkout's docs/ beside a build tree (build/wrc), else "docs/..." as in the repository.
inline std::string DocFile(const std::string& relative) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const std::filesystem::path above = self.parent_path().parent_path();
    for (const std::filesystem::path& page :
         {above / "share" / "doc" / "wrc" / relative, above / "docs" / relative}) {
      if (std::filesystem::is_regular_file(page, ec)) return page.lexically_normal().string();
    }
  }
  return "docs/" + relative;
}

/// Registers `wrc solve` on `app`; the callback stores its exit code in *exit_code.
void AddSolveCommand(CLI::App& app, int* exit_code);

/// Registers `wrc generate SCENE.toml -o TABLE.h5` (docs/reference/table-layout.md): exit 0 when
/// the table was written (failed points are in /status), 2 for bad input, 130 when interrupted.
void AddGenerateCommand(CLI::App& app, int* exit_code);

/// Registers `wrc info TABLE.h5 [--json]`: axes, outputs, status counts, provenance.
void AddInfoCommand(CLI::App& app, int* exit_code);

/// Registers `wrc upgrade OLD.h5 -o NEW.h5`: a table from before seals, checksummed and sealed.
void AddUpgradeCommand(CLI::App& app, int* exit_code);

/// Registers `wrc export TABLE.h5 -o TABLE.wrct`: the table as a flat file for a runtime built
/// without HDF5 (runtime/format/flat_table.h).
void AddExportCommand(CLI::App& app, int* exit_code);

/// Registers `wrc fmu TABLE.h5 -o wheelset.fmu`: the wheelset FMU (FMI 3.0 co-simulation)
/// packed with the table (fmu/).
void AddFmuCommand(CLI::App& app, int* exit_code);

/// Registers `wrc geometry CASE.toml`: the rigid contact geometry of a wheelset over y and its
/// equivalent conicity (docs/conicity.md).
void AddGeometryCommand(CLI::App& app, int* exit_code);

/// Registers `wrc verify` (docs/reference/cli.md, wrc verify).
void AddVerifyCommand(CLI::App& app, int* exit_code);

/// Registers `wrc plot` (patch, profiles, table; docs/plots.md).
void AddPlotCommand(CLI::App& app, int* exit_code);

}  // namespace wrc::cli
