// Files and paths as a hostile user gives them to `wrc solve` and `wrc info`: inputs that are
// FIFOs or devices are refused without blocking, a full standard output is an error, and --out
// never replaces something that is not a regular file.

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/files.h"
#include "tests/tools/tool_test_util.h"

namespace {

namespace fs = std::filesystem;

const fs::path kWrc = fs::path(WRC_BINARY_DIR) / "wrc";
const fs::path kCase =
    fs::path(WRC_TEST_DATA_DIR) / "reference" / "cases" / "halfspace" / "ab03_ceta0.003.toml";

struct Outcome {
  int exit_code = -1;
  std::string err;
};

using wrc::test_support::Quoted;

class CliFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("wrc_cli_files_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs `wrc ARGS` with stdout sent to `out`; `timeout 20` turns a hang into exit 124.
  Outcome Run(const std::string& args, const std::string& out = "/dev/null") const {
    const fs::path err = dir_ / "stderr";
    const std::string command = "timeout 20 " + Quoted(kWrc.string()) + " " + args + " >" +
                                Quoted(out) + " 2>" + Quoted(err.string());
    const int status = std::system(command.c_str());
    Outcome outcome;
    if (status != -1 && WIFEXITED(status)) outcome.exit_code = WEXITSTATUS(status);
    outcome.err = wrc::test_support::ReadFile(err);
    return outcome;
  }

  fs::path dir_;
};

TEST_F(CliFiles, CaseThatIsAFifoIsRefusedWithoutBlocking) {
  const fs::path fifo = dir_ / "case.toml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const Outcome outcome = Run("solve " + Quoted(fifo.string()));
  EXPECT_EQ(outcome.exit_code, 2) << outcome.err;
  EXPECT_NE(outcome.err.find("not a regular file"), std::string::npos) << outcome.err;
}

TEST_F(CliFiles, CaseThatIsADeviceIsRefused) {
  const Outcome outcome = Run("solve /dev/zero");
  EXPECT_EQ(outcome.exit_code, 2) << outcome.err;
  EXPECT_NE(outcome.err.find("/dev/zero: is not a regular file"), std::string::npos) << outcome.err;
}

TEST_F(CliFiles, TableThatIsAFifoIsRefusedWithoutBlocking) {
  const fs::path fifo = dir_ / "table.h5";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const Outcome outcome = Run("info " + Quoted(fifo.string()));
  EXPECT_EQ(outcome.exit_code, 2) << outcome.err;
  EXPECT_NE(outcome.err.find("not a regular file"), std::string::npos) << outcome.err;
}

TEST_F(CliFiles, FullStandardOutputIsAnError) {
  for (const std::string flags : {"", " --json"}) {
    const Outcome outcome = Run("solve " + Quoted(kCase.string()) + flags, "/dev/full");
    EXPECT_EQ(outcome.exit_code, 2) << flags << ": " << outcome.err;
    EXPECT_NE(outcome.err.find("standard output"), std::string::npos) << outcome.err;
  }
}

TEST_F(CliFiles, OutFilesNeverReplaceAFifo) {
  const fs::path out = dir_ / "fields";
  fs::create_directories(out);
  ASSERT_EQ(::mkfifo((out / "fields.csv").c_str(), 0600), 0);
  const Outcome outcome = Run("solve " + Quoted(kCase.string()) + " --out " + Quoted(out.string()));
  EXPECT_EQ(outcome.exit_code, 2) << outcome.err;
  EXPECT_NE(outcome.err.find("is a FIFO"), std::string::npos) << outcome.err;
  EXPECT_TRUE(fs::is_fifo(out / "fields.csv"));
  EXPECT_FALSE(fs::exists(out / "fields.csv.tmp"));
}

TEST_F(CliFiles, OutFilesAreWrittenWhole) {
  const fs::path out = dir_ / "fields";
  const Outcome outcome = Run("solve " + Quoted(kCase.string()) + " --out " + Quoted(out.string()));
  ASSERT_EQ(outcome.exit_code, 0) << outcome.err;
  EXPECT_GT(fs::file_size(out / "fields.csv"), 1000u);
  EXPECT_GT(fs::file_size(out / "summary.json"), 10u);
  EXPECT_FALSE(fs::exists(out / "fields.csv.tmp"));
}

// A file-size limit (64 blocks of 512 bytes in sh) makes the writes of the 97 KB fields.csv fail
// (EFBIG) as a full disk would.
TEST_F(CliFiles, OutOnAFullDiskIsAnErrorAndLeavesNoFile) {
  const fs::path out = dir_ / "fields";
  const std::string command = "ulimit -f 64; trap '' XFSZ; timeout 20 " + Quoted(kWrc.string()) +
                              " solve " + Quoted(kCase.string()) + " --out " +
                              Quoted(out.string()) + " >/dev/null 2>" +
                              Quoted((dir_ / "stderr").string());
  const int status = std::system(("sh -c " + Quoted(command)).c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_FALSE(fs::exists(out / "fields.csv"));
  EXPECT_FALSE(fs::exists(out / "fields.csv.tmp"));
}

// Pictures go through the same checks: on a disk that fills up while the data is written (32 KB
// limit) or while gnuplot draws the 64 KB PNG (50 KB limit), the command fails naming the file
// and leaves no part of it; without gnuplot the data is written and the picture is skipped
// with a warning.
TEST_F(CliFiles, PicturesOnAFullDiskAreErrorsAndLeaveNoFile) {
  const fs::path scene = fs::path(WRC_SOURCE_DIR) / "tables" / "mbench_case.toml";
  for (const int blocks : {64, 100}) {
    const fs::path out = dir_ / ("plot" + std::to_string(blocks));
    const std::string command =
        "ulimit -f " + std::to_string(blocks) + "; trap '' XFSZ; timeout 60 " +
        Quoted(kWrc.string()) + " plot profiles " + Quoted(scene.string()) + " --out " +
        Quoted(out.string()) + " >/dev/null 2>" + Quoted((dir_ / "stderr").string());
    const int status = std::system(("sh -c " + Quoted(command)).c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 2) << blocks;
    const std::string err = wrc::tool_test::ReadFile(dir_ / "stderr");
    EXPECT_NE(err.find(blocks == 64 ? "profiles_gap.dat" : "could not draw"), std::string::npos)
        << err;
    EXPECT_FALSE(fs::exists(out / "profiles.png")) << blocks;
    for (const auto& entry : fs::directory_iterator(out)) {
      EXPECT_NE(entry.path().extension(), ".tmp") << entry.path();
      EXPECT_GT(fs::file_size(entry.path()), 0u) << entry.path();
    }
  }
  const fs::path out = dir_ / "no_gnuplot";
  const std::string command = "timeout 60 env PATH=/nonexistent " + Quoted(kWrc.string()) +
                              " plot profiles " + Quoted(scene.string()) + " --out " +
                              Quoted(out.string()) + " >/dev/null 2>" +
                              Quoted((dir_ / "stderr").string());
  const int status = std::system(("sh -c " + Quoted(command)).c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_NE(wrc::tool_test::ReadFile(dir_ / "stderr").find("gnuplot is not installed"),
            std::string::npos);
  EXPECT_TRUE(fs::exists(out / "profiles_gap.dat"));
  EXPECT_FALSE(fs::exists(out / "profiles.png"));
}

// A command never writes onto one of its inputs, under any spelling of the path: the table
// onto its scene or profile, verify's CSV or map onto the table.
TEST_F(CliFiles, OutputsNeverOverwriteTheirInputs) {
  const fs::path profiles = fs::path(WRC_SOURCE_DIR) / "tables" / "profiles";
  fs::copy_file(profiles / "MBench_UIC60_v3.prr", dir_ / "rail.prr");
  const std::string scene_text =
      "[problem]\ntype = \"wheel-rail\"\n[rail]\nprofile = \"rail.prr\"\n[wheel]\nprofile = \"" +
      (profiles / "MBench_S1002_v3.prw").string() +
      "\"\n[grid]\ndx = 0.5\nds = 0.5\n[method]\nreference = \"planar\"\n[state]\nfz = "
      "10000.0\nyaw = 0.002\nvelocity = 2000.0\n[table]\naxes = [\"y\"]\ny = [0.0, 1.0]\n"
      "outputs = [\"fy\"]\n";
  const fs::path scene = dir_ / "scene.toml";
  std::ofstream(scene) << scene_text;
  const std::string rail_text = wrc::tool_test::ReadFile(dir_ / "rail.prr");
  const std::vector<std::string> outputs = {"scene.toml", "./scene.toml", "rail.prr",
                                            "../" + dir_.filename().string() + "/rail.prr"};
  for (const std::string& output : outputs) {
    const Outcome outcome =
        Run("generate " + Quoted(scene.string()) + " -o " + Quoted((dir_ / output).string()));
    EXPECT_EQ(outcome.exit_code, 2) << output << ": " << outcome.err;
    EXPECT_NE(outcome.err.find("is also an input"), std::string::npos) << outcome.err;
  }
  EXPECT_EQ(wrc::tool_test::ReadFile(scene), scene_text);
  EXPECT_EQ(wrc::tool_test::ReadFile(dir_ / "rail.prr"), rail_text);

  const fs::path table = dir_ / "table.h5";
  ASSERT_EQ(Run("generate " + Quoted(scene.string()) + " -o " + Quoted(table.string()) + " --quiet")
                .exit_code,
            0);
  const auto table_size = fs::file_size(table);
  const std::vector<std::string> verify_outputs = {" --csv " + Quoted(table.string()),
                                                   " --map y,y --png " + Quoted(table.string())};
  for (const std::string& args : verify_outputs) {
    const Outcome outcome = Run("verify " + Quoted(table.string()) + " --samples 2" + args);
    EXPECT_EQ(outcome.exit_code, 2) << args << ": " << outcome.err;
    EXPECT_NE(outcome.err.find("is also an input"), std::string::npos) << outcome.err;
  }
  EXPECT_EQ(fs::file_size(table), table_size);
  EXPECT_EQ(Run("info " + Quoted(table.string())).exit_code, 0);
}

// Thread counts far beyond any machine fail to start (the system's thread limit) and ended in
// std::terminate; every --threads takes 1 … 1024 (0 where it means all cores) and says so.
TEST_F(CliFiles, ThreadCountsBeyondTheLimitAreRefusedInWords) {
  const std::string scene = Quoted((fs::path(WRC_SOURCE_DIR) / "tables" / "demo.toml").string());
  const std::string table = Quoted((dir_ / "t.h5").string());
  for (const std::string& args :
       {"generate " + scene + " -o " + table + " --threads 100000",
        "generate " + scene + " -o " + table + " --threads 0",
        "verify " + table + " --threads 1025", "verify " + table + " --threads -3",
        "study tables " + scene + " --threads 5000",
        "study stability " + Quoted(kCase.string()) + " --threads 2.5"}) {
    const Outcome outcome = Run(args);
    EXPECT_EQ(outcome.exit_code, 2) << args << ": " << outcome.err;
    EXPECT_NE(outcome.err.find("--threads: must be"), std::string::npos)
        << args << ": " << outcome.err;
    EXPECT_NE(outcome.err.find("1024"), std::string::npos) << args << ": " << outcome.err;
  }
  EXPECT_FALSE(fs::exists(dir_ / "t.h5"));
}

}  // namespace
