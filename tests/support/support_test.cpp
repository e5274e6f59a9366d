// The shared test helpers themselves: a comparison that can fail must say where.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "tests/support/case_builder.h"
#include "tests/support/files.h"
#include "tests/support/near.h"
#include "tests/support/run.h"

namespace wrc::test_support {
namespace {

TEST(AllNear, PassesWithinTheToleranceAndNamesTheWorstEntryOutsideIt) {
  const std::vector<double> expected = {1.0, 2.0, 3.0, 4.0};
  EXPECT_TRUE(AllNear({1.0, 2.0 + 1e-13, 3.0, 4.0 - 1e-13}, expected, 1e-12));
  const ::testing::AssertionResult result = AllNear({1.0, 2.1, 3.5, 4.0}, expected, 0.2);
  ASSERT_FALSE(result);
  const std::string message = result.message();
  EXPECT_NE(message.find("1 of 4 values"), std::string::npos) << message;
  EXPECT_NE(message.find("index 2"), std::string::npos) << message;
}

TEST(AllNear, RefusesNanAndDifferentSizes) {
  EXPECT_FALSE(AllNear({1.0, NAN}, {1.0, 2.0}, 1e300));
  EXPECT_FALSE(AllNear({NAN}, {NAN}, 1.0));
  const ::testing::AssertionResult sizes = AllNear({1.0}, {1.0, 2.0}, 1.0);
  ASSERT_FALSE(sizes);
  EXPECT_NE(std::string(sizes.message()).find("sizes differ"), std::string::npos);
}

TEST(Files, RoundTripBytesAndQuoteForTheShell) {
  const ScratchDir dir("wrc_support");
  const std::string bytes = std::string("a\0b\r\n'q'", 8);
  EXPECT_EQ(ReadFile(WriteFile(dir / "x.bin", bytes)), bytes);
  // The quoted word reaches the program unchanged, quotes and spaces included.
  const std::string word = "it's a  path";
  const CommandResult echo = RunCommand("printf %s " + Quoted(word), dir.path());
  EXPECT_EQ(echo.exit_code, 0);
  EXPECT_EQ(echo.out, word);
}

TEST(RunCommand, CapturesBothStreamsAndTheExitCodeAndEndsAHang) {
  const ScratchDir dir("wrc_support");
  const CommandResult result = RunCommand("echo out; echo err >&2; exit 3", dir.path());
  EXPECT_EQ(result.exit_code, 3);
  EXPECT_EQ(result.out, "out\n");
  EXPECT_EQ(result.err, "err\n");
  EXPECT_EQ(RunCommand("sleep 30", dir.path(), 1).exit_code, 124);
}

TEST(CaseBuilder, SetsReplacesAddsAndRemovesKeysBySection) {
  const std::string text = CaseBuilder("[grid]\ndx = 0.5\nds = 0.5\n[state]\ny = 1.0\n")
                               .Set("grid", "dx", "0.25")
                               .Set("state", "yaw", "0.002")
                               .Set("friction", "mu", "0.3")
                               .Remove("grid", "ds")
                               .Remove("state", "absent")
                               .Text();
  EXPECT_EQ(text, "[grid]\ndx = 0.25\n[state]\nyaw = 0.002\ny = 1.0\n[friction]\nmu = 0.3\n");
}

TEST(CaseBuilder, AShippedCaseSolvesFromAnyDirectory) {
  const ScratchDir dir("wrc_support_case");
  const std::string text = CaseBuilder::Shipped("mbench_case.toml").Text();
  EXPECT_EQ(text.find("\"profiles/"), std::string::npos) << text;
  const auto path = CaseBuilder::Shipped("mbench_case.toml").Write(dir / "case.toml");
  const CommandResult solve = RunCommand(
      Quoted(WrcBinary().string()) + " solve " + Quoted(path.string()) + " --json", dir.path());
  EXPECT_EQ(solve.exit_code, 0) << solve.err;
  EXPECT_NE(solve.out.find("\"status\": \"ok\""), std::string::npos) << solve.out;
}

}  // namespace
}  // namespace wrc::test_support
