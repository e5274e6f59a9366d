// The one map from exception classes to the exit codes and messages of every `wrc` command
// (tools/wrc/exit_codes.h; docs/design.md, Error policy).

#include "tools/wrc/exit_codes.h"

#include <gtest/gtest.h>

#include <exception>
#include <filesystem>
#include <new>
#include <stdexcept>
#include <string>
#include <system_error>

#include "core/gsl/error.h"
#include "runtime/hdf5/hdf5.h"
#include "wrc/core/errors.h"
#include "wrc/generator/generator.h"
#include "wrc/runtime.hpp"

namespace wrc::cli {
namespace {

template <class E>
Failure Of(const E& error) {
  return FailureOf(std::make_exception_ptr(error));
}

TEST(ExitCodes, BadInputIsTwoAndSaysWhy) {
  for (const Failure& f : {Of(InputError("case.toml:3: state.fn = -1: must be 0 or more")),
                           Of(ResourceError("case.toml:3: state.fn = -1: must be 0 or more")),
                           Of(h5::Error("case.toml:3", "state.fn = -1: must be 0 or more")),
                           Of(TableError(3, "case.toml:3: state.fn = -1: must be 0 or more"))}) {
    EXPECT_EQ(f.exit_code, kExitBadInput);
    EXPECT_EQ(f.line.rfind("error: case.toml:3", 0), 0u) << f.line;
    EXPECT_NE(f.message.find("must be 0 or more"), std::string::npos) << f.message;
  }
  const Failure path = Of(std::filesystem::filesystem_error(
      "cannot create directories", "/out/dir", std::make_error_code(std::errc::permission_denied)));
  EXPECT_EQ(path.exit_code, kExitBadInput);
  EXPECT_NE(path.line.find("/out/dir"), std::string::npos) << path.line;
}

TEST(ExitCodes, OutOfMemoryIsTwoInWords) {
  const Failure f = Of(std::bad_alloc());
  EXPECT_EQ(f.exit_code, kExitBadInput);
  EXPECT_EQ(f.line, "error: out of memory");
}

TEST(ExitCodes, AnotherMpiRanksRefusalIsTwoAndSilent) {
  const Failure f = Of(GenerateAborted("rank 0 says why"));
  EXPECT_EQ(f.exit_code, kExitBadInput);
  EXPECT_TRUE(f.line.empty()) << f.line;
}

TEST(ExitCodes, ANumericalFailureIsThree) {
  for (const Failure& f :
       {Of(NumericalError("factorisation failed")), Of(GslError("gsl_integration_qags", 11))}) {
    EXPECT_EQ(f.exit_code, kExitNumerical);
    EXPECT_EQ(f.line.rfind("error: ", 0), 0u) << f.line;
  }
}

TEST(ExitCodes, InterruptedIs130WithoutError) {
  const Failure f = Of(Interrupted("interrupted after 3 of 10 exact solves"));
  EXPECT_EQ(f.exit_code, kExitInterrupted);
  EXPECT_EQ(f.line, "interrupted after 3 of 10 exact solves");
}

TEST(ExitCodes, ABugIsSeventyAndSaysSo) {
  for (const Failure& f :
       {Of(std::logic_error("workspace used with another operator")),
        Of(std::out_of_range("CaseAtIndex: 2 indices for 1 axes")),
        Of(std::runtime_error("MPI protocol: unexpected message tag 9")), Of(42)}) {
    EXPECT_EQ(f.exit_code, kExitBug);
    EXPECT_EQ(f.line.rfind("internal error: ", 0), 0u) << f.line;
    EXPECT_NE(f.line.find("a bug in wrc"), std::string::npos) << f.line;
  }
  EXPECT_NE(Of(std::logic_error("workspace used with another operator"))
                .line.find("workspace used with another operator"),
            std::string::npos);
}

}  // namespace
}  // namespace wrc::cli
