#pragma once
// How a `wrc` command ends: its exit codes, and the one map from the exceptions of the error
// policy (docs/design.md) to a message and an exit code.

#include <exception>
#include <stdexcept>
#include <string>

namespace wrc::cli {

/// Exit codes (docs/reference/cli.md).
enum ExitCode : int {
  kExitOk = 0,             ///< success; `solve`: ok or no contact
  kExitGateFailed = 1,     ///< a gate of verify or a study failed
  kExitBadInput = 2,       ///< bad input: a file, a value, the command line, the machine's limits
  kExitNumerical = 3,      ///< a numerical outcome: not converged, or a numerical routine failed
  kExitBug = 70,           ///< a bug in wrc (EX_SOFTWARE of sysexits.h): a broken invariant
  kExitInterrupted = 130,  ///< SIGINT or SIGTERM, as a shell reports a process ended by SIGINT
};

/// SIGINT or SIGTERM stopped a command before it finished; what() says how far it got and what
/// was kept. Commands report it without "error:" and exit with kExitInterrupted.
class Interrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// What a command reports for the exception that ended it.
struct Failure {
  int exit_code = kExitBug;
  /// The line for stderr after "wrc COMMAND: " ("error: ...", "internal error: ...", or an
  /// Interrupted's text); empty when another process reports it (an MPI rank other than 0).
  std::string line;
  /// The exception's own text, for an error object in JSON output (a bug's without the words
  /// around it in `line`).
  std::string message;
};

/// The map from exception classes to exit codes, for every command:
///  - InputError (ResourceError too), h5::Error, TableError, std::filesystem::filesystem_error,
///    std::bad_alloc: kExitBadInput, "error: <what()>" ("error: out of memory");
///  - GenerateAborted (an MPI rank other than 0, whose rank 0 reports): kExitBadInput, no line;
///  - NumericalError: kExitNumerical, "error: <what()>";
///  - Interrupted: kExitInterrupted, "<what()>";
///  - std::logic_error and anything else: kExitBug, "internal error: <what()> (a bug in wrc ...)".
Failure FailureOf(std::exception_ptr error);

/// Prints FailureOf(error)'s line to stderr as "COMMAND: line" and returns its exit code; for
/// `catch (...)` around a command's work.
int ReportFailure(const std::string& command, std::exception_ptr error = std::current_exception());

}  // namespace wrc::cli
