// Results checked before they are called ok, and inputs range-checked where they are read:
// absurd grids, speeds and angles are errors naming their key; a contact cut off by the
// potential contact area, a coarse patch and every profile repair are warnings in the JSON.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>

#include "tests/support/files.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kWrc = fs::path(WRC_BINARY_DIR) / "wrc";
const fs::path kHalfspaceCase =
    fs::path(WRC_TEST_DATA_DIR) / "reference" / "cases" / "halfspace" / "ab03_ceta0.003.toml";
const fs::path kProfiles = fs::path(WRC_SOURCE_DIR) / "tables" / "profiles";

using wrc::test_support::ReadFile;

struct Outcome {
  int exit_code = -1;
  std::string out, err;
};

class CliResults : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("wrc_cli_results_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  Outcome Solve(const std::string& text, const std::string& flags = " --json") const {
    const fs::path path = dir_ / "case.toml";
    std::ofstream(path) << text;
    const std::string command = "'" + kWrc.string() + "' solve '" + path.string() + "'" + flags +
                                " >'" + (dir_ / "out").string() + "' 2>'" +
                                (dir_ / "err").string() + "'";
    const int status = std::system(command.c_str());
    Outcome outcome;
    if (status != -1 && WIFEXITED(status)) outcome.exit_code = WEXITSTATUS(status);
    outcome.out = ReadFile(dir_ / "out");
    outcome.err = ReadFile(dir_ / "err");
    return outcome;
  }

  // The reference half-space case with the line starting `key =` replaced.
  static std::string HalfspaceWith(const std::string& key, const std::string& line) {
    return std::regex_replace(ReadFile(kHalfspaceCase), std::regex("\n" + key + " = [^\n]*"),
                              "\n" + line);
  }

  // A wheel-rail case on the Manchester benchmark profiles, with a rail profile of choice;
  // 2 m/s unless `state` gives its own velocity.
  static std::string WheelRail(const std::string& state, const fs::path& rail) {
    const std::string velocity =
        state.find("velocity") == std::string::npos ? "velocity = 2000.0\n" : "";
    return "[problem]\ntype = \"wheel-rail\"\n[rail]\nprofile = \"" + rail.string() +
           "\"\n[wheel]\nprofile = \"" + (kProfiles / "MBench_S1002_v3.prw").string() +
           "\"\n[grid]\ndx = 1.0\nds = 1.0\n[state]\nfz = 10000.0\n" + velocity + state + "\n";
  }

  fs::path dir_;
};

void ExpectErrorNaming(const Outcome& outcome, const std::string& key) {
  EXPECT_EQ(outcome.exit_code, 2) << outcome.err;
  EXPECT_NE(outcome.err.find(key), std::string::npos) << outcome.err;
}

TEST_F(CliResults, AGridRangeThatWouldWrapTheElementCountIsAnError) {
  const std::string text = std::regex_replace(
      HalfspaceWith("dx", "dx = 1.0"), std::regex("\nx = [^\n]*"), "\nx = [0.0, 4294967297.0]");
  ExpectErrorNaming(Solve(text), "grid.x = [0, 4294967297]: holds 4294967297 elements");
}

TEST_F(CliResults, AnElementOfAKilometreIsAnError) {
  ExpectErrorNaming(Solve(HalfspaceWith("dx", "dx = 1e6")), "grid.dx = 1e+06: must be between");
}

TEST_F(CliResults, ARollPastDerailmentNamesStateRoll) {
  ExpectErrorNaming(Solve(WheelRail("roll = 0.19", kProfiles / "MBench_UIC60_v3.prr")),
                    "state.roll = 0.19: more than 0.1 rad");
}

TEST_F(CliResults, AnAbsurdVelocityNamesStateVelocity) {
  ExpectErrorNaming(Solve(WheelRail("velocity = 1e200", kProfiles / "MBench_UIC60_v3.prr")),
                    "state.velocity = 1e+200");
}

TEST_F(CliResults, HugeCreepageAndTinyFrictionAreErrors) {
  ExpectErrorNaming(Solve(HalfspaceWith("ceta", "ceta = 1e30")), "state.ceta");
  ExpectErrorNaming(Solve(HalfspaceWith("mu", "mu = 1e-300")), "friction.mu");
  ExpectErrorNaming(Solve(HalfspaceWith("fn", "fn = 1e-300")), "state.fn");
}

TEST_F(CliResults, AnAcceptableCaseHasAnEmptyWarningsArray) {
  const Outcome outcome = Solve(ReadFile(kHalfspaceCase));
  ASSERT_EQ(outcome.exit_code, 0) << outcome.err;
  const json result = json::parse(outcome.out);
  ASSERT_TRUE(result.contains("warnings"));
  EXPECT_TRUE(result["warnings"].empty()) << result["warnings"];
}

TEST_F(CliResults, APotentialAreaTooSmallIsAWarning) {
  const std::string text = std::regex_replace(HalfspaceWith("x", "x = [-0.54, 0.54]"),
                                              std::regex("\ny = [^\n]*"), "\ny = [-0.62, 0.62]");
  const Outcome outcome = Solve(text);
  const json result = json::parse(outcome.out);
  const std::string warnings = result["warnings"].dump();
  EXPECT_NE(warnings.find("edge of the potential contact area"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("elements across the contact patch"), std::string::npos) << warnings;
  // And on stderr in text mode.
  EXPECT_NE(Solve(text, "").err.find("warning: the contact reaches the edge"), std::string::npos);
}

TEST_F(CliResults, APotentialAreaOffsetFromTheContactIsAWarning) {
  const Outcome outcome = Solve(HalfspaceWith("x", "x = [2.0, 6.0]"));
  const std::string warnings = json::parse(outcome.out)["warnings"].dump();
  EXPECT_NE(warnings.find("edge of the potential contact area"), std::string::npos) << warnings;
}

TEST_F(CliResults, AnAbsurdlyFineWheelRailGridIsAnErrorNotBadAlloc) {
  std::string text = WheelRail("", kProfiles / "MBench_UIC60_v3.prr");
  text = std::regex_replace(text, std::regex("dx = 1.0\nds = 1.0"), "dx = 0.0001\nds = 0.0001");
  const Outcome outcome = Solve(text, "");
  ExpectErrorNaming(outcome, "more than the limit of 200000: coarsen grid.dx/grid.ds");
  EXPECT_EQ(outcome.err.find("bad_alloc"), std::string::npos) << outcome.err;
}

TEST_F(CliResults, ACoarseWheelRailPatchIsAWarning) {
  std::string text = WheelRail("", kProfiles / "MBench_UIC60_v3.prr");
  text = std::regex_replace(text, std::regex("dx = 1.0\nds = 1.0"), "dx = 6.0\nds = 6.0");
  const Outcome outcome = Solve(text);
  ASSERT_EQ(outcome.exit_code, 0) << outcome.err;
  const std::string warnings = json::parse(outcome.out)["warnings"].dump();
  EXPECT_NE(warnings.find("patch 1 has only 1 x 1 elements across it"), std::string::npos)
      << warnings;
}

// Coarse along x only: the tread patch (about 12 mm long) gets 2 or 3 columns but
// a dozen or more rows at ds = 0.1, so more than 16 elements in contact; too few across x is
// still a warning.
TEST_F(CliResults, AWheelRailPatchCoarseAlongXOnlyIsAWarning) {
  std::string text = WheelRail("", kProfiles / "MBench_UIC60_v3.prr");
  text = std::regex_replace(text, std::regex("dx = 1.0\nds = 1.0"), "dx = 6.0\nds = 0.1");
  const Outcome outcome = Solve(text);
  ASSERT_EQ(outcome.exit_code, 0) << outcome.err;
  const json result = json::parse(outcome.out);
  ASSERT_EQ(result["patches"].size(), 1u);
  EXPECT_GE(result["patches"][0]["n_contact"].get<int>(), 16);
  const std::string warnings = result["warnings"].dump();
  EXPECT_NE(warnings.find("elements across it (fewer than 4 along x or s)"), std::string::npos)
      << warnings;
}

// A rail profile with one point moved back across its neighbour: the zig-zag is repaired, and
// the result says so.
TEST_F(CliResults, ProfileRepairsAreWarnings) {
  std::istringstream in(ReadFile(kProfiles / "MBench_UIC60_v3.prr"));
  std::ofstream out(dir_ / "zigzag.prr");
  int line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    out << line << '\n';
    if (line_number == 300) {
      std::istringstream fields(line);
      double y = 0.0, z = 0.0;
      fields >> y >> z;
      out << y - 0.3 << '\t' << z << '\n';
    }
  }
  out.close();
  const Outcome outcome = Solve(WheelRail("", dir_ / "zigzag.prr"));
  ASSERT_EQ(outcome.exit_code, 0) << outcome.err;
  const std::string warnings = json::parse(outcome.out)["warnings"].dump();
  EXPECT_NE(warnings.find("zig-zag at lines 300 and 301"), std::string::npos) << warnings;
}

}  // namespace
