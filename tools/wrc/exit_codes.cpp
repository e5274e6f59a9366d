#include "tools/wrc/exit_codes.h"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <iostream>
#include <new>

#include "runtime/hdf5/hdf5.h"
#include "tools/wrc/commands.h"
#include "wrc/core/errors.h"
#include "wrc/core/output_file.h"
#include "wrc/generator/generator.h"
#include "wrc/runtime.hpp"

namespace wrc::cli {
namespace {

Failure Report(int exit_code, const std::string& prefix, const std::string& message) {
  return {exit_code, prefix + message, message};
}

// What no input can cause: the user can only report it.
Failure Bug(const std::string& what) {
  return {kExitBug,
          "internal error: " + what +
              " (a bug in wrc; please report it with the command and its input files)",
          what};
}

}  // namespace

Failure FailureOf(std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const Interrupted& e) {
    return Report(kExitInterrupted, "", e.what());
  } catch (const GenerateAborted& e) {
    return {kExitBadInput, "", e.what()};
  } catch (const InputError& e) {
    return Report(kExitBadInput, "error: ", e.what());
  } catch (const NumericalError& e) {
    return Report(kExitNumerical, "error: ", e.what());
  } catch (const h5::Error& e) {
    // The HDF5 wrapper sits below core and knows no InputError: its failures are the table
    // file's (damaged, unreadable, a full disk), so they count as bad input here.
    return Report(kExitBadInput, "error: ", e.what());
  } catch (const TableError& e) {
    return Report(kExitBadInput, "error: ", e.what());
  } catch (const std::filesystem::filesystem_error& e) {
    return Report(kExitBadInput, "error: ", e.what());  // names the path and the system's reason
  } catch (const std::bad_alloc&) {
    return Report(kExitBadInput, "error: ", "out of memory");
  } catch (const std::exception& e) {
    return Bug(e.what());  // std::logic_error, and any class the policy does not name
  } catch (...) {
    return Bug("an exception that is not a std::exception");
  }
}

int ReportFailure(const std::string& command, std::exception_ptr error) {
  const Failure failure = FailureOf(error);
  if (!failure.line.empty()) std::cerr << command << ": " << failure.line << '\n';
  return failure.exit_code;
}

int RunCommandLine(CLI::App& app, int argc, char** argv, const int& exit_code) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (app.get_subcommands().empty() && !app.remaining().empty()) {
      std::cerr << "wrc: unknown subcommand '" << app.remaining().front()
                << "'; run 'wrc --help' for the list\n";
      return kExitBadInput;
    }
    // CLI11 prints help/usage errors itself; bad command lines are bad input (exit 2).
    const int code = app.exit(e);
    return code == 0 ? 0 : kExitBadInput;
  }
  try {
    FinishStandardOutput();
  } catch (...) {
    return ReportFailure("wrc");
  }
  return exit_code;
}

}  // namespace wrc::cli
