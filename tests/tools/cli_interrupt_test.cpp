// Ctrl-C during `wrc solve`: a message, for --json an error object, exit 130, and no output file
// left half-written under its final name.

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
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

// An interrupted refinement tells how many solves it keeps (over grid passes and midpoint
// samples, not a pass's share of them) and where.
TEST(GenerateInterrupt, ARefinementRunTellsWhatItKeeps) {
  const ScratchDir dir("wrc_generate_sigint");
  const fs::path scene = CaseBuilder::Shipped("mbench_small.toml")
                             .Set("table.refine", "target", "0.01")
                             .Set("table.refine", "max_points", "40000")
                             .Write(dir / "refine.toml");
  const fs::path table = dir / "refined.h5";
  const std::string generate = Quoted(WrcBinary().string()) + " generate " +
                               Quoted(scene.string()) + " -o " + Quoted(table.string()) +
                               " --threads 1 --quiet";
  // Signalled once the refinement has started writing (the handlers are in place by then); the
  // whole run takes minutes, so it is still going.
  const CommandResult run =
      RunCommand(generate + " & pid=$!; while [ ! -d " + Quoted(table.string() + ".refine") +
                     " ]; do sleep 0.1; done; sleep 1; kill -INT $pid; wait $pid",
                 dir.path(), 120);
  EXPECT_EQ(run.exit_code, 130) << run.err;
  const std::regex said(
      "wrc generate: interrupted; all [0-9]+ solves of this run \\(grid points "
      "and interval midpoints\\) are saved in .*refined\\.h5\\.refine\\.");
  EXPECT_TRUE(std::regex_search(run.err, said)) << run.err;
  EXPECT_NE(run.err.find("--resume"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(table));
}

// `wrc study tables` interrupted while it generates: exit 130 and what was not written.
TEST(StudyInterrupt, ARefinedTableCutShortEndsTheStudyWith130) {
  const ScratchDir dir("wrc_study_sigint");
  const fs::path scene = CaseBuilder::Shipped("mbench_small.toml")
                             .Set("table.refine", "target", "0.01")
                             .Write(dir / "study.toml");
  const fs::path out = dir / "out";
  const std::string study = Quoted(WrcBinary().string()) + " study tables " +
                            Quoted(scene.string()) + " --targets 0.16 --samples 20 --threads 1" +
                            " --out " + Quoted(out.string());
  const CommandResult run = RunCommand(
      study + " & pid=$!; while [ ! -d " + Quoted((out / "refined_0.160000.h5.refine").string()) +
          " ]; do sleep 0.1; done; sleep 1; kill -INT $pid; wait $pid",
      dir.path(), 120);
  EXPECT_EQ(run.exit_code, 130) << run.err;
  EXPECT_NE(run.err.find("wrc study tables: interrupted while generating "), std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("the study's report is not written"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(out / "tables.md"));
}

}  // namespace
