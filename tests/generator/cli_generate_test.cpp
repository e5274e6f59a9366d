// `wrc generate` and `wrc info` as users run them: the real binary, killed with SIGKILL or
// interrupted with SIGINT half-way and resumed, under mpirun, and on bad input.

#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <chrono>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "generator/journal.h"
#include "tests/generator/generator_test_util.h"
#include "wrc/generator.h"
#include "wrc/scene.h"

extern char** environ;

namespace wrc {
namespace {

using test::Quoted;
using test::ScratchDir;
namespace fs = std::filesystem;

// 4 × 10 points: long enough (a second or more) to be caught half-way.
std::string KillScene() {
  return test::TinyScene(
      "axes = [\"yaw\", \"y\"]\nyaw = [-0.004, 0.0, 0.002, 0.004]\n"
      "y = {from = 0.0, to = 4.5, step = 0.5}\noutputs = [\"fx\", \"fy\", \"fz\", \"z\"]");
}

// Starts `wrc generate` without a shell, so that signals reach it directly.
pid_t Spawn(const std::vector<std::string>& arguments) {
  std::vector<char*> argv;
  const std::string binary = test::WrcBinary();
  argv.push_back(const_cast<char*>(binary.c_str()));
  for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  const int error = posix_spawn(&pid, binary.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  EXPECT_EQ(error, 0) << "cannot start " << binary;
  return pid;
}

// Records in the journal so far (0 while it does not exist yet).
std::size_t JournalRecords(const fs::path& journal) {
  if (!fs::exists(journal)) return 0;
  try {
    return gen::ParseJournal(test::ReadFile(journal), journal.string()).records.size();
  } catch (const std::exception&) {
    return 0;  // caught between creating the file and writing its header
  }
}

// Waits until the journal holds at least n records; false if the process ended first.
bool WaitForRecords(pid_t pid, const fs::path& journal, std::size_t n) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline) {
    if (JournalRecords(journal) >= n) return true;
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return false;
}

int WaitExitCode(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string Generate(const fs::path& scene, const fs::path& table, const std::string& extra = "") {
  return Quoted(test::WrcBinary()) + " generate " + Quoted(scene.string()) + " -o " +
         Quoted(table.string()) + " " + extra;
}

// A table of the kill scene generated in one go, shared by the tests below.
class CliGenerateTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new ScratchDir("cli_generate");
    scene_ = test::WriteFile(*dir_ / "kill.toml", KillScene());
    reference_ = *dir_ / "reference.h5";
    const test::CommandResult result =
        test::RunCommand(Generate(scene_, reference_, "--threads 2"), dir_->path());
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.out.find("40 points (40 ok"), std::string::npos) << result.out;
  }
  static void TearDownTestSuite() { delete dir_; }
  static ScratchDir* dir_;
  static fs::path scene_, reference_;
};
ScratchDir* CliGenerateTest::dir_ = nullptr;
fs::path CliGenerateTest::scene_;
fs::path CliGenerateTest::reference_;

TEST_F(CliGenerateTest, KilledWithSigkillAndResumedGivesTheSameTable) {
  const fs::path table = *dir_ / "killed.h5";
  const fs::path journal = table.string() + ".journal";
  const pid_t pid = Spawn({"generate", scene_.string(), "-o", table.string(), "--threads", "1"});
  ASSERT_TRUE(WaitForRecords(pid, journal, 4)) << "the run ended before it could be killed";
  kill(pid, SIGKILL);
  EXPECT_EQ(WaitExitCode(pid), 128 + SIGKILL);
  const std::size_t saved = JournalRecords(journal);
  EXPECT_GE(saved, 4u);
  EXPECT_LT(saved, 40u);
  EXPECT_FALSE(fs::exists(table));

  const test::CommandResult resumed =
      test::RunCommand(Generate(scene_, table, "--resume --threads 2"), dir_->path());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.out.find("reused from the journal"), std::string::npos) << resumed.out;
  EXPECT_FALSE(fs::exists(journal));
  test::ExpectIdenticalTables(reference_, table);
}

TEST_F(CliGenerateTest, SigintStopsCleanlyAndTellsHowToResume) {
  const fs::path table = *dir_ / "interrupted.h5";
  const fs::path journal = table.string() + ".journal";
  const pid_t pid = Spawn({"generate", scene_.string(), "-o", table.string(), "--threads", "2"});
  ASSERT_TRUE(WaitForRecords(pid, journal, 2)) << "the run ended before it could be interrupted";
  kill(pid, SIGINT);
  EXPECT_EQ(WaitExitCode(pid), 130);
  EXPECT_FALSE(fs::exists(table));
  // The journal holds every point that finished, nothing torn.
  const gen::JournalContents contents = gen::ParseJournal(test::ReadFile(journal), "j");
  EXPECT_EQ(contents.valid_bytes, contents.file_bytes);
  EXPECT_GE(contents.records.size(), 2u);

  // The same again through a shell, to see the message.
  const test::CommandResult refused = test::RunCommand(Generate(scene_, table), dir_->path());
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("--resume"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("interrupted.h5.journal"), std::string::npos) << refused.err;

  const test::CommandResult resumed =
      test::RunCommand(Generate(scene_, table, "--resume --quiet"), dir_->path());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  test::ExpectIdenticalTables(reference_, table);
}

TEST_F(CliGenerateTest, InterruptionMessageNamesTheResumeCommand) {
  // A journal left by an in-process run cut short, continued by the CLI, interrupted again by
  // SIGTERM: the message must give the command to continue.
  const fs::path table = *dir_ / "message.h5";
  const pid_t pid = Spawn({"generate", scene_.string(), "-o", table.string(), "--threads", "1"});
  ASSERT_TRUE(WaitForRecords(pid, table.string() + ".journal", 1));
  kill(pid, SIGTERM);
  EXPECT_EQ(WaitExitCode(pid), 130);
  const test::CommandResult resumed =
      test::RunCommand(Generate(scene_, table, "--resume --threads 1"), dir_->path());
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  test::ExpectIdenticalTables(reference_, table);
}

TEST_F(CliGenerateTest, TwoMpiRanksGiveTheSameTableAsOneProcess) {
  if (!GeneratorSupportsMpi()) GTEST_SKIP() << "wrc was built without MPI support";
  const fs::path table = *dir_ / "mpi.h5";
  const std::string mpirun = "mpirun --allow-run-as-root --oversubscribe -n 2 ";
  const test::CommandResult result =
      test::RunCommand(mpirun + Generate(scene_, table, "--threads 1 --quiet"), dir_->path());
  ASSERT_EQ(result.exit_code, 0) << result.out << result.err;
  EXPECT_NE(result.out.find("2 MPI ranks"), std::string::npos) << result.out;
  test::ExpectIdenticalTables(reference_, table);

  // Resume under MPI from a journal of an interrupted single-process run: rank 0 takes the
  // journal over, the others compute what is missing.
  const fs::path resumed = *dir_ / "mpi_resumed.h5";
  GenerateOptions options;
  options.output = resumed;
  options.threads = 1;
  options.max_points = 7;
  options.progress = ProgressMode::kOff;
  options.mpi = MpiMode::kOff;
  const GenerateSummary partial = GenerateTable(LoadScene(scene_), options);
  ASSERT_FALSE(partial.complete);
  const test::CommandResult finished = test::RunCommand(
      mpirun + Generate(scene_, resumed, "--threads 1 --quiet --resume"), dir_->path());
  ASSERT_EQ(finished.exit_code, 0) << finished.out << finished.err;
  EXPECT_NE(finished.out.find("7 points reused"), std::string::npos) << finished.out;
  test::ExpectIdenticalTables(reference_, resumed);
}

TEST_F(CliGenerateTest, ResumingWithAnotherSceneIsRefused) {
  const fs::path table = *dir_ / "other.h5";
  const fs::path other_scene = test::WriteFile(*dir_ / "other.toml", KillScene() + "# edited\n");
  GenerateOptions options;
  options.output = table;
  options.threads = 1;
  options.max_points = 1;
  options.progress = ProgressMode::kOff;
  options.mpi = MpiMode::kOff;
  GenerateTable(LoadScene(scene_), options);
  const test::CommandResult result =
      test::RunCommand(Generate(other_scene, table, "--resume"), dir_->path());
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("different"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("other.h5.journal"), std::string::npos) << result.err;
}

TEST_F(CliGenerateTest, InfoDescribesTheTable) {
  const test::CommandResult json_result = test::RunCommand(
      Quoted(test::WrcBinary()) + " info " + Quoted(reference_.string()) + " --json", dir_->path());
  ASSERT_EQ(json_result.exit_code, 0) << json_result.err;
  const nlohmann::json info = nlohmann::json::parse(json_result.out);
  EXPECT_EQ(info["format"], "wrc-table");
  EXPECT_EQ(info["format_version"], 1);
  EXPECT_EQ(info["points"], 40);
  ASSERT_EQ(info["axes"].size(), 2u);
  EXPECT_EQ(info["axes"][0]["name"], "yaw");
  EXPECT_EQ(info["axes"][1]["name"], "y");
  EXPECT_EQ(info["axes"][1]["size"], 10);
  EXPECT_EQ(info["axes"][1]["min"], 0.0);
  EXPECT_EQ(info["axes"][1]["max"], 4.5);
  EXPECT_EQ(info["axes"][1]["unit"], "mm");
  ASSERT_EQ(info["outputs"].size(), 4u);
  EXPECT_EQ(info["outputs"][3]["name"], "z");
  EXPECT_EQ(info["outputs"][0]["unit"], "N");
  EXPECT_EQ(info["status"]["ok"], 40);
  EXPECT_EQ(info["status"]["error"], 0);
  EXPECT_EQ(info["attributes"]["scene"], KillScene());
  EXPECT_EQ(info["attributes"]["rail_profile_sha256"].get<std::string>().size(), 64u);
  EXPECT_EQ(info["profiles"]["wheel"]["name"], "MBench_S1002_v3.prw");
  // fz is prescribed: every ok point meets it to the solver's relative tolerance 1e-7.
  EXPECT_NEAR(info["outputs"][2]["min"].get<double>(), 10000.0, 1e-3);

  const test::CommandResult human = test::RunCommand(
      Quoted(test::WrcBinary()) + " info " + Quoted(reference_.string()), dir_->path());
  EXPECT_EQ(human.exit_code, 0);
  EXPECT_NE(human.out.find("status: ok 40"), std::string::npos) << human.out;
}

TEST(CliGenerateErrors, BadInputExitsWith2AndSaysWhy) {
  ScratchDir dir("cli_errors");
  struct Case {
    std::string scene_text, expected;
  };
  const std::vector<Case> cases = {
      {"[problem\n", "bad.toml"},
      {test::TinyScene("axes = [\"why\"]\nwhy = [1.0]"), "unknown axis"},
      {test::TinyScene("axes = [\"y\"]\ny = {from = 1.0, to = 0.0, step = 0.5}"), "table.y"},
      {test::TinyScene("axes = [\"y\"]\ny = [0.0]\noutputs = [\"fq\"]"), "unknown output"},
  };
  for (const Case& c : cases) {
    const fs::path scene = test::WriteFile(dir / "bad.toml", c.scene_text);
    const test::CommandResult result =
        test::RunCommand(Generate(scene, dir / "bad.h5"), dir.path());
    EXPECT_EQ(result.exit_code, 2) << c.scene_text;
    EXPECT_NE(result.err.find(c.expected), std::string::npos) << result.err;
    EXPECT_FALSE(fs::exists(dir / "bad.h5"));
    EXPECT_FALSE(fs::exists(dir / "bad.h5.journal"));
  }
  const test::CommandResult missing =
      test::RunCommand(Generate(dir / "missing.toml", dir / "t.h5"), dir.path());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("missing.toml"), std::string::npos) << missing.err;
  const test::CommandResult no_output = test::RunCommand(
      Quoted(test::WrcBinary()) + " generate " + Quoted((dir / "bad.toml").string()), dir.path());
  EXPECT_EQ(no_output.exit_code, 2);

  test::WriteFile(dir / "not_a_table.h5", "plain text");
  for (const char* table : {"not_a_table.h5", "absent.h5"}) {
    const test::CommandResult info = test::RunCommand(
        Quoted(test::WrcBinary()) + " info " + Quoted((dir / table).string()), dir.path());
    EXPECT_EQ(info.exit_code, 2) << table;
    EXPECT_NE(info.err.find(table), std::string::npos) << info.err;
  }
}

}  // namespace
}  // namespace wrc
