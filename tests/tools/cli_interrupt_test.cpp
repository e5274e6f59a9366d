// Ctrl-C during `wrc solve`: a message, for --json an error object, exit 130, and no output file
// left half-written under its final name.

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/case_builder.h"
#include "tests/support/files.h"
#include "tests/support/run.h"

namespace {

namespace fs = std::filesystem;
using wrc::test_support::CaseBuilder;
using wrc::test_support::CommandResult;
using wrc::test_support::Quoted;
using wrc::test_support::RunCommand;
using wrc::test_support::ScratchDir;
using wrc::test_support::WrcBinary;

// The shipped heavy-haul flange case on 0.1 mm elements: about 20 s of solving on this
// machine, so a signal 1 s after the start always arrives during the solve.
fs::path SlowCase(const ScratchDir& dir) {
  return CaseBuilder::Shipped("heavy_haul_case.toml")
      .Set("grid", "dx", "0.1")
      .Set("grid", "ds", "0.1")
      .Write(dir / "slow.toml");
}

CommandResult SolveAndInterrupt(const ScratchDir& dir, const std::string& flags) {
  const std::string solve =
      Quoted(WrcBinary().string()) + " solve " + Quoted(SlowCase(dir).string()) + flags;
  return RunCommand(solve + " & pid=$!; sleep 1; kill -INT $pid; wait $pid", dir.path());
}

TEST(SolveInterrupt, CtrlCEndsTheSolveWithAMessageAndExit130) {
  const ScratchDir dir("wrc_solve_sigint");
  const CommandResult run = SolveAndInterrupt(dir, " --out " + Quoted((dir / "out").string()));
  EXPECT_EQ(run.exit_code, 130) << run.err;
  EXPECT_EQ(run.err, "wrc solve: interrupted\n");
  EXPECT_FALSE(fs::exists(dir / "out" / "summary.json"));
}

TEST(SolveInterrupt, WithJsonStdoutHoldsAnErrorObject) {
  const ScratchDir dir("wrc_solve_sigint_json");
  const CommandResult run = SolveAndInterrupt(dir, " --json");
  EXPECT_EQ(run.exit_code, 130) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j.at("status"), "error");
  EXPECT_EQ(j.at("message"), "interrupted");
}

}  // namespace
