// `wrc generate SCENE.toml -o TABLE.h5 [--threads N] [--resume] [--quiet]`, and
// `wrc generate SCENE.toml --estimate`
// (docs/reference/table-layout.md).

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "tools/wrc/commands.h"
#include "tools/wrc/thread_option.h"
#include "wrc/core/errors.h"
#include "wrc/core/output_file.h"
#include "wrc/core/scene.h"
#include "wrc/generator/generator.h"

namespace wrc::cli {
namespace {

// One shell word, so that the printed resume command can be pasted as is.
std::string ShellWord(const std::string& word) {
  if (word.find_first_of(" \t\n'\"\\$`*?[]{}()<>|&;#~!") == std::string::npos && !word.empty()) {
    return word;
  }
  std::string quoted = "'";
  for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

// "(y = 200, yaw = 0.01)" for a flat point index.
std::string DescribePoint(const std::vector<SceneAxis>& axes, std::uint64_t point) {
  std::vector<std::size_t> shape;
  for (const SceneAxis& axis : axes) shape.push_back(axis.values.size());
  std::vector<std::size_t> indices(shape.size());
  for (std::size_t a = shape.size(); a-- > 0;) {
    indices[a] = static_cast<std::size_t>(point % shape[a]);
    point /= shape[a];
  }
  std::ostringstream text;
  text << '(';
  for (std::size_t a = 0; a < shape.size(); ++a) {
    text << (a ? ", " : "") << axes[a].name << " = " << axes[a].values[indices[a]];
  }
  text << ')';
  return text.str();
}

void PrintSummary(const std::string& output, const GenerateSummary& s) {
  const auto& counts = s.status_counts;
  std::cout << "wrote " << output << ": " << s.points << " points (" << counts[0] << " ok, "
            << counts[1] << " no contact, " << counts[2] << " not converged, " << counts[3]
            << " errors)\n";
  std::cout << "solved " << s.computed << " points in " << std::fixed << std::setprecision(1)
            << s.seconds << " s";
  if (s.computed > 0 && s.seconds > 0.0) {
    std::cout << " (" << std::setprecision(2) << static_cast<double>(s.computed) / s.seconds
              << " points/s)";
  }
  std::cout << " on " << s.threads << (s.threads == 1 ? " thread" : " threads");
  if (s.ranks > 1) std::cout << " per rank, " << s.ranks << " MPI ranks";
  std::cout << ", " << std::setprecision(1) << s.cpu_seconds << " CPU s"
            << (s.ranks > 1 ? " on rank 0" : "");
  if (s.reused > 0) std::cout << "; " << s.reused << " points reused from the journal";
  std::cout << '\n' << std::defaultfloat;
  if (!s.failures.empty()) {
    std::cerr << "wrc generate: " << counts[2] + counts[3]
              << " points failed (status 2/3, outputs NaN); the first:\n";
    for (const auto& [point, message] : s.failures) {
      std::cerr << "  point " << point << " " << DescribePoint(s.axes, point) << ": " << message
                << '\n';
    }
    std::cerr << "  (all of them: wrc info " << ShellWord(output) << ")\n";
  }
}

// "about 40 s", "about 12 min", "about 2 h 05 min".
std::string Duration(double seconds) {
  std::ostringstream text;
  text << "about ";
  if (seconds < 90.0) {
    text << std::max(1, static_cast<int>(seconds + 0.5)) << " s";
  } else if (seconds < 5400.0) {
    text << static_cast<int>(seconds / 60.0 + 0.5) << " min";
  } else {
    const int minutes = static_cast<int>(seconds / 60.0 + 0.5);
    text << minutes / 60 << " h " << std::setw(2) << std::setfill('0') << minutes % 60 << " min";
  }
  return text.str();
}

// Solves of a refinement beyond its grid points: the interval midpoints, the slope target's
// probes and the final check. Measured: 404 831 solves for the 395 010 points of
// tables/mbench_vehicle.toml (2.5 %).
constexpr double kRefinementSolvesPerPoint = 1.03;
// A refinement's nodes gather where the contact changes (flange, two-point contact, the largest
// loads), where solves take longer than at the starting grid's nodes: the mean solve of the
// finished table over that of the estimate's, measured 1.4 on tables/mbench_vehicle.toml at its
// static load (60 000 points) and 2.0 on the whole scene (395 010 points, with other work beside).
constexpr double kRefinedSolveRatio = 2.0;

void PrintEstimate(const std::string& scene_path, const Scene& scene, int threads) {
  const GenerateEstimate e = EstimateGeneration(scene);
  const int workers = threads > 0 ? threads : AllCores();
  const double per_point = e.mean_solve_s / workers;  // the threads scale about linearly
  std::cout << "estimate for " << scene_path << " from " << e.solves << " solves (" << e.solves
            << " grid points in short runs along " << scene.axes.back().name
            << ", warm-started as a run does), one thread:\n"
            << std::setprecision(3) << "  a solve takes " << 1000.0 * e.mean_solve_s
            << " ms on average, " << 1000.0 * e.max_solve_s << " ms at most";
  if (e.failed > 0) std::cout << "; " << e.failed << " of them failed";
  std::cout << "\n  the scene's grid: " << e.start_points << " points, "
            << Duration(static_cast<double>(e.start_points) * per_point) << " on " << workers
            << (workers == 1 ? " thread" : " threads") << '\n';
  if (scene.refine) {
    const double budget = static_cast<double>(e.max_points) * kRefinementSolvesPerPoint * per_point;
    const double quantile = scene.refine->quantile;
    std::cout << "  the refinement starts from that grid and places nodes until "
              << (quantile < 1.0 ? std::to_string(static_cast<int>(std::lround(100 * quantile))) +
                                       " % of random states meet the target"
                                 : std::string("every sampled midpoint meets its target"))
              << " or the budget of " << e.max_points
              << " points is spent; the whole budget with its midpoint solves would take "
              << Duration(budget) << " at the grid's solve time, up to "
              << Duration(kRefinedSolveRatio * budget)
              << " where the nodes gather at the harder states";
    if (quantile < 1.0) {
      std::cout << " (an upper bound: the quantile is usually met well before the budget, on "
                   "tables/mbench.toml at 239 400 of 800 000 points)";
    }
    std::cout << '\n';
  }
}

}  // namespace

void AddGenerateCommand(CLI::App& app, int* exit_code) {
  auto* cmd =
      app.add_subcommand("generate", "Solve a scene at every grid point into an HDF5 table");
  auto scene_path = std::make_shared<std::string>();
  auto output = std::make_shared<std::string>();
  auto threads = std::make_shared<int>(0);
  auto resume = std::make_shared<bool>(false);
  auto quiet = std::make_shared<bool>(false);
  auto cold_start = std::make_shared<bool>(false);
  auto keep_passes = std::make_shared<bool>(false);
  cmd->add_option("SCENE", *scene_path,
                  "Scene file (TOML, " + DocFile("reference/case-files.md") + ")")
      ->required();
  auto estimate = std::make_shared<bool>(false);
  cmd->add_option("-o,--output", *output, "Table to write (HDF5; not with --estimate)");
  cmd->add_option("--threads", *threads,
                  "Worker threads (default: all cores, shared among MPI ranks on one machine)")
      ->check(ThreadCount(false));
  cmd->add_flag("--resume", *resume,
                "Continue an interrupted run from TABLE.h5.journal, reusing its points");
  cmd->add_flag("--quiet", *quiet, "No progress on stderr");
  cmd->add_flag("--estimate", *estimate,
                "Write nothing: the run's points and time from a few solves of the scene's grid");
  cmd->add_flag("--no-warm-start", *cold_start,
                "Start every prescribed-fz solve from first contact instead of from the previous "
                "point's z (slower; results differ in the last digits)");
  cmd->add_flag("--keep-passes", *keep_passes,
                "A refinement also writes every pass's grid as TABLE.h5.pass<P>.h5 (one run, "
                "the accuracy and size of every coarser table on the way)");
  cmd->callback([=]() {
    try {
      if (*estimate) {
        PrintEstimate(*scene_path, LoadScene(*scene_path), *threads);
        *exit_code = kExitOk;
        return;
      }
      if (output->empty()) {
        throw InputError("-o/--output is required: the table to write (or --estimate)");
      }
      RequireNotAnInput(*output, {*scene_path});
      const Scene scene = LoadScene(*scene_path);
      GenerateOptions options;
      options.output = *output;
      options.threads = *threads;
      options.resume = *resume;
      options.progress = *quiet ? ProgressMode::kOff : ProgressMode::kAuto;
      options.handle_signals = true;
      options.warm_start = !*cold_start;
      options.keep_passes = *keep_passes;
      const GenerateSummary summary = GenerateTable(scene, options);
      if (!summary.is_root) {
        *exit_code = summary.interrupted ? kExitInterrupted : kExitOk;
        return;
      }
      if (summary.complete) {
        PrintSummary(*output, summary);
        *exit_code = kExitOk;
        return;
      }
      // A refinement run counts its solves over passes and midpoint samples; a pass's own
      // share of them is no measure of what --resume keeps, so only the run's total is told.
      if (scene.refine) {
        std::cerr << "wrc generate: interrupted; all " << summary.computed
                  << " solves of this run (grid points and interval midpoints) are saved in ";
      } else {
        std::cerr << "wrc generate: interrupted; " << summary.reused + summary.computed << " of "
                  << summary.points << " points are saved in ";
      }
      std::cerr << summary.journal.string() << ".\nContinue with:\n  wrc generate "
                << ShellWord(*scene_path) << " -o " << ShellWord(*output);
      if (*threads > 0) std::cerr << " --threads " << *threads;
      if (*cold_start) std::cerr << " --no-warm-start";
      std::cerr << " --resume\n";
      *exit_code = kExitInterrupted;
    } catch (...) {
      *exit_code = ReportFailure("wrc generate");  // MPI rank > 0 (GenerateAborted): silent
    }
  });
}

}  // namespace wrc::cli
