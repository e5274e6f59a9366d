// `wrc verify` on small tables: errors shrink when the table is refined, JSON per
// docs/reference/cli.md, wrc verify, the tolerance gate.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "tests/support/files.h"
#include "tests/support/run.h"

namespace {

namespace fs = std::filesystem;

std::string Wrc() { return std::string(WRC_BINARY_DIR) + "/wrc"; }

// Runs a command, returns its exit code and stdout.
int RunCommand(const std::string& command, std::string* out) {
  // One file per test process: ctest runs these tests side by side.
  const fs::path file =
      fs::temp_directory_path() / ("wrc_verify_test_stdout_" + std::to_string(::getpid()) + ".txt");
  const int status = std::system((command + " > '" + file.string() + "' 2>/dev/null").c_str());
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  *out = text.str();
  in.close();
  fs::remove(file);
  return WEXITSTATUS(status);
}

// A 1-D scene over the lateral shift on the Manchester pair (planar, coarse grid, tread
// contact only, so the outputs are smooth in y): step 1 mm against 0.5 mm.
fs::path WriteScene(const fs::path& dir, double step) {
  std::ostringstream t;
  t << "[problem]\ntype = \"wheel-rail\"\n[rail]\nprofile = \"" << WRC_SOURCE_DIR
    << "/tables/profiles/MBench_UIC60_v3.prr\"\n[wheel]\nprofile = \"" << WRC_SOURCE_DIR
    << "/tables/profiles/MBench_S1002_v3.prw\"\n[grid]\ndx = 0.5\nds = 0.5\n"
    << "[method]\nreference = \"planar\"\n[state]\nfz = 10000.0\nroll = 0.0\nyaw = 0.002\n"
    << "velocity = 2000.0\nspin = 0.001\n[table]\naxes = [\"y\"]\ny = {from = 0.0, to = 4.0, step "
       "= "
    << step << "}\noutputs = [\"fx\", \"fy\", \"fz\", \"z\"]\n";
  const fs::path path = dir / ("scene_" + std::to_string(static_cast<int>(step * 100)) + ".toml");
  std::ofstream(path) << t.str();
  return path;
}

TEST(Verify, ErrorsShrinkWhenTheTableIsRefined) {
  const fs::path dir = fs::temp_directory_path() / "wrc_verify_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  double rms[2] = {0.0, 0.0};
  int k = 0;
  for (double step : {1.0, 0.5}) {
    const fs::path scene = WriteScene(dir, step);
    const fs::path table = dir / ("table_" + std::to_string(k) + ".h5");
    std::string out;
    ASSERT_EQ(RunCommand(Wrc() + " generate '" + scene.string() + "' -o '" + table.string() +
                             "' --quiet --threads 2",
                         &out),
              0);
    ASSERT_EQ(
        RunCommand(Wrc() + " verify '" + table.string() + "' --samples 24 --seed 7 --json", &out),
        0);
    const nlohmann::json r = nlohmann::json::parse(out);
    EXPECT_EQ(r["samples"].get<int>(), 24);
    EXPECT_EQ(r["exact_status"]["ok"].get<int>(), 24);
    for (const char* key : {"max_abs", "rms", "p95_abs", "max_rel", "worst"}) {
      EXPECT_TRUE(r["outputs"]["fy"].contains(key)) << key;
    }
    rms[k++] = r["outputs"]["z"]["rms"].get<double>();
  }
  // Multilinear interpolation of a smooth function: the error falls ~4x per halving; ask for 2x.
  EXPECT_GT(rms[0], 0.0);
  EXPECT_LT(rms[1], 0.5 * rms[0]) << rms[0] << " " << rms[1];

  // The tolerance gate: an impossible tolerance fails with exit 1.
  std::string out;
  EXPECT_EQ(RunCommand(Wrc() + " verify '" + (dir / "table_0.h5").string() +
                           "' --samples 4 --tolerance 1e-12",
                       &out),
            1);
  EXPECT_NE(out.find("EXCEEDED by fx (max_rel"), std::string::npos) << out;
  EXPECT_EQ(RunCommand(Wrc() + " verify '" + (dir / "missing.h5").string() + "'", &out), 2);
  // A tolerance that is no number >= 0 would silently disable the gate: a command-line error.
  for (const char* tolerance : {"-1", "nan", "-inf", "inf"}) {
    EXPECT_EQ(RunCommand(Wrc() + " verify '" + (dir / "table_0.h5").string() +
                             "' --samples 2 --tolerance=" + tolerance,
                         &out),
              2)
        << tolerance;
  }
  // A seed CLI11 would wrap (-1) or saturate (2^64) would verify at other points than asked.
  for (const char* seed : {"-1", "18446744073709551616"}) {
    EXPECT_EQ(RunCommand(Wrc() + " verify '" + (dir / "table_0.h5").string() +
                             "' --samples 2 --seed=" + seed,
                         &out),
              2)
        << seed;
  }
}

// fz prescribed in [state] and stored varies only by the vertical-force iteration's tolerance
// (1e-6 of the load); dividing its error by that range would fail every gate. Its max_rel is
// relative to a thousandth of the load at least.
TEST(Verify, PrescribedLoadDoesNotFailTheGate) {
  const fs::path dir = fs::temp_directory_path() / "wrc_verify_prescribed";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path table = dir / "table.h5";
  std::string out;
  ASSERT_EQ(RunCommand(Wrc() + " generate '" + WriteScene(dir, 1.0).string() + "' -o '" +
                           table.string() + "' --quiet --threads 2",
                       &out),
            0);
  ASSERT_EQ(RunCommand(Wrc() + " verify '" + table.string() + "' --samples 8 --json", &out), 0);
  const nlohmann::json fz = nlohmann::json::parse(out)["outputs"]["fz"];
  EXPECT_GE(fz["scale"].get<double>(), 10.0);  // 1e-3 of 10 kN
  EXPECT_LT(fz["range"].get<double>(), 1.0);
  EXPECT_LT(fz["max_rel"].get<double>(), 1e-3);
}

// A table whose every exact solve fails (here every point: the wheel is nowhere above the rail)
// verifies nothing: an error naming the first failure, and no output "meets" a tolerance.
TEST(Verify, NothingVerifiedIsAnError) {
  const fs::path dir = fs::temp_directory_path() / "wrc_verify_nothing";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path scene = WriteScene(dir, 1.0);
  std::ifstream in(scene);
  std::stringstream text;
  text << in.rdbuf();
  std::string shifted = text.str();
  shifted.replace(shifted.find("from = 0.0, to = 4.0"), 20, "from = 200.0, to = 202.0");
  std::ofstream(dir / "away.toml") << shifted;
  const fs::path table = dir / "away.h5";
  std::string out;
  ASSERT_EQ(RunCommand(Wrc() + " generate '" + (dir / "away.toml").string() + "' -o '" +
                           table.string() + "' --quiet --threads 2",
                       &out),
            0);
  EXPECT_EQ(
      RunCommand(Wrc() + " verify '" + table.string() + "' --samples 3 --tolerance 0.5", &out), 2);
  EXPECT_NE(out.find("first failed exact solve:"), std::string::npos) << out;
  EXPECT_NE(out.find("nowhere above the rail"), std::string::npos) << out;
  EXPECT_NE(out.find("EXCEEDED by fx (no point compared)"), std::string::npos) << out;
  EXPECT_EQ(RunCommand(Wrc() + " verify '" + table.string() + "' --samples 3 --json", &out), 2);
  const nlohmann::json report = nlohmann::json::parse(out);
  EXPECT_TRUE(report["outputs"]["fy"]["max_rel"].is_null());
  EXPECT_EQ(report["exact_status"]["error"].get<int>(), 3);
}

// Sample counts outside 1 to a million say so in words, not as CLI11's range of doubles: a
// billion would grow the report without bound.
TEST(Verify, ASampleCountOutOfRangeIsRefusedInWords) {
  const wrc::test_support::ScratchDir dir("wrc_verify_cli");
  for (const char* samples : {"0", "-3", "1000001", "1000000000"}) {
    const wrc::test_support::CommandResult run =
        wrc::test_support::RunCommand(Wrc() + " verify table.h5 --samples " + samples, dir.path());
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_NE(run.err.find(std::string("--samples: must be 1 to 1000000, is ") + samples),
              std::string::npos)
        << run.err;
    EXPECT_EQ(run.err.find("1797693"), std::string::npos) << run.err;
  }
}

// Ctrl-C stops the exact solves cleanly: a message saying how far it got, exit 130, no file.
TEST(Verify, SigintStopsWithAMessageAndWritesNothing) {
  const wrc::test_support::ScratchDir dir("wrc_verify_sigint");
  const fs::path scene = WriteScene(dir.path(), 1.0);
  const fs::path table = dir / "table.h5";
  std::string out;
  ASSERT_EQ(RunCommand(Wrc() + " generate '" + scene.string() + "' -o '" + table.string() +
                           "' --quiet --threads 1",
                       &out),
            0);
  // Far more samples than finish in the 2 s before the signal; the table opens in milliseconds.
  const std::string verify = Wrc() + " verify '" + table.string() +
                             "' --samples 100000 --threads 1 --csv '" + (dir / "out.csv").string() +
                             "'";
  const wrc::test_support::CommandResult run = wrc::test_support::RunCommand(
      verify + " & pid=$!; sleep 2; kill -INT $pid; wait $pid", dir.path());
  EXPECT_EQ(run.exit_code, 130) << run.err;
  EXPECT_NE(run.err.find("wrc verify: interrupted after "), std::string::npos) << run.err;
  EXPECT_NE(run.err.find(" of 100000 exact solves; no report or file written"), std::string::npos)
      << run.err;
  EXPECT_FALSE(fs::exists(dir / "out.csv"));
}

}  // namespace
