// `wrc verify TABLE.h5` (SPEC §5): re-solves sampled points exactly with the scene stored in
// the table and reports how far the interpolated table is from the full solver.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "runtime/hdf5/hdf5.h"
#include "tools/wrc/commands.h"
#include "wrc/errors.h"
#include "wrc/generator.h"
#include "wrc/profile.h"
#include "wrc/runtime.hpp"
#include "wrc/scene.h"

namespace wrc::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct VerifyOptions {
  std::string table;
  int samples = 200;
  std::uint64_t seed = 1;
  std::string sampler = "uniform";
  bool near_jumps = false;
  bool as_json = false;
  double tolerance = -1.0;
  int threads = 0;
};

// The scene of a table with its profiles restored from /profiles into a scratch directory, so
// that a table verifies wherever it is moved (SPEC §4.2).
struct StoredScene {
  Scene scene;
  fs::path scratch;
  ~StoredScene() {
    std::error_code ec;
    if (!scratch.empty()) fs::remove_all(scratch, ec);
  }
};

void RestoreProfile(const h5::File& file, const std::string& name, const fs::path& target) {
  const h5::Dataset d = file.OpenGroup("profiles").OpenDataset(name);
  const std::vector<std::uint8_t> bytes = d.Read<std::uint8_t>();
  fs::create_directories(target.parent_path());
  std::ofstream out(target, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
  if (!out) throw InputError("cannot write the table's profile to " + target.string());
}

std::unique_ptr<StoredScene> LoadStoredScene(const fs::path& table) {
  auto stored = std::make_unique<StoredScene>();
  const h5::File file = h5::File::Open(table.string());
  const std::string text = file.ReadStringAttribute("scene");
  stored->scratch = fs::temp_directory_path() /
                    ("wrc_verify_" + std::to_string(std::random_device{}()) + "_" +
                     std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
  fs::create_directories(stored->scratch);
  stored->scene = ParseScene(text, stored->scratch, table.string() + ":/scene");
  RestoreProfile(file, "rail", stored->scene.base.rail.path);
  RestoreProfile(file, "wheel", stored->scene.base.wheel.path);
  // Read and spline the profiles once for all sampled points (as LoadScene does).
  for (auto [source, kind] : {std::pair{&stored->scene.base.rail, ProfileKind::kRail},
                              std::pair{&stored->scene.base.wheel, ProfileKind::kWheel}}) {
    ProfileOptions options;
    options.mirror_y = source->mirror_y;
    source->spline =
        std::make_shared<const ProfileSpline>(ReadProfile(source->path.string(), kind, options));
  }
  return stored;
}

// Spread (max − min) of the finite values, or `if_flat` when there is none.
double FiniteRange(const std::vector<double>& values, double if_flat) {
  double lo = INFINITY, hi = -INFINITY;
  for (double v : values) {
    if (std::isfinite(v)) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  return hi > lo ? hi - lo : if_flat;
}

// Sample points: uniform, or a Latin hypercube (each axis range cut into N strata, one sample
// per stratum, strata shuffled independently per axis).
std::vector<std::vector<double>> Sample(const std::vector<std::vector<double>>& axes, int n,
                                        std::uint64_t seed, bool lhs) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::size_t d = axes.size();
  std::vector<std::vector<double>> points(n, std::vector<double>(d));
  for (std::size_t a = 0; a < d; ++a) {
    const double lo = axes[a].front(), hi = axes[a].back();
    std::vector<int> strata(n);
    for (int k = 0; k < n; ++k) strata[k] = k;
    if (lhs) std::shuffle(strata.begin(), strata.end(), rng);
    for (int k = 0; k < n; ++k) {
      const double u = lhs ? (strata[k] + unit(rng)) / n : unit(rng);
      points[k][a] = lo + u * (hi - lo);
    }
  }
  return points;
}

// Samples concentrated in the grid cells where neighbouring table values jump: for each cell
// edge along each axis, the change of any output relative to that output's range; cells with
// the largest changes (top 5 %) are sampled uniformly.
std::vector<std::vector<double>> SampleNearJumps(const std::vector<std::vector<double>>& axes,
                                                 const std::vector<std::vector<double>>& outputs,
                                                 int n, std::uint64_t seed) {
  const std::size_t d = axes.size();
  std::vector<std::size_t> shape(d), stride(d);
  std::size_t total = 1;
  for (std::size_t a = d; a-- > 0;) {
    shape[a] = axes[a].size();
    stride[a] = total;
    total *= shape[a];
  }
  std::vector<double> range(outputs.size(), 0.0);
  for (std::size_t o = 0; o < outputs.size(); ++o) range[o] = FiniteRange(outputs[o], 1.0);
  std::vector<std::pair<double, std::size_t>> edges;  // (jump, lower node) per axis-edge
  std::vector<int> edge_axis;
  for (std::size_t node = 0; node < total; ++node) {
    for (std::size_t a = 0; a < d; ++a) {
      if ((node / stride[a]) % shape[a] + 1 >= shape[a]) continue;
      double jump = 0.0;
      for (std::size_t o = 0; o < outputs.size(); ++o) {
        const double dv = outputs[o][node + stride[a]] - outputs[o][node];
        if (std::isfinite(dv)) jump = std::max(jump, std::fabs(dv) / range[o]);
      }
      edges.push_back({jump, node});
      edge_axis.push_back(static_cast<int>(a));
    }
  }
  std::vector<std::size_t> order(edges.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return edges[a].first > edges[b].first; });
  const std::size_t keep = std::max<std::size_t>(1, order.size() / 20);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<std::size_t> pick(0, keep - 1);
  std::vector<std::vector<double>> points(n, std::vector<double>(d));
  for (int k = 0; k < n; ++k) {
    const std::size_t e = order[pick(rng)];
    const std::size_t node = edges[e].second;
    for (std::size_t a = 0; a < d; ++a) {
      const std::size_t i = (node / stride[a]) % shape[a];
      // Within the cell above the node (or the last cell): anywhere along every axis.
      const std::size_t i0 = std::min(i, shape[a] > 1 ? shape[a] - 2 : 0);
      const double lo = axes[a][i0], hi = axes[a][std::min(i0 + 1, shape[a] - 1)];
      points[k][a] = lo + unit(rng) * (hi - lo);
    }
  }
  return points;
}

struct OutputStats {
  double max_abs = 0.0, rms = 0.0, p95_abs = 0.0, max_rel = 0.0, range = 0.0;
  std::vector<double> worst;
  int compared = 0;
};

OutputStats Stats(const std::vector<double>& errors, const std::vector<std::vector<double>>& pts,
                  const std::vector<int>& index, double range) {
  OutputStats s;
  s.range = range;
  std::vector<double> abs;
  double sum2 = 0.0;
  std::size_t worst = 0;
  for (std::size_t k = 0; k < errors.size(); ++k) {
    const double e = std::fabs(errors[k]);
    abs.push_back(e);
    sum2 += e * e;
    if (e >= s.max_abs) {
      s.max_abs = e;
      worst = static_cast<std::size_t>(index[k]);
    }
  }
  s.compared = static_cast<int>(abs.size());
  if (!abs.empty()) {
    s.rms = std::sqrt(sum2 / abs.size());
    std::sort(abs.begin(), abs.end());
    s.p95_abs = abs[std::min(abs.size() - 1, static_cast<std::size_t>(0.95 * abs.size()))];
    s.worst = pts[worst];
  }
  s.max_rel = range > 0.0 ? s.max_abs / range : 0.0;
  return s;
}

int RunVerify(const VerifyOptions& opt) {
  auto stored = LoadStoredScene(opt.table);
  const Scene& scene = stored->scene;
  Table table(opt.table);
  const int n_axes = table.num_axes(), n_out = table.num_outputs();
  std::vector<std::vector<double>> axes;
  for (int a = 0; a < n_axes; ++a) axes.push_back(table.axis_values(a));
  // Output values over the table, for the ranges (and the near-jump sampler).
  const h5::File file = h5::File::Open(opt.table);
  const h5::Group outputs_group = file.OpenGroup("outputs");
  std::vector<std::vector<double>> values(n_out);
  std::vector<double> range(n_out, 0.0);
  for (int o = 0; o < n_out; ++o) {
    values[o] = outputs_group.OpenDataset(table.output_name(o)).Read<double>();
    range[o] = FiniteRange(values[o], 0.0);
  }
  const std::vector<std::vector<double>> points =
      opt.near_jumps ? SampleNearJumps(axes, values, opt.samples, opt.seed)
                     : Sample(axes, opt.samples, opt.seed, opt.sampler == "lhs");

  // Exact solves on all threads. The scene's outputs are in the table's output order.
  std::vector<std::vector<double>> exact(points.size());
  std::vector<int> status(points.size(), 3);
  std::vector<double> solve_seconds(points.size(), 0.0);
  std::atomic<std::size_t> next{0};
  auto worker = [&]() {
    for (std::size_t k = next++; k < points.size(); k = next++) {
      const auto t0 = std::chrono::steady_clock::now();
      try {
        const WheelRailResult r = SolveWheelRail(CaseAtPoint(scene, points[k]));
        status[k] = r.status == SolverStatus::kConverged   ? 0
                    : r.status == SolverStatus::kNoContact ? 1
                                                           : 2;
        exact[k] = SceneOutputValues(scene, r, static_cast<PointStatus>(status[k]));
      } catch (const std::exception&) {
        status[k] = 3;
      }
      solve_seconds[k] =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
  };
  const int threads =
      opt.threads > 0 ? opt.threads : std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(worker);
  for (auto& t : pool) t.join();

  json result = {{"table", opt.table},
                 {"samples", opt.samples},
                 {"seed", opt.seed},
                 {"sampler", opt.near_jumps ? "near-jumps" : opt.sampler}};
  double total_solve = 0.0;
  for (double s : solve_seconds) total_solve += s;
  result["solve_time_s"] = {{"mean", total_solve / std::max<std::size_t>(1, points.size())}};
  int counts[4] = {0, 0, 0, 0};
  for (int s : status) counts[s]++;
  result["exact_status"] = {{"ok", counts[0]},
                            {"no_contact", counts[1]},
                            {"not_converged", counts[2]},
                            {"error", counts[3]}};
  bool gate_failed = false;
  for (Interpolation mode : {Interpolation::kLinear, Interpolation::kCubic}) {
    table.set_interpolation(mode);
    std::vector<std::vector<double>> errors(n_out);
    std::vector<std::vector<int>> index(n_out);
    std::vector<double> out(n_out);
    int flagged = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t k = 0; k < points.size(); ++k) table.eval(points[k].data(), out.data());
    const double lookup =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() /
        std::max<std::size_t>(1, points.size());
    for (std::size_t k = 0; k < points.size(); ++k) {
      int flags = 0;
      try {
        flags = table.eval(points[k].data(), out.data());
      } catch (const std::exception&) {
        ++flagged;  // a NaN node in the cell: the table has no value there
        continue;
      }
      if (flags & WRC_FLAG_STATUS) ++flagged;
      if (status[k] > 1 || exact[k].size() != static_cast<std::size_t>(n_out)) continue;
      for (int o = 0; o < n_out; ++o) {
        if (std::isfinite(exact[k][o]) && std::isfinite(out[o])) {
          errors[o].push_back(out[o] - exact[k][o]);
          index[o].push_back(static_cast<int>(k));
        }
      }
    }
    json outputs = json::object();
    for (int o = 0; o < n_out; ++o) {
      const OutputStats s = Stats(errors[o], points, index[o], range[o]);
      json worst = json::object();
      for (int a = 0; a < n_axes && !s.worst.empty(); ++a) worst[table.axis_name(a)] = s.worst[a];
      outputs[table.output_name(o)] = {{"max_abs", s.max_abs}, {"rms", s.rms},
                                       {"p95_abs", s.p95_abs}, {"max_rel", s.max_rel},
                                       {"range", s.range},     {"compared", s.compared},
                                       {"worst", worst}};
      if (opt.tolerance >= 0.0 && s.max_rel > opt.tolerance) gate_failed = true;
    }
    const std::string key = mode == Interpolation::kLinear ? "linear" : "cubic";
    result["interpolation"][key] = {
        {"outputs", outputs}, {"lookup_time_s", {{"mean", lookup}}}, {"flagged_points", flagged}};
    if (mode == Interpolation::kLinear) {
      // SPEC §5's top-level fields are those of the default (multilinear) interpolation.
      result["outputs"] = outputs;
      result["lookup_time_s"] = {{"mean", lookup}};
    }
  }
  if (opt.as_json) {
    std::cout << result.dump(1) << '\n';
  } else {
    std::printf(
        "%s: %d samples (%s, seed %llu), exact solves: %d ok, %d no contact, %d not "
        "converged, %d errors; %.3f s per solve\n",
        opt.table.c_str(), opt.samples, result["sampler"].get<std::string>().c_str(),
        static_cast<unsigned long long>(opt.seed), counts[0], counts[1], counts[2], counts[3],
        result["solve_time_s"]["mean"].get<double>());
    for (const char* key : {"linear", "cubic"}) {
      const json& m = result["interpolation"][key];
      std::printf("\n%s interpolation (%.0f ns per lookup):\n  %-14s %12s %12s %12s %10s\n", key,
                  1e9 * m["lookup_time_s"]["mean"].get<double>(), "output", "max_abs", "rms",
                  "p95_abs", "max_rel");
      for (auto it = m["outputs"].begin(); it != m["outputs"].end(); ++it) {
        std::printf("  %-14s %12.4g %12.4g %12.4g %10.3g\n", it.key().c_str(),
                    (*it)["max_abs"].get<double>(), (*it)["rms"].get<double>(),
                    (*it)["p95_abs"].get<double>(), (*it)["max_rel"].get<double>());
      }
    }
    if (opt.tolerance >= 0.0) {
      std::printf("\ntolerance %.3g on max_rel: %s\n", opt.tolerance,
                  gate_failed ? "EXCEEDED" : "met");
    }
  }
  return gate_failed ? kExitGateFailed : kExitOk;
}

}  // namespace

void AddVerifyCommand(CLI::App& app, int* exit_code) {
  auto* cmd = app.add_subcommand("verify", "Re-solve sampled points and compare with a table");
  auto opt = std::make_shared<VerifyOptions>();
  cmd->add_option("TABLE", opt->table, "Table (HDF5) written by wrc generate")->required();
  cmd->add_option("--samples", opt->samples, "Number of sample points")->check(CLI::PositiveNumber);
  cmd->add_option("--seed", opt->seed, "Random seed (fixed: results are repeatable)");
  cmd->add_option("--sampler", opt->sampler, "uniform or lhs (Latin hypercube)")
      ->check(CLI::IsMember({"uniform", "lhs"}));
  cmd->add_flag("--near-jumps", opt->near_jumps,
                "Sample the cells where neighbouring table values jump (two-point contact)");
  cmd->add_flag("--json", opt->as_json, "Print the report as JSON (SPEC §5)");
  cmd->add_option("--tolerance", opt->tolerance,
                  "Fail (exit 1) when any output's max_rel exceeds this");
  cmd->add_option("--threads", opt->threads, "Worker threads (default: all cores)");
  cmd->callback([=]() {
    try {
      *exit_code = RunVerify(*opt);
    } catch (const std::exception& e) {
      std::cerr << "wrc verify: error: " << e.what() << '\n';
      *exit_code = kExitBadInput;
    }
  });
}

}  // namespace wrc::cli
