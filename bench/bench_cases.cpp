// Process-to-process timing of `wrc solve` on the visible reference cases (the aim: a full solve
// at least 5x faster than CONTACT): each benchmark runs the front end on one case, as a user
// would, and reports CONTACT's time from the reference JSON, the speed-up, and wrc's own stage
// timings (`timing_s` of `wrc solve --json`, in ms, from the last run).
//
//   build/bench/bench_cases                          # Manchester curved + heavy haul
//   build/bench/bench_cases --benchmark_filter=heavy --benchmark_repetitions=5
//   WRC_BENCH_GROUPS="groove mbench_planar" build/bench/bench_cases
//
// Use --benchmark_min_time=1 or repetitions on a quiet machine: the 2-core CI box shares its
// cores with builds and the numbers are upper bounds otherwise.

#include <benchmark/benchmark.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

extern char** environ;

namespace {

namespace fs = std::filesystem;

// Runs `wrc solve CASE --json` and returns its standard output; aborts on failure (a benchmark
// of a failing solve would time the error path).
std::string RunSolve(const std::string& wrc, const std::string& case_path) {
  int out[2];
  if (pipe(out) != 0) std::abort();
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO);
  posix_spawn_file_actions_addclose(&actions, out[0]);
  std::vector<std::string> args = {wrc, "solve", case_path, "--json"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, wrc.c_str(), &actions, nullptr, argv.data(), environ) != 0) {
    std::cerr << "bench_cases: cannot start " << wrc << "\n";
    std::abort();
  }
  posix_spawn_file_actions_destroy(&actions);
  close(out[1]);
  std::string text;
  char buffer[1 << 14];
  for (ssize_t n; (n = read(out[0], buffer, sizeof buffer)) > 0;) text.append(buffer, n);
  close(out[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::cerr << "bench_cases: wrc solve " << case_path << " failed\n";
    std::abort();
  }
  return text;
}

void BM_Solve(benchmark::State& state, const std::string& wrc, const std::string& case_path,
              double contact_seconds) {
  std::string last;
  double wall = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    last = RunSolve(wrc, case_path);
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  const nlohmann::json result = nlohmann::json::parse(last);
  for (const auto& [stage, value] : result.at("timing_s").items()) {
    state.counters[stage + "_ms"] = value.get<double>() * 1e3;
  }
  state.counters["contact_ms"] = contact_seconds * 1e3;
  // Speed-up against CONTACT: CONTACT's time over wrc's mean process time per run.
  state.counters["speedup"] = contact_seconds * static_cast<double>(state.iterations()) / wall;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string wrc = std::string(WRC_BINARY_DIR) + "/wrc";
  const fs::path cases = fs::path(WRC_TEST_DATA_DIR) / "reference" / "cases";
  std::vector<std::string> groups = {"mbench_curved", "heavy_haul"};
  if (const char* env = std::getenv("WRC_BENCH_GROUPS")) {
    groups.clear();
    std::istringstream in(env);
    for (std::string g; in >> g;) groups.push_back(g);
  }
  for (const std::string& group : groups) {
    std::vector<fs::path> files;
    if (fs::is_directory(cases / group)) {
      for (const auto& entry : fs::directory_iterator(cases / group)) {
        if (entry.path().extension() == ".toml") files.push_back(entry.path());
      }
    }
    std::sort(files.begin(), files.end());
    for (const fs::path& file : files) {
      fs::path reference = file;
      reference.replace_extension(".contact.json");
      double contact_seconds = 0.0;
      if (std::ifstream in(reference); in) {
        const nlohmann::json j = nlohmann::json::parse(in);
        // CONTACT's process wall time (reference README: `contact.time_s`).
        if (j.contains("contact") && j.at("contact").contains("time_s")) {
          contact_seconds = j.at("contact").at("time_s").get<double>();
        } else if (j.contains("time_s")) {
          contact_seconds = j.at("time_s").get<double>();
        }
      }
      benchmark::RegisterBenchmark((group + "/" + file.stem().string()).c_str(), BM_Solve, wrc,
                                   file.string(), contact_seconds)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
