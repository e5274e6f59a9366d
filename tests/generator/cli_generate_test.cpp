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
#include "wrc/core/scene.h"
#include "wrc/core/wheelrail.h"
#include "wrc/generator/generator.h"

extern char** environ;

namespace wrc {
namespace {

using test::Quoted;
using test::ScratchDir;
namespace fs = std::filesystem;

// 4 × 10 points: under a second with 2 threads in a Release build, so the tests below catch a
// run part-way by stopping it (StartAndCatch) rather than by timing. On the 0.5 mm grid (not
// the tiny scene's 1 mm) a point takes a few ms, so the whole run outlasts the 2 ms polling of
// the catch by far: at 1 mm the faster solver finished 40 points before a loaded test machine
// looked.
constexpr std::size_t kKillScenePoints = 40;
std::string KillScene() {
  std::string scene = test::TinyScene(
      "axes = [\"yaw\", \"y\"]\nyaw = [-0.004, 0.0, 0.002, 0.004]\n"
      "y = {from = 0.0, to = 4.5, step = 0.5}\noutputs = [\"fx\", \"fy\", \"fz\", \"z\"]");
  const std::string grid = "dx = 1.0\nds = 1.0\n";
  const std::size_t at = scene.find(grid);
  if (at != std::string::npos) scene.replace(at, grid.size(), "dx = 0.5\nds = 0.5\n");
  return scene;
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

// A `wrc generate` run caught part-way: its pid, stopped, and the records in its journal.
struct CaughtRun {
  pid_t pid = -1;
  std::size_t records = 0;
};

// Starts `wrc generate SCENE -o TABLE --threads THREADS`, waits until its journal holds at least
// `min_records` points (the signal handlers are installed before the journal is created), then
// freezes it with SIGSTOP, which it can neither catch nor delay. Whatever the test sends next
// reaches a run that cannot move on meanwhile, so how far it got is known, not raced: a fixed
// sleep, or a signal sent to a running process after reading the journal, can come too late on
// a loaded machine, when the run has finished or is about to (exit 0 instead of 130). A run
// caught too late even so (the test process descheduled for the second the rest takes) is
// killed and started again, up to 3 times; `pid` is -1 when no attempt worked. Each worker
// finishes the point it is on and may claim one more before it sees a signal, hence the margin.
CaughtRun StartAndCatch(const fs::path& scene, const fs::path& table, int threads,
                        std::size_t min_records) {
  const fs::path journal = table.string() + ".journal";
  for (int attempt = 0; attempt < 3; ++attempt) {
    fs::remove(table);
    fs::remove(journal);
    const pid_t pid = Spawn(
        {"generate", scene.string(), "-o", table.string(), "--threads", std::to_string(threads)});
    if (pid <= 0) break;
    int status = 0;
    if (!WaitForRecords(pid, journal, min_records)) {
      // Ended before it got there (already reaped), or stuck: make sure it is gone.
      if (kill(pid, SIGKILL) == 0) waitpid(pid, &status, 0);
      continue;
    }
    kill(pid, SIGSTOP);
    if (waitpid(pid, &status, WUNTRACED) != pid || !WIFSTOPPED(status)) continue;  // it ended
    const std::size_t records = JournalRecords(journal);
    if (records + 2 * static_cast<std::size_t>(threads) < kKillScenePoints) return {pid, records};
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
  }
  return {};
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

#if defined(__SANITIZE_ADDRESS__)
#define WRC_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define WRC_TEST_UNDER_ASAN 1
#endif
#endif

// `mpirun` with two ranks. In a sanitizer build (WRC_SANITIZE) LeakSanitizer reports Open MPI's
// own allocations when the ranks exit and fails them; the ranks get the suppressions of
// tools/lsan.supp, which match only with the slow unwinder (Open MPI has no frame pointers; see
// that file). Passed with -x to the ranks alone: it slows every allocation down about 10 times.
std::string Mpirun() {
  std::string command = "mpirun --allow-run-as-root --oversubscribe -n 2 ";
#ifdef WRC_TEST_UNDER_ASAN
  command += "-x " +
             Quoted("LSAN_OPTIONS=suppressions=" +
                    (fs::path(WRC_SOURCE_DIR) / "tools" / "lsan.supp").string() +
                    ":print_suppressions=0:fast_unwind_on_malloc=0") +
             " ";
#endif
  return command;
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
  const CaughtRun run = StartAndCatch(scene_, table, 1, 4);
  ASSERT_GT(run.pid, 0) << "the run could not be caught before it ended";
  kill(run.pid, SIGKILL);
  EXPECT_EQ(WaitExitCode(run.pid), 128 + SIGKILL);
  // Stopped, it wrote nothing more: the journal holds exactly what it held then.
  const std::size_t saved = JournalRecords(journal);
  EXPECT_EQ(saved, run.records);
  EXPECT_GE(saved, 4u);
  EXPECT_LT(saved, kKillScenePoints);
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
  const CaughtRun run = StartAndCatch(scene_, table, 2, 2);
  ASSERT_GT(run.pid, 0) << "the run could not be caught before it ended";
  // SIGINT waits while the run is stopped and is handled as soon as it continues.
  kill(run.pid, SIGINT);
  kill(run.pid, SIGCONT);
  EXPECT_EQ(WaitExitCode(run.pid), 130);
  EXPECT_FALSE(fs::exists(table));
  // The journal holds every point that finished, nothing torn: those of the stop and the ones
  // the workers were on.
  const gen::JournalContents contents = gen::ParseJournal(test::ReadFile(journal), "j");
  EXPECT_EQ(contents.valid_bytes, contents.file_bytes);
  EXPECT_GE(contents.records.size(), run.records);
  EXPECT_LT(contents.records.size(), kKillScenePoints);

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
  const CaughtRun run = StartAndCatch(scene_, table, 1, 1);
  ASSERT_GT(run.pid, 0) << "the run could not be caught before it ended";
  kill(run.pid, SIGTERM);
  kill(run.pid, SIGCONT);
  EXPECT_EQ(WaitExitCode(run.pid), 130);
  const test::CommandResult resumed =
      test::RunCommand(Generate(scene_, table, "--resume --threads 1"), dir_->path());
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  test::ExpectIdenticalTables(reference_, table);
}

TEST_F(CliGenerateTest, TwoMpiRanksGiveTheSameTableAsOneProcess) {
  if (!GeneratorSupportsMpi()) GTEST_SKIP() << "wrc was built without MPI support";
  const fs::path table = *dir_ / "mpi.h5";
  const std::string mpirun = Mpirun();
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

// A refinement under MPI: rank 0 decides the nodes and sends each pass's axes to the other
// rank, which solves its share of every grid; the table equals a single-process refinement.
TEST_F(CliGenerateTest, TwoMpiRanksRefineToTheSameTableAsOneProcess) {
  if (!GeneratorSupportsMpi()) GTEST_SKIP() << "wrc was built without MPI support";
  const fs::path scene = test::WriteFile(
      *dir_ / "refine.toml",
      test::TinyScene("axes = [\"yaw\", \"y\"]\nyaw = [0.0, 0.004]\ny = {from = 2.0, to = "
                      "8.0, count = 3}\noutputs = [\"fx\", \"fy\", \"fz\", \"z\"]\n"
                      "[table.refine]\ntarget = 0.01\nsamples = 2\nmax_passes = 3\n"));
  const fs::path single = *dir_ / "refine_single.h5", mpi = *dir_ / "refine_mpi.h5";
  GenerateOptions options;
  options.output = single;
  options.threads = 1;
  options.progress = ProgressMode::kOff;
  options.mpi = MpiMode::kOff;
  ASSERT_TRUE(GenerateTable(LoadScene(scene), options).complete);
  const test::CommandResult result =
      test::RunCommand(Mpirun() + Generate(scene, mpi, "--threads 1 --quiet"), dir_->path());
  ASSERT_EQ(result.exit_code, 0) << result.out << result.err;
  EXPECT_NE(result.out.find("2 MPI ranks"), std::string::npos) << result.out;
  test::ExpectIdenticalTables(single, mpi);
}

// Generates the fixture's scene into `table` and stops after one point: a journal to resume.
void StopAfterOnePoint(const fs::path& table, const fs::path& scene) {
  GenerateOptions options;
  options.output = table;
  options.threads = 1;
  options.max_points = 1;
  options.progress = ProgressMode::kOff;
  options.mpi = MpiMode::kOff;
  GenerateTable(LoadScene(scene), options);
}

TEST_F(CliGenerateTest, ResumingWithAnotherSceneIsRefused) {
  const fs::path table = *dir_ / "other.h5";
  const fs::path other_scene = test::WriteFile(*dir_ / "other.toml", KillScene() + "# edited\n");
  StopAfterOnePoint(table, scene_);
  const test::CommandResult result =
      test::RunCommand(Generate(other_scene, table, "--resume"), dir_->path());
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("different"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("other.h5.journal"), std::string::npos) << result.err;
}

// A damaged journal is the user's file, not a bug: exit 2, and the message names the file.
TEST_F(CliGenerateTest, ResumingFromADamagedJournalIsBadInput) {
  const fs::path table = *dir_ / "damaged.h5";
  const fs::path journal = table.string() + ".journal";
  StopAfterOnePoint(table, scene_);
  std::string bytes = test::ReadFile(journal);
  ASSERT_GT(bytes.size(), 12u);
  bytes[12] = static_cast<char>(bytes[12] ^ 0x01);  // inside the header: its CRC no longer holds
  test::WriteFile(journal, bytes);
  const test::CommandResult damaged =
      test::RunCommand(Generate(scene_, table, "--resume"), dir_->path());
  EXPECT_EQ(damaged.exit_code, 2) << damaged.err;
  EXPECT_NE(damaged.err.find("wrc generate: error: "), std::string::npos) << damaged.err;
  EXPECT_NE(damaged.err.find("damaged.h5.journal"), std::string::npos) << damaged.err;
  EXPECT_NE(damaged.err.find("damaged"), std::string::npos) << damaged.err;

  test::WriteFile(journal, "these are not the bytes of a journal\n");
  const test::CommandResult foreign =
      test::RunCommand(Generate(scene_, table, "--resume"), dir_->path());
  EXPECT_EQ(foreign.exit_code, 2) << foreign.err;
  EXPECT_NE(foreign.err.find("damaged.h5.journal: not a wrc journal"), std::string::npos)
      << foreign.err;
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
  // The fixed state, as the wheelset API reads it: the scene's values, null for the axes.
  EXPECT_EQ(info["attributes"]["wheelset_velocity"], 2000.0);
  EXPECT_EQ(info["attributes"]["fixed_fz"], 10000.0);
  EXPECT_EQ(info["attributes"]["wheelset_side"], "right");
  EXPECT_TRUE(info["attributes"]["fixed_yaw"].is_null());
  EXPECT_TRUE(info["attributes"]["fixed_y"].is_null());
  const test::CommandResult text = test::RunCommand(
      Quoted(test::WrcBinary()) + " info " + Quoted(reference_.string()), dir_->path());
  EXPECT_NE(text.out.find("fixed state           right wheel, V 2000 mm/s, r0 460 mm; fz 10000"),
            std::string::npos)
      << text.out;
  EXPECT_EQ(info["status"]["ok"], 40);
  EXPECT_EQ(info["status"]["error"], 0);
  EXPECT_EQ(info["attributes"]["scene"], KillScene());
  EXPECT_EQ(info["attributes"]["rail_profile_sha256"].get<std::string>().size(), 64u);
  EXPECT_EQ(info["profiles"]["wheel"]["name"], "MBench_S1002_v3.prw");
  // fz is prescribed: every ok point meets it to the solver's relative tolerance,
  // WheelRailOptions::fz_tolerance (1e-6).
  EXPECT_NEAR(info["outputs"][2]["min"].get<double>(), 10000.0,
              WheelRailOptions{}.fz_tolerance * 10000.0);

  const test::CommandResult human = test::RunCommand(
      Quoted(test::WrcBinary()) + " info " + Quoted(reference_.string()), dir_->path());
  EXPECT_EQ(human.exit_code, 0);
  EXPECT_NE(human.out.find("status: ok 40"), std::string::npos) << human.out;
}

// --estimate solves a few short runs of the grid and writes nothing: 8 runs of up to 4 points
// along the last axis (here y, 6 nodes), the grid's point count, and for a refinement its budget.
TEST(CliGenerate, EstimateSolvesAFewPointsAndWritesNothing) {
  ScratchDir dir("cli_estimate");
  const fs::path scene =
      test::WriteFile(dir / "scene.toml", test::TinyScene(test::DefaultTinyTable()));
  const test::CommandResult plain = test::RunCommand(
      Quoted(test::WrcBinary()) + " generate " + Quoted(scene.string()) + " --estimate --threads 2",
      dir.path());
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_NE(plain.out.find("from 32 solves"), std::string::npos) << plain.out;
  EXPECT_NE(plain.out.find("the scene's grid: 12 points"), std::string::npos) << plain.out;
  EXPECT_NE(plain.out.find("on 2 threads"), std::string::npos) << plain.out;
  EXPECT_EQ(plain.out.find("failed"), std::string::npos) << plain.out;
  EXPECT_EQ(plain.out.find("refinement"), std::string::npos) << plain.out;
  const fs::path refined = test::WriteFile(
      dir / "refined.toml",
      test::TinyScene(test::DefaultTinyTable() + "\n[table.refine]\nmax_points = 5000\n"));
  const test::CommandResult refine = test::RunCommand(
      Quoted(test::WrcBinary()) + " generate " + Quoted(refined.string()) + " --estimate",
      dir.path());
  ASSERT_EQ(refine.exit_code, 0) << refine.err;
  EXPECT_NE(refine.out.find("budget of 5000 points"), std::string::npos) << refine.out;
  for (const auto& entry : fs::directory_iterator(dir.path())) {  // no table, journal, or .tmp
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(name.find(".h5"), std::string::npos) << name;
    EXPECT_EQ(name.find("journal"), std::string::npos) << name;
  }
}

// wrc info tells which lookups a table was refined for, in its target and its error estimate;
// a table refined before the target named them was refined for linear ones.
TEST(CliGenerate, InfoNamesTheInterpolationATableWasRefinedFor) {
  ScratchDir dir("cli_info_interpolation");
  for (const std::string mode : {"linear", "cubic"}) {
    const fs::path scene = test::WriteFile(
        dir / (mode + ".toml"),
        test::TinyScene("axes = [\"y\"]\ny = {from = 2.0, to = 8.0, count = 3}\n"
                        "outputs = [\"fx\", \"fy\", \"fz\"]\n[table.refine]\ntarget = 0.05\n"
                        "samples = 1\nmax_passes = 1\ninterpolation = \"" +
                        mode + "\"\n"));
    const fs::path table = dir / (mode + ".h5");
    ASSERT_EQ(test::RunCommand(Generate(scene, table, "--quiet"), dir.path()).exit_code, 0);
    const test::CommandResult info =
        test::RunCommand(Quoted(test::WrcBinary()) + " info " + Quoted(table.string()), dir.path());
    ASSERT_EQ(info.exit_code, 0) << info.err;
    const std::string named = mode == "cubic" ? "cubic" : "multilinear";
    EXPECT_NE(info.out.find("random states, each output, " + named + " lookups)"),
              std::string::npos)
        << info.out;
    EXPECT_NE(info.out.find("random points (" + named + ")"), std::string::npos) << info.out;
  }
}

// EstimateGeneration times one solve per point of each run, a run no longer than its axis.
TEST(CliGenerate, EstimateCountsTheSolvesItTimes) {
  ScratchDir dir("estimate_counts");
  const Scene scene = LoadScene(test::WriteFile(
      dir / "scene.toml", test::TinyScene("axes = [\"y\"]\ny = [0.0, 2.0]\noutputs = [\"fy\"]")));
  const GenerateEstimate e = EstimateGeneration(scene, 3, 4);
  EXPECT_EQ(e.solves, 6);  // 3 runs, each along all 2 nodes of the only axis
  EXPECT_EQ(e.failed, 0);
  EXPECT_EQ(e.start_points, 2u);
  EXPECT_EQ(e.max_points, 2u);
  EXPECT_GT(e.mean_solve_s, 0.0);
  EXPECT_GE(e.max_solve_s, e.mean_solve_s);
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
  EXPECT_NE(no_output.err.find("--output"), std::string::npos) << no_output.err;

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
