// VerifyTable(): sampled points re-solved exactly and compared with the table, in both
// interpolation modes, with errors also relative to the local wheel load and split by whether
// the number of contact patches changes within the point's cell.

#include "tools/wrc/verify.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <fstream>
#include <new>
#include <random>
#include <stdexcept>
#include <thread>
#include <utility>

#include "runtime/format/flat_table.h"
#include "runtime/hdf5/table_schema.h"
#include "tools/wrc/commands.h"
#include "wrc/core/errors.h"
#include "wrc/core/output_file.h"
#include "wrc/core/profile.h"
#include "wrc/core/wheelrail.h"
#include "wrc/generator/generator.h"
#include "wrc/generator/interrupt.h"
#include "wrc/generator/worker_threads.h"
#include "wrc/runtime.hpp"

namespace wrc::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The table's copy of a profile, checked against its recorded digest (a copy that differs
// would verify the table against another profile), written to `target`.
void RestoreProfile(const fs::path& table, const std::string& name, const fs::path& target) {
  const std::string bytes = ReadStoredProfile(table, name);
  fs::create_directories(target.parent_path());
  WriteFileAtomically(target, bytes);
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

// What max_rel divides by: the output's range over the table, but at least a thousandth of
// its largest magnitude. An output that is constant by construction (fz prescribed in
// [state]) varies only by the solver's tolerance; its range would turn that into a huge
// "relative" error.
struct ErrorScale {
  double range = 0.0;
  double scale = 0.0;
};

ErrorScale ErrorScaleOf(const std::vector<double>& values) {
  double largest = 0.0;
  for (double v : values) {
    if (std::isfinite(v)) largest = std::max(largest, std::fabs(v));
  }
  const double range = FiniteRange(values, 0.0);
  return {range, std::max(range, 1e-3 * largest)};
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

std::vector<std::size_t> Strides(const std::vector<std::vector<double>>& axes) {
  std::vector<std::size_t> stride(axes.size());
  std::size_t total = 1;
  for (std::size_t a = axes.size(); a-- > 0;) {
    stride[a] = total;
    total *= axes[a].size();
  }
  return stride;
}

// Samples concentrated in the grid cells where neighbouring table values jump: for each cell
// edge along each axis, the change of any output relative to that output's range; cells with
// the largest changes (top 5 %) are sampled uniformly.
std::vector<std::vector<double>> SampleNearJumps(const std::vector<std::vector<double>>& axes,
                                                 const std::vector<std::vector<double>>& outputs,
                                                 int n, std::uint64_t seed) {
  const std::size_t d = axes.size();
  const std::vector<std::size_t> stride = Strides(axes);
  std::size_t total = 1;
  for (const auto& axis : axes) total *= axis.size();
  std::vector<double> range(outputs.size(), 0.0);
  for (std::size_t o = 0; o < outputs.size(); ++o) range[o] = FiniteRange(outputs[o], 1.0);
  std::vector<std::pair<double, std::size_t>> edges;  // (jump, lower node) per axis-edge
  for (std::size_t node = 0; node < total; ++node) {
    for (std::size_t a = 0; a < d; ++a) {
      if ((node / stride[a]) % axes[a].size() + 1 >= axes[a].size()) continue;
      double jump = 0.0;
      for (std::size_t o = 0; o < outputs.size(); ++o) {
        const double dv = outputs[o][node + stride[a]] - outputs[o][node];
        if (std::isfinite(dv)) jump = std::max(jump, std::fabs(dv) / range[o]);
      }
      edges.push_back({jump, node});
    }
  }
  std::sort(edges.begin(), edges.end(),
            [](const auto& a, const auto& b) { return a.first > b.first; });
  const std::size_t keep = std::max<std::size_t>(1, edges.size() / 20);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<std::size_t> pick(0, keep - 1);
  std::vector<std::vector<double>> points(n, std::vector<double>(d));
  for (int k = 0; k < n; ++k) {
    const std::size_t node = edges[pick(rng)].second;
    for (std::size_t a = 0; a < d; ++a) {
      const std::size_t size = axes[a].size();
      const std::size_t i = (node / stride[a]) % size;
      // Within the cell above the node (or the last cell): anywhere along every axis.
      const std::size_t i0 = std::min(i, size > 1 ? size - 2 : 0);
      const double lo = axes[a][i0], hi = axes[a][std::min(i0 + 1, size - 1)];
      points[k][a] = lo + unit(rng) * (hi - lo);
    }
  }
  return points;
}

// Whether the patch count differs between the corners of the point's cell.
int PatchChange(const std::vector<std::vector<double>>& axes, const std::vector<double>& patches,
                const std::vector<double>& point) {
  const std::vector<std::size_t> stride = Strides(axes);
  std::vector<std::size_t> lower(axes.size());
  std::vector<bool> flat(axes.size());
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const std::vector<double>& v = axes[a];
    flat[a] = v.size() == 1;
    if (flat[a]) continue;
    const double x = std::clamp(point[a], v.front(), v.back());
    const std::size_t i =
        static_cast<std::size_t>(std::upper_bound(v.begin(), v.end(), x) - v.begin());
    lower[a] = std::min(std::max<std::size_t>(i, 1), v.size() - 1) - 1;
  }
  double lo = INFINITY, hi = -INFINITY;
  for (std::size_t corner = 0; corner < (std::size_t{1} << axes.size()); ++corner) {
    std::size_t node = 0;
    bool valid = true;
    for (std::size_t a = 0; a < axes.size(); ++a) {
      const bool up = (corner >> a) & 1;
      if (up && flat[a]) valid = false;
      node += (lower[a] + (up ? 1 : 0)) * stride[a];
    }
    if (!valid || !std::isfinite(patches[node])) continue;
    lo = std::min(lo, patches[node]);
    hi = std::max(hi, patches[node]);
  }
  return hi > lo ? 1 : 0;
}

double Percentile(std::vector<double> values, double q) {
  if (values.empty()) return kNaN;
  std::sort(values.begin(), values.end());
  return values[std::min(values.size() - 1, static_cast<std::size_t>(q * values.size()))];
}

double Rms(const std::vector<double>& values) {
  if (values.empty()) return kNaN;
  double sum2 = 0.0;
  for (const double v : values) sum2 += v * v;
  return std::sqrt(sum2 / static_cast<double>(values.size()));
}

double Max(const std::vector<double>& values) {
  return values.empty() ? kNaN : *std::max_element(values.begin(), values.end());
}

json Number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// The statistics of one output in one interpolation mode.
json OutputReport(const Verification& v, std::size_t o, bool cubic, const ErrorScale& scale) {
  std::vector<double> abs, rel_load, same_abs, same_load, change_abs, change_load;
  std::size_t worst = 0;
  double worst_error = -1.0;
  const bool force = IsForceOutput(v.output_names[o]);
  for (std::size_t k = 0; k < v.points.size(); ++k) {
    const VerifiedPoint& p = v.points[k];
    if (p.status > 1 || p.exact.size() <= o) continue;
    const double table = cubic ? p.cubic[o] : p.linear[o];
    if (!std::isfinite(p.exact[o]) || !std::isfinite(table)) continue;
    const double e = std::fabs(table - p.exact[o]);
    abs.push_back(e);
    if (e > worst_error) {
      worst_error = e;
      worst = k;
    }
    const double by_load = force && p.load > 0.0 ? e / p.load : kNaN;
    if (std::isfinite(by_load)) rel_load.push_back(by_load);
    (p.patch_change == 1 ? change_abs : same_abs).push_back(e);
    if (std::isfinite(by_load)) (p.patch_change == 1 ? change_load : same_load).push_back(by_load);
  }
  json worst_point = json::object();
  if (worst_error >= 0.0) {
    for (std::size_t a = 0; a < v.axis_names.size(); ++a) {
      worst_point[v.axis_names[a]] = v.points[worst].point[a];
    }
  }
  // No compared point: null, not a zero error that nothing measured.
  json report = {{"max_abs", Number(Max(abs))},
                 {"rms", Number(Rms(abs))},
                 {"p95_abs", Number(Percentile(abs, 0.95))},
                 {"max_rel", abs.empty()         ? json(nullptr)
                             : scale.scale > 0.0 ? json(Max(abs) / scale.scale)
                                                 : json(0.0)},
                 {"range", scale.range},
                 {"scale", scale.scale},
                 {"compared", abs.size()},
                 {"worst", worst_point}};
  if (force) {
    report["load"] = {{"p95", Number(Percentile(rel_load, 0.95))},
                      {"rms", Number(Rms(rel_load))},
                      {"max", Number(Max(rel_load))},
                      {"unit", "fraction of the local wheel load"}};
  }
  const auto cell_stats = [&](const std::vector<double>& e, const std::vector<double>& l) {
    json cell = {{"compared", e.size()},
                 {"max_abs", Number(Max(e))},
                 {"p95_abs", Number(Percentile(e, 0.95))}};
    if (force) cell["max_load"] = Number(Max(l));
    if (force) cell["p95_load"] = Number(Percentile(l, 0.95));
    return cell;
  };
  report["cells"] = {{"same_patches", cell_stats(same_abs, same_load)},
                     {"patch_change", cell_stats(change_abs, change_load)}};
  return report;
}

// The wheel load of each point: the prescribed fz (axis or state), else the solved one.
void AssignLoads(const Scene& scene, const std::vector<std::string>& outputs,
                 std::vector<VerifiedPoint>* points) {
  int fz_axis = -1;
  for (std::size_t a = 0; a < scene.axes.size(); ++a) {
    if (scene.axes[a].name == "fz") fz_axis = static_cast<int>(a);
  }
  const auto fz_output = std::find(outputs.begin(), outputs.end(), "fz");
  for (VerifiedPoint& p : *points) {
    if (fz_axis >= 0) {
      p.load = p.point[static_cast<std::size_t>(fz_axis)];
    } else if (scene.base.state.fz) {
      p.load = *scene.base.state.fz;
    } else if (fz_output != outputs.end() && p.exact.size() == outputs.size()) {
      p.load = std::fabs(p.exact[static_cast<std::size_t>(fz_output - outputs.begin())]);
    } else {
      p.load = kNaN;
    }
  }
}

// Each output's node values, in the table's storage order, as the loaded table holds them.
std::vector<std::vector<double>> OutputNodeValues(const Table& table) {
  const double* nodes = wrc_table_node_values(table.get());
  std::size_t count = 1;
  for (int a = 0; a < table.num_axes(); ++a) count *= static_cast<std::size_t>(table.axis_size(a));
  const auto n_out = static_cast<std::size_t>(table.num_outputs());
  std::vector<std::vector<double>> values(n_out, std::vector<double>(count));
  for (std::size_t node = 0; node < count; ++node) {
    for (std::size_t o = 0; o < n_out; ++o) values[o][node] = nodes[node * n_out + o];
  }
  return values;
}

}  // namespace

StoredScene::~StoredScene() {
  std::error_code ec;
  if (!scratch.empty()) fs::remove_all(scratch, ec);
}

std::unique_ptr<StoredScene> LoadStoredScene(const fs::path& table) {
  const Table validated(table.string());  // the runtime's checks, before any other read
  if (const std::string warning = validated.warning(); !warning.empty()) {
    std::cerr << "wrc verify: warning: " << warning << '\n';
  }
  if (format::IsFlatTableFile(table.string())) {
    throw InputError(table.string() +
                     ": a flat table (wrc export) holds neither the scene's profiles nor its "
                     "failures: use the HDF5 table it was exported from");
  }
  auto stored = std::make_unique<StoredScene>();
  const std::string text = validated.attribute(schema::kScene);
  stored->scratch = fs::temp_directory_path() /
                    ("wrc_verify_" + std::to_string(std::random_device{}()) + "_" +
                     std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
  fs::create_directories(stored->scratch);
  stored->scene = ParseScene(text, stored->scratch, table.string() + ":/scene");
  // The profiles are solved from copies inside the scratch directory, whatever paths the scene
  // names: an absolute or "../" path would otherwise overwrite the user's own file.
  for (auto [name, source] : {std::pair{"rail", &stored->scene.base.rail},
                              std::pair{"wheel", &stored->scene.base.wheel}}) {
    const fs::path file_name = source->path.filename();
    source->path = stored->scratch / name / (file_name.empty() ? fs::path(name) : file_name);
    RestoreProfile(table, name, source->path);
  }
  // Read and spline the profiles once for all sampled points (as LoadScene does).
  for (auto [source, kind] : {std::pair{&stored->scene.base.rail, ProfileKind::kRail},
                              std::pair{&stored->scene.base.wheel, ProfileKind::kWheel}}) {
    try {
      source->spline = std::make_shared<const ProfileSpline>(
          ReadProfile(source->path.string(), kind, ProfileOptionsOf(*source)));
    } catch (const InputError& error) {
      // The message names the scratch copy, deleted when verify ends: name the table's copy.
      std::string message = error.what();
      const std::string scratch = source->path.string();
      const std::string stored_at =
          table.string() + ":/profiles/" + (kind == ProfileKind::kRail ? "rail" : "wheel");
      for (auto at = message.find(scratch); at != std::string::npos;
           at = message.find(scratch, at + stored_at.size())) {
        message.replace(at, scratch.size(), stored_at);
      }
      throw InputError(message);
    }
  }
  return stored;
}

void SolveExactly(const Scene& scene, const std::vector<std::vector<double>>& points, int threads,
                  std::vector<std::vector<double>>* values, std::vector<int>* status,
                  std::vector<double>* seconds, std::vector<std::string>* messages) {
  messages->assign(points.size(), {});
  values->assign(points.size(), {});
  status->assign(points.size(), 3);
  seconds->assign(points.size(), 0.0);
  gen::ClearInterrupt();
  const gen::InterruptHandlers handlers;
  std::atomic<std::size_t> next{0}, solved{0};
  std::atomic<bool> out_of_memory{false};  // a fault of the run, not of the sampled point
  auto worker = [&]() {
    for (std::size_t k = next++;
         k < points.size() && !gen::InterruptRequested() && !out_of_memory.load(); k = next++) {
      const auto t0 = std::chrono::steady_clock::now();
      try {
        const WheelRailResult r = SolveWheelRail(CaseAtPoint(scene, points[k]));
        (*status)[k] = r.status == SolverStatus::kConverged   ? 0
                       : r.status == SolverStatus::kNoContact ? 1
                                                              : 2;
        (*values)[k] = SceneOutputValues(scene, r, static_cast<PointStatus>((*status)[k]));
      } catch (const std::bad_alloc&) {
        out_of_memory.store(true);
        break;
      } catch (...) {
        (*status)[k] = 3;
        // As a table stores it; a bug propagates and ends the command (after Join).
        (*messages)[k] = PointFailureMessage(std::current_exception());
      }
      (*seconds)[k] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      ++solved;
    }
  };
  const int n = threads > 0 ? threads : std::max(1u, std::thread::hardware_concurrency());
  gen::WorkerThreads pool(n, worker, "wrc verify");
  pool.Join();
  if (out_of_memory.load()) {
    throw ResourceError("out of memory after " + std::to_string(solved) + " of " +
                        std::to_string(points.size()) +
                        " exact solves; no report or file written: run with fewer "
                        "--threads or more memory");
  }
  if (gen::InterruptRequested()) {
    throw Interrupted("interrupted after " + std::to_string(solved) + " of " +
                      std::to_string(points.size()) + " exact solves; no report or file written");
  }
}

namespace {

// The mean time of one lookup at the sample points. A first pass warms the caches and the
// kernels' dispatch (a cold first lookup costs microseconds); then whole passes are timed until
// 10 ms have passed, so that a few samples still give a steady figure.
double MeanLookupSeconds(const Table& table, const std::vector<std::vector<double>>& points,
                         double* out) {
  if (points.empty()) return 0.0;
  for (const std::vector<double>& point : points) table.try_eval(point.data(), out);
  constexpr double kMinSeconds = 0.01;
  const auto t0 = std::chrono::steady_clock::now();
  double elapsed = 0.0;
  std::size_t lookups = 0;
  while (elapsed < kMinSeconds) {
    for (const std::vector<double>& point : points) table.try_eval(point.data(), out);
    lookups += points.size();
    elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  return elapsed / static_cast<double>(lookups);
}

}  // namespace

Verification VerifyTable(const VerifyOptions& opt) {
  auto stored = LoadStoredScene(opt.table);
  const Scene& scene = stored->scene;
  Table table(opt.table);
  Verification v;
  v.axis_names = table.axis_names();
  v.output_names = table.output_names();
  const std::size_t n_out = v.output_names.size();
  std::vector<std::vector<double>> axes;
  for (int a = 0; a < table.num_axes(); ++a) axes.push_back(table.axis_values(a));
  // Output values over the table, for the ranges, the patch counts and the near-jump sampler.
  const std::vector<std::vector<double>> values = OutputNodeValues(table);
  std::vector<ErrorScale> scales(n_out);
  for (std::size_t o = 0; o < n_out; ++o) scales[o] = ErrorScaleOf(values[o]);
  const auto patches_output = std::find(v.output_names.begin(), v.output_names.end(), "n_patches");
  const std::vector<std::vector<double>> points =
      opt.near_jumps ? SampleNearJumps(axes, values, opt.samples, opt.seed)
                     : Sample(axes, opt.samples, opt.seed, opt.sampler == "lhs");

  std::vector<std::vector<double>> exact;
  std::vector<int> status;
  std::vector<double> seconds;
  std::vector<std::string> messages;
  SolveExactly(scene, points, opt.threads, &exact, &status, &seconds, &messages);
  v.points.resize(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    v.points[k].point = points[k];
    v.points[k].status = status[k];
    v.points[k].exact = exact[k];
    if (patches_output != v.output_names.end()) {
      v.points[k].patch_change = PatchChange(
          axes, values[static_cast<std::size_t>(patches_output - v.output_names.begin())],
          points[k]);
    }
  }
  AssignLoads(scene, v.output_names, &v.points);

  json& result = v.report;
  result = {{"table", opt.table},
            {"samples", opt.samples},
            {"seed", opt.seed},
            {"sampler", opt.near_jumps ? "near-jumps" : opt.sampler}};
  double total_solve = 0.0;
  for (double s : seconds) total_solve += s;
  result["solve_time_s"] = {{"mean", total_solve / std::max<std::size_t>(1, points.size())}};
  int counts[4] = {0, 0, 0, 0};
  int cells_with_change = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    counts[status[k]]++;
    cells_with_change += v.points[k].patch_change == 1 ? 1 : 0;
  }
  result["exact_status"] = {{"ok", counts[0]},
                            {"no_contact", counts[1]},
                            {"not_converged", counts[2]},
                            {"error", counts[3]}};
  result["points_in_patch_change_cells"] = cells_with_change;
  const auto first_error =
      std::find_if(messages.begin(), messages.end(), [](const auto& m) { return !m.empty(); });
  if (first_error != messages.end()) result["first_error"] = *first_error;
  for (Interpolation mode : {Interpolation::kLinear, Interpolation::kCubic}) {
    table.set_interpolation(mode);
    const bool cubic = mode == Interpolation::kCubic;
    std::vector<double> out(n_out);
    int flagged = 0, no_value = 0;
    const double lookup = MeanLookupSeconds(table, points, out.data());
    for (std::size_t k = 0; k < points.size(); ++k) {
      const int code = table.try_eval(points[k].data(), out.data());
      if (code < 0) {
        ++no_value;  // the table has no value there (every corner failed)
        out.assign(n_out, kNaN);
      } else if (code & WRC_FLAG_STATUS) {
        ++flagged;
      }
      (cubic ? v.points[k].cubic : v.points[k].linear) = out;
    }
    json outputs = json::object();
    for (std::size_t o = 0; o < n_out; ++o) {
      outputs[v.output_names[o]] = OutputReport(v, o, cubic, scales[o]);
    }
    const std::string key = cubic ? "cubic" : "linear";
    result["interpolation"][key] = {{"outputs", outputs},
                                    {"lookup_time_s", {{"mean", lookup}}},
                                    {"flagged_points", flagged},
                                    {"points_without_value", no_value}};
    if (!cubic) {
      // The top-level fields are those of the default (multilinear) interpolation.
      result["outputs"] = outputs;
      result["lookup_time_s"] = {{"mean", lookup}};
    }
  }
  return v;
}

}  // namespace wrc::cli
