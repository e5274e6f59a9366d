// Ctrl-C during `wrc solve`: a message, for --json an error object, exit 130, and no output file
// left half-written under its final name.

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/files.h"
#include "tests/support/run.h"

namespace {

namespace fs = std::filesystem;
using wrc::test_support::CommandResult;
using wrc::test_support::Quoted;
using wrc::test_support::ReadFile;
using wrc::test_support::RunCommand;
using wrc::test_support::ScratchDir;
using wrc::test_support::WrcBinary;
using wrc::test_support::WriteFile;

// The shipped heavy-haul flange case on 0.1 mm elements: about 20 s of solving on this
// machine, so a signal 1 s after the start always arrives during the solve.
fs::path SlowCase(const ScratchDir& dir) {
  std::string text = ReadFile(fs::path(WRC_SOURCE_DIR) / "tables" / "heavy_haul_case.toml");
  for (const char* key : {"dx = 0.8", "ds = 0.8"}) {
    const std::size_t at = text.find(key);
    EXPECT_NE(at, std::string::npos) << key;
    if (at != std::string::npos) text.replace(at + 5, 3, "0.1");
  }
  const std::string profiles = "\"profiles/";
  for (std::size_t at = text.find(profiles); at != std::string::npos;
       at = text.find(profiles, at)) {
    const std::string absolute = "\"" + std::string(WRC_SOURCE_DIR) + "/tables/profiles/";
    text.replace(at, profiles.size(), absolute);
    at += absolute.size();
  }
  return WriteFile(dir / "slow.toml", text);
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
