// RefineTable(): error-driven node placement over repeated grid runs (see refine.h).
//
// Files of a refinement of TABLE.h5, in TABLE.h5.refine/ (removed when the table is written):
//   passes            the axes of every pass decided so far (hex floats, exact), rewritten
//                     atomically after each decision: a resume continues at the last one;
//   pass<P>.h5.journal  the grid journal of pass P (kept until pass P + 1 is complete);
//   samples<P>.journal  the midpoint solves of pass P (same record format);
//   check.journal       the exact solves at the random states that judge every pass;
//   check.h5            a pass's grid as a table, while cubic lookups judge it.
// With --keep-passes, every pass's grid is also written as TABLE.h5.pass<P>.h5 (kept).

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <thread>
#include <unordered_map>

#include "generator/journal.h"
#include "generator/progress.h"
#include "generator/refine.h"
#include "generator/sha256.h"
#include "generator/sweep.h"
#include "runtime/format/little_endian.h"
#include "runtime/hdf5/table_schema.h"
#include "runtime/interp/cubic_line.h"
#include "wrc/core/errors.h"
#include "wrc/core/scene.h"
#include "wrc/generator/interrupt.h"
#include "wrc/generator/worker_threads.h"
#include "wrc/runtime.hpp"

namespace wrc::gen {
namespace {

namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// An axis without a min_step gets range / 2048: eleven halvings of the range. The onset of
// flange contact is a kink whose slope jumps by about 3e5 N/mm (the flange's contact
// stiffness), so a linear interval across it errs by a quarter of that times its width: on the
// Manchester pair a 0.068 mm interval still errs by 36 % of a 10 kN load, and range / 512
// (0.043 mm over 21.8 mm, so no interval below 0.085 mm is split) stopped there. The score²
// ranking spends a true discontinuity's nodes only while they pay, and a limit still keeps
// one from taking the whole budget.
constexpr double kDefaultMinStepFraction = 1.0 / 2048.0;
// A pass at most doubles the point count: the intervals that pay most go first, and those that
// pay little wait until the better ones are within target instead of taking the budget early
// (every split is final). Doubling keeps the passes few: about log2(budget / start) of them.
constexpr double kMaxGrowthPerPass = 2.0;
// With the quantile stop, a pass grows the table by what the error's fall over the last pass
// predicts it needs to meet the target, times this margin (the fall is measured, not known),
// and by at least kMinGrowthPerPass: the last pass then does not double a table that needed a
// third more.
constexpr double kGrowthMargin = 1.2;
constexpr double kMinGrowthPerPass = 1.1;
// Halving an interval divides a smooth function's linear-interpolation error by four.
constexpr double kSmoothSplitGain = 4.0;
// Exact solves at uniformly random states, the same every pass (solved once), that judge each
// pass against the stop rule and give the final estimate. With 1000 of them the 95 % quantile's
// 90 % upper bound (QuantileBound) lies about nine ranks above the sample's own 95 % quantile.
constexpr int kCheckPoints = 1000;
// One-sided normal quantile of the stop rule's confidence (90 %) that the share of states
// within the target is at least the asked quantile.
constexpr double kStopConfidenceZ = 1.2816;
// The score of an interval whose midpoint fails to solve while its ends solve (see
// ScoreIntervals), in units of the target.
constexpr double kFailedMidpointScore = 1.5;
// Messages to other ranks between passes.
constexpr int kTagAxes = 20;
enum class PassKind : char { kGrid = 'g', kFinal = 'f', kStop = 's' };

using Axes = std::vector<SceneAxis>;

// ---- small functions --------------------------------------------------------------------------

std::string HexDouble(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%a", value);
  return text;
}

fs::path WorkDirectory(const fs::path& output) { return fs::path(output.string() + ".refine"); }
fs::path PassOutput(const fs::path& work, int pass) {
  return work / ("pass" + std::to_string(pass) + ".h5");
}
fs::path PassJournal(const fs::path& work, int pass) {
  return fs::path(PassOutput(work, pass).string() + ".journal");
}
fs::path SamplesJournal(const fs::path& work, int pass) {
  return work / ("samples" + std::to_string(pass) + ".journal");
}

std::string RawSha(const std::string& text) {
  const std::string hex = Sha256Hex(text);
  std::string raw;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) {
    raw += static_cast<char>(std::stoi(hex.substr(i, 2), nullptr, 16));
  }
  return raw;
}

std::size_t PointCount(const Axes& axes) {
  std::size_t n = 1;
  for (const SceneAxis& axis : axes) n *= axis.values.size();
  return n;
}

Scene WithAxes(const Scene& scene, const Axes& axes) {
  Scene copy = scene;
  copy.axes = axes;
  copy.refine.reset();
  return copy;
}

// SplitMix64: a portable, seedable stream, so that the same seed draws the same samples on
// every platform (std::uniform_real_distribution is implementation-defined).
class SplitMix {
 public:
  explicit SplitMix(std::uint64_t seed) : state_(seed) {}
  std::uint64_t Next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double Unit() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }

 private:
  std::uint64_t state_;
};

std::uint64_t Mix(std::uint64_t a, std::uint64_t b) {
  SplitMix mix(a * 0x100000001B3ull ^ b);
  return mix.Next();
}

std::size_t NearestNode(const std::vector<double>& nodes, double x) {
  const auto upper = std::lower_bound(nodes.begin(), nodes.end(), x);
  if (upper == nodes.begin()) return 0;
  if (upper == nodes.end()) return nodes.size() - 1;
  const std::size_t i = static_cast<std::size_t>(upper - nodes.begin());
  return (x - nodes[i - 1] <= nodes[i] - x) ? i - 1 : i;
}

std::vector<std::size_t> Strides(const Axes& axes) {
  std::vector<std::size_t> stride(axes.size());
  std::size_t s = 1;
  for (std::size_t a = axes.size(); a-- > 0;) {
    stride[a] = s;
    s *= axes[a].values.size();
  }
  return stride;
}

PointResult ResultAt(const TableData& data, std::uint64_t point) {
  PointResult r;
  r.status = static_cast<PointStatus>(data.status[point]);
  r.solve_time_s = data.solve_time_s[point];
  r.z = data.z[point];
  r.values.resize(data.values.size());
  for (std::size_t k = 0; k < data.values.size(); ++k) r.values[k] = data.values[k][point];
  const auto message = data.messages.find(point);
  if (message != data.messages.end()) r.message = message->second;
  return r;
}

// The point's coordinates as bytes: a map key, and part of the check journal's fingerprint.
std::string PointKey(const std::vector<double>& point) {
  std::string key;
  for (const double v : point) le::PutF64(key, v);
  return key;
}

// ---- the passes file ------------------------------------------------------------------------

std::string SceneIdentity(const Scene& scene) {
  return Sha256Hex(scene.base.source_text + "\n" + Sha256FileHex(scene.base.rail.path) + "\n" +
                   Sha256FileHex(scene.base.wheel.path));
}

// What a pass did, for the table's refine_passes record.
struct PassRecord {
  std::size_t points = 0, new_points = 0, samples = 0, above_target = 0;
  double worst = 0.0;
  /// The error at the random check states over the grid of this pass (units of the target):
  /// the asked quantile and its upper confidence bound, which the stop rule reads.
  double quantile_error = kNaN, quantile_bound = kNaN;
  /// CPU seconds of this process from the start of the run (or of its resume) to the end of
  /// this pass's decision.
  double cpu_seconds = kNaN;
};

void WritePasses(const fs::path& work, const std::string& identity, const std::vector<Axes>& passes,
                 const std::vector<PassRecord>& records) {
  std::ostringstream text;
  text << "wrc-refine 2 " << identity << "\n";
  for (std::size_t p = 0; p < passes.size(); ++p) {
    text << "pass " << p << "\n";
    for (const SceneAxis& axis : passes[p]) {
      text << axis.name << " " << axis.values.size();
      for (const double v : axis.values) text << " " << HexDouble(v);
      text << "\n";
    }
    if (p < records.size()) {
      const PassRecord& r = records[p];
      text << "record " << r.points << " " << r.new_points << " " << r.samples << " "
           << r.above_target << " " << HexDouble(r.worst) << " " << HexDouble(r.quantile_error)
           << " " << HexDouble(r.quantile_bound) << " " << HexDouble(r.cpu_seconds) << "\n";
    }
  }
  text << "end\n";
  const fs::path temporary = work / "passes.tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << text.str();
    out.flush();
    if (!out) throw InputError(temporary.string() + ": cannot write the refinement state");
  }
  fs::rename(temporary, work / "passes");
}

std::vector<Axes> ReadPasses(const fs::path& work, const std::string& identity, const Scene& scene,
                             std::vector<PassRecord>* records) {
  const fs::path path = work / "passes";
  std::ifstream in(path);
  const auto damaged = [&](const std::string& why) {
    return InputError(path.string() + ": " + why + "; delete " + work.string() +
                      " to start the refinement over");
  };
  std::string magic, version, stored_identity;
  // Version 1 (records without the check's quantile and the CPU time) is still read.
  if (!(in >> magic >> version >> stored_identity) || magic != "wrc-refine" ||
      (version != "1" && version != "2")) {
    throw damaged("not a refinement state file");
  }
  if (stored_identity != identity) {
    throw damaged("it belongs to another scene or other profile files");
  }
  std::vector<Axes> passes;
  std::string word;
  records->clear();
  while (in >> word) {
    if (word == "end") return passes;
    if (word == "record") {
      PassRecord r;
      std::string worst, quantile, bound, cpu;
      if (!(in >> r.points >> r.new_points >> r.samples >> r.above_target >> worst) ||
          (version == "2" && !(in >> quantile >> bound >> cpu))) {
        throw damaged("damaged");
      }
      r.worst = std::strtod(worst.c_str(), nullptr);
      if (version == "2") {
        r.quantile_error = std::strtod(quantile.c_str(), nullptr);
        r.quantile_bound = std::strtod(bound.c_str(), nullptr);
        r.cpu_seconds = std::strtod(cpu.c_str(), nullptr);
      }
      records->push_back(r);
      continue;
    }
    std::size_t index = 0;
    if (word != "pass" || !(in >> index) || index != passes.size()) throw damaged("damaged");
    Axes axes;
    for (const SceneAxis& expected : scene.axes) {
      std::string name;
      std::size_t count = 0;
      if (!(in >> name >> count) || name != expected.name || count == 0) throw damaged("damaged");
      SceneAxis axis{name, {}};
      for (std::size_t i = 0; i < count; ++i) {
        std::string hex;
        if (!(in >> hex)) throw damaged("damaged");
        axis.values.push_back(std::strtod(hex.c_str(), nullptr));
      }
      axes.push_back(std::move(axis));
    }
    passes.push_back(std::move(axes));
  }
  throw damaged("truncated");
}

// ---- samples --------------------------------------------------------------------------------

double MinStep(const RefineSettings& settings, const SceneAxis& axis) {
  const auto it = settings.min_step.find(axis.name);
  if (it != settings.min_step.end()) return it->second;
  return (axis.values.back() - axis.values.front()) * kDefaultMinStepFraction;
}

bool Splittable(const RefineSettings& settings, const SceneAxis& axis, std::size_t interval) {
  const double a = axis.values[interval];
  const double b = axis.values[interval + 1];
  // Both halves must also stay within the runtime's axis limits, whatever min_step says, or
  // the table could not be opened.
  const double middle = 0.5 * (a + b);
  return b - a >= 2.0 * MinStep(settings, axis) && AxisStepIsResolvable(a, middle) &&
         AxisStepIsResolvable(middle, b);
}

}  // namespace

std::vector<RefineSample> DrawRefineSamples(const Axes& axes, const RefineSettings& settings,
                                            int pass) {
  std::vector<RefineSample> samples;
  for (std::size_t k = 0; k < axes.size(); ++k) {
    const std::vector<double>& nodes = axes[k].values;
    for (std::size_t j = 0; j + 1 < nodes.size(); ++j) {
      if (!Splittable(settings, axes[k], j)) continue;
      SplitMix rng(Mix(Mix(settings.seed, static_cast<std::uint64_t>(pass)), k * 1'000'003 + j));
      for (int s = 0; s < settings.samples; ++s) {
        RefineSample sample;
        sample.axis = k;
        sample.interval = j;
        for (std::size_t a = 0; a < axes.size(); ++a) {
          const std::vector<double>& v = axes[a].values;
          if (a == k) {
            sample.nodes.push_back(j);
            sample.point.push_back(0.5 * (v[j] + v[j + 1]));
          } else {
            const double x = v.front() + rng.Unit() * (v.back() - v.front());
            sample.nodes.push_back(NearestNode(v, x));
            sample.point.push_back(v[sample.nodes.back()]);
          }
        }
        samples.push_back(std::move(sample));
      }
    }
  }
  return samples;
}

namespace {

struct SampleRun {
  std::vector<PointResult> results;
  std::size_t computed = 0;
  bool complete = false;
};

// Solves points on this process's threads, journaled in `journal_path` so that an interrupted
// run keeps them. z_guess[i] warm-starts point i.
SampleRun SolvePoints(const Scene& scene, const std::vector<std::vector<double>>& points,
                      const std::vector<double>& z_guess, const fs::path& journal_path,
                      const std::string& identity, int threads, StopControl& stop,
                      ProgressMode progress_mode) {
  std::string fingerprint_text = identity;
  for (const auto& point : points) fingerprint_text += PointKey(point);
  const JournalHeader header{RawSha(fingerprint_text), points.size(),
                             static_cast<std::uint32_t>(scene.outputs.size())};
  SampleRun run;
  run.results.resize(points.size());
  std::vector<char> done(points.size(), 0);
  std::size_t reused = 0;
  std::optional<JournalWriter> journal;
  if (fs::exists(journal_path)) {
    JournalContents contents;
    journal.emplace(JournalWriter::Continue(journal_path, header, &contents));
    for (JournalRecord& record : contents.records) {
      if (record.index >= points.size() || done[record.index]) continue;
      run.results[record.index] = std::move(record.result);
      done[record.index] = 1;
      ++reused;
    }
  } else {
    journal.emplace(JournalWriter::Create(journal_path, header));
  }
  std::mutex mutex;
  std::atomic<std::size_t> next{0}, computed{0};
  const auto work = [&]() {
    WheelRailCache cache;  // random points rarely share a pose, but always the placement check
    try {
      for (std::size_t i = next++; i < points.size(); i = next++) {
        if (done[i]) continue;
        if (!stop.ClaimPoint()) break;
        Scene at = scene;
        for (std::size_t a = 0; a < at.axes.size(); ++a) at.axes[a].values = {points[i][a]};
        PointResult result =
            SolveScenePoint(at, std::vector<std::size_t>(at.axes.size(), 0), z_guess[i], &cache);
        const std::string record = EncodeRecord(i, result);
        std::lock_guard<std::mutex> lock(mutex);
        journal->Append(record);
        run.results[i] = std::move(result);
        done[i] = 1;
        computed.fetch_add(1);
      }
    } catch (...) {
      stop.RequestStop();  // an error outside a solve (the journal's disk is full) ends the run
      throw;               // to the pool, whose Join() rethrows it
    }
  };
  ProgressReporter progress(progress_mode, points.size(), reused);
  WorkerThreads pool(std::max(1, threads), work, "wrc generate");
  try {
    auto last_sync = std::chrono::steady_clock::now();
    while (!pool.Finished()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      progress.Update(computed.load());
      if (std::chrono::steady_clock::now() - last_sync > std::chrono::seconds(1)) {
        std::lock_guard<std::mutex> lock(mutex);  // appends and syncs do not interleave
        journal->Sync();
        last_sync = std::chrono::steady_clock::now();
      }
    }
  } catch (...) {
    stop.RequestStop();  // the pool's destructor joins workers that then take no new point
    throw;
  }
  pool.Join();
  journal->Sync();
  journal->Close();
  progress.Finish(computed.load());
  run.computed = computed.load();
  run.complete = std::all_of(done.begin(), done.end(), [](char d) { return d != 0; });
  return run;
}

// ---- errors ---------------------------------------------------------------------------------

// How the refined outputs' errors are measured: per output its index in the scene's outputs
// and either an absolute tolerance or the fraction of the local load.
struct ErrorModel {
  std::vector<std::size_t> outputs;
  std::vector<double> absolute;  ///< NaN for force outputs (relative to the load).
  double load_fraction = 0.0;
  int fz_axis = -1;        ///< Axis holding the prescribed load, or -1.
  double fz_state = kNaN;  ///< The scene's prescribed load when fz is not an axis.
  int fz_output = -1;      ///< Index of output fz, or -1.
};

ErrorModel MakeErrorModel(const Scene& scene, const RefineSettings& settings) {
  ErrorModel model;
  model.load_fraction = settings.load_fraction;
  for (const std::string& name : settings.outputs) {
    const auto it = std::find(scene.outputs.begin(), scene.outputs.end(), name);
    model.outputs.push_back(static_cast<std::size_t>(it - scene.outputs.begin()));
    const auto abs = settings.absolute.find(name);
    model.absolute.push_back(IsForceOutput(name) ? kNaN : abs->second);
  }
  for (std::size_t a = 0; a < scene.axes.size(); ++a) {
    if (scene.axes[a].name == "fz") model.fz_axis = static_cast<int>(a);
  }
  if (scene.base.state.fz) model.fz_state = *scene.base.state.fz;
  const auto fz = std::find(scene.outputs.begin(), scene.outputs.end(), "fz");
  if (fz != scene.outputs.end()) model.fz_output = static_cast<int>(fz - scene.outputs.begin());
  return model;
}

// The local wheel load at `point` from the prescribed fz or, where z is prescribed, the
// largest solved vertical force among the given results.
double LocalLoad(const ErrorModel& model, const std::vector<double>& point,
                 std::initializer_list<const std::vector<double>*> values) {
  if (model.fz_axis >= 0) return point[static_cast<std::size_t>(model.fz_axis)];
  if (std::isfinite(model.fz_state)) return model.fz_state;
  double load = 0.0;
  for (const std::vector<double>* v : values) {
    const double fz = (*v)[static_cast<std::size_t>(model.fz_output)];
    if (std::isfinite(fz)) load = std::max(load, std::fabs(fz));
  }
  return load;
}

bool Usable(PointStatus status) {
  return status == PointStatus::kOk || status == PointStatus::kNoContact;
}

// The error of `estimate` against `exact` in each refined output (model.outputs order), in
// units of its target (1 = exactly on target); NaN where it cannot be compared.
std::vector<double> NormalisedErrors(const ErrorModel& model, double load,
                                     const std::vector<double>& exact,
                                     const std::vector<double>& estimate) {
  std::vector<double> errors(model.outputs.size(), kNaN);
  for (std::size_t i = 0; i < model.outputs.size(); ++i) {
    const std::size_t k = model.outputs[i];
    if (!std::isfinite(exact[k]) || !std::isfinite(estimate[k])) continue;
    const double tolerance =
        std::isnan(model.absolute[i]) ? model.load_fraction * load : model.absolute[i];
    if (!(tolerance > 0.0)) continue;  // no load (no contact anywhere): forces are exactly 0
    errors[i] = std::fabs(exact[k] - estimate[k]) / tolerance;
  }
  return errors;
}

// The largest of NormalisedErrors(); NaN when nothing could be compared.
double NormalisedError(const ErrorModel& model, double load, const std::vector<double>& exact,
                       const std::vector<double>& estimate) {
  double worst = kNaN;
  for (const double e : NormalisedErrors(model, load, exact, estimate)) {
    if (!std::isnan(e)) worst = std::isnan(worst) ? e : std::max(worst, e);
  }
  return worst;
}

struct IntervalScore {
  double max_error = 0.0;       ///< In units of the target.
  double sum_of_squares = 0.0;  ///< Of the sampled errors, in units of the target.
  int samples = 0;
  /// Samples above the target, and of those the ones above kSmoothSplitGain × target.
  int above = 0, far_above = 0;
  double MeanSquare() const { return samples > 0 ? sum_of_squares / samples : 0.0; }
  /// The share of the interval's samples a split is expected to bring within the target: a
  /// smooth error falls by kSmoothSplitGain when the interval is halved, so those up to that
  /// factor above the target come within it; further above lies a jump (or a far coarser
  /// interval), whose band a split halves.
  double ShareMended() const {
    if (samples == 0) return 0.0;
    return (static_cast<double>(above - far_above) + 0.5 * static_cast<double>(far_above)) /
           static_cast<double>(samples);
  }
  void Add(double error) {
    max_error = std::max(max_error, error);
    sum_of_squares += error * error;
    ++samples;
    above += error > 1.0 ? 1 : 0;
    far_above += error > kSmoothSplitGain ? 1 : 0;
  }
};

using Interpolation = RefineSettings::Interpolation;

// The runtime's cubic lookup at local coordinate t of interval j of axis a, every other
// coordinate at the node of `on_line` (any node of the grid line): there only this axis' value
// and slope terms enter (the other axes' bases are 1 and 0), so it is the one-dimensional
// Hermite cubic with the runtime's limited slopes (runtime/interp/cubic_line.h).
double CubicAlongAxis(const Axes& axes, const std::vector<std::size_t>& stride,
                      const std::vector<double>& values, std::uint64_t on_line, std::size_t a,
                      std::size_t j, double t) {
  const std::vector<double>& x = axes[a].values;
  const auto n = static_cast<std::uint64_t>(x.size());
  const std::uint64_t first = on_line - on_line / stride[a] % n * stride[a];
  // The slopes of nodes j and j + 1 read at most kWindow - 1 nodes beyond them.
  const int jj = static_cast<int>(j);
  const int lo = std::max(0, jj - (cubic::kWindow - 1));
  const int hi = std::min(static_cast<int>(n) - 1, jj + cubic::kWindow);
  std::array<double, 2 * cubic::kWindow> f{};
  for (int m = lo; m <= hi; ++m)
    f[static_cast<std::size_t>(m - lo)] = values[first + static_cast<std::uint64_t>(m) * stride[a]];
  const double* xs = x.data() + lo;
  const int width = hi - lo + 1;
  double basis[4];
  cubic::HermiteBasis(t, x[j + 1] - x[j], basis);
  return basis[0] * f[static_cast<std::size_t>(jj - lo)] +
         basis[1] * cubic::NodeSlope(xs, width, f.data(), jj - lo) +
         basis[2] * f[static_cast<std::size_t>(jj + 1 - lo)] +
         basis[3] * cubic::NodeSlope(xs, width, f.data(), jj + 1 - lo);
}

// Midpoint errors of the interpolant the table will be read with, per axis and interval: for
// linear lookups the mean of the interval's end values, for cubic ones the Hermite cubic along
// the interval's axis.
std::vector<std::vector<IntervalScore>> ScoreIntervals(const Axes& axes, const TableData& data,
                                                       const std::vector<RefineSample>& samples,
                                                       const std::vector<PointResult>& results,
                                                       const ErrorModel& model,
                                                       Interpolation interpolation) {
  std::vector<std::vector<IntervalScore>> scores(axes.size());
  for (std::size_t a = 0; a < axes.size(); ++a) {
    scores[a].resize(axes[a].values.size() > 1 ? axes[a].values.size() - 1 : 0);
  }
  const std::vector<std::size_t> stride = Strides(axes);
  for (std::size_t s = 0; s < samples.size(); ++s) {
    const RefineSample& sample = samples[s];
    std::uint64_t lower = 0;
    for (std::size_t a = 0; a < axes.size(); ++a) lower += sample.nodes[a] * stride[a];
    const std::uint64_t upper = lower + stride[sample.axis];
    const PointResult& mid = results[s];
    if (data.status[lower] > 1 || data.status[upper] > 1) continue;
    IntervalScore& score = scores[sample.axis][sample.interval];
    if (!Usable(mid.status)) {
      // Both ends solve, the middle does not: the behaviour changes in between, which a
      // finer grid resolves (or bounds, at min_step). Above target, but after every interval
      // with a measured error above 1.5 × target.
      score.Add(kFailedMidpointScore);
      continue;
    }
    const PointResult left = ResultAt(data, lower), right = ResultAt(data, upper);
    std::vector<double> estimate(left.values.size());
    for (std::size_t k = 0; k < estimate.size(); ++k) {
      estimate[k] = interpolation == Interpolation::kCubic
                        ? CubicAlongAxis(axes, stride, data.values[k], lower, sample.axis,
                                         sample.interval, 0.5)
                        : 0.5 * (left.values[k] + right.values[k]);
    }
    const double load = LocalLoad(model, sample.point, {&left.values, &right.values, &mid.values});
    const double e = NormalisedError(model, load, mid.values, estimate);
    if (std::isnan(e)) continue;
    score.Add(e);
  }
  return scores;
}

struct Split {
  std::size_t axis, interval;
  double priority;
};

// Splits intervals above target, those that lower the mean-square error the most per added
// point first, while the pass stays within kMaxGrowthPerPass and the table within the budget.
// Linear interpolation leaves an interval's error spread over its share of the state space, so
// its contribution to the mean square is about (mean squared sampled error) × relative width;
// a node on axis a adds N / n_a points (N points, n_a nodes on a). The mean, not the maximum,
// of the samples: a steep rise that moves with the other coordinates (the flange climb on the
// Manchester pair, 0.1 mm wide in y, moving by 0.1 mm with load, roll and yaw) shows in every
// sample of the y intervals it crosses but in few samples of a yaw interval, and splitting yaw
// there buys little. Ranking by score alone, or by score × width, starves narrow intervals
// around such a rise, which then dominate the rms of a uniform verification.
//
// With a quantile stop (quantile < 1) the aim is the share of the state space above target,
// not the mean square: an interval's gain is its ShareMended() × relative width, so that the
// few huge samples of a jump, which every axis' intervals see where it moves with them (a fz or
// roll interval at a flange node), do not buy whole hyperplanes that leave the jump as it was.
Axes SplitIntervals(const Axes& axes, const std::vector<std::vector<IntervalScore>>& scores,
                    std::size_t max_points, double max_growth, bool for_quantile,
                    std::size_t* refused) {
  std::vector<Split> candidates;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const std::vector<double>& v = axes[a].values;
    const double range = v.back() - v.front();
    for (std::size_t j = 0; j < scores[a].size(); ++j) {
      const IntervalScore& score = scores[a][j];
      if (score.max_error <= 1.0) continue;
      const double width = (v[j + 1] - v[j]) / range;
      const double gain = for_quantile ? score.ShareMended() : score.MeanSquare();
      candidates.push_back({a, j, gain * width * static_cast<double>(v.size())});
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Split& x, const Split& y) { return x.priority > y.priority; });
  std::vector<std::size_t> size(axes.size());
  for (std::size_t a = 0; a < axes.size(); ++a) size[a] = axes[a].values.size();
  const double pass_limit = max_growth * static_cast<double>(PointCount(axes));
  std::vector<std::vector<char>> chosen(axes.size());
  for (std::size_t a = 0; a < axes.size(); ++a) chosen[a].assign(scores[a].size(), 0);
  *refused = 0;
  for (const Split& split : candidates) {
    ++size[split.axis];
    double points = 1.0;
    for (const std::size_t n : size) points *= static_cast<double>(n);
    if (points > pass_limit && points <= static_cast<double>(max_points)) {
      // The pass is full: the rest wait for the next pass, ranked again on its samples.
      --size[split.axis];
      break;
    }
    if (points > static_cast<double>(max_points)) {
      --size[split.axis];
      ++*refused;
      continue;
    }
    chosen[split.axis][split.interval] = 1;
  }
  Axes next = axes;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const std::vector<double>& v = axes[a].values;
    std::vector<double> values;
    for (std::size_t i = 0; i < v.size(); ++i) {
      values.push_back(v[i]);
      if (i + 1 < v.size() && chosen[a][i]) values.push_back(0.5 * (v[i] + v[i + 1]));
    }
    next[a].values = std::move(values);
  }
  return next;
}

// ---- slope target ---------------------------------------------------------------------------

// Adds the slope target's nodes (SlopeNodes) to `axes`, axis by axis, while the grid stays
// within `max_points` and the runtime's axis limits. Counts in `refused` the axes left out.
void AddSlopeNodes(const std::vector<std::vector<double>>& nodes, std::size_t max_points,
                   Axes* axes, std::size_t* refused) {
  for (std::size_t a = 0; a < axes->size(); ++a) {
    std::vector<double> values = (*axes)[a].values;
    for (const double x : nodes[a]) {
      if (std::find(values.begin(), values.end(), x) == values.end()) values.push_back(x);
    }
    std::sort(values.begin(), values.end());
    const std::size_t added = values.size() - (*axes)[a].values.size();
    const double grown = static_cast<double>(PointCount(*axes)) *
                         static_cast<double>(values.size()) /
                         static_cast<double>((*axes)[a].values.size());
    if (added == 0) continue;
    bool resolvable = true;  // the runtime's axis limits, as for a split
    for (std::size_t i = 0; i + 1 < values.size(); ++i) {
      resolvable = resolvable && AxisStepIsResolvable(values[i], values[i + 1]);
    }
    if (!resolvable || grown > static_cast<double>(max_points)) {
      ++*refused;
      continue;
    }
    (*axes)[a].values = std::move(values);
  }
}

// How many times the grid grows when `nodes` join it.
double SlopeGrowth(const std::vector<std::vector<double>>& nodes, const Axes& axes) {
  double growth = 1.0;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const double n = static_cast<double>(axes[a].values.size());
    growth *= (n + static_cast<double>(nodes[a].size())) / n;
  }
  return growth;
}

// ---- final estimate -------------------------------------------------------------------------

struct ErrorEstimate {
  int compared = 0;
  /// Of each state's largest error over the refined outputs, in units of the target.
  double p50 = kNaN, p95 = kNaN, max = kNaN;
  /// The stop rule's quantile of each refined output's errors and its upper confidence bound,
  /// the largest over the outputs (as `wrc verify` reports a quantile per output), and the
  /// output that has it.
  double quantile = kNaN, bound = kNaN;
  std::string worst_output;
};

// The rank (0-based, in ascending order) of the sample that bounds the q-quantile from above
// with kStopConfidenceZ's confidence: the number of samples below the true quantile is
// binomial (n, q), so it exceeds n·q + z·sqrt(n·q·(1 − q)) only with that small probability.
// q = 1 gives the largest sample.
std::size_t QuantileBoundRank(std::size_t n, double q) {
  const double nq = static_cast<double>(n) * q;
  const double rank = std::ceil(nq + kStopConfidenceZ * std::sqrt(nq * (1.0 - q)));
  return std::min(n - 1, static_cast<std::size_t>(rank));
}

// The sample quantile q of sorted errors (the same rank rule as `wrc verify`'s p95).
double SortedQuantile(const std::vector<double>& sorted, double q) {
  return sorted[std::min(sorted.size() - 1, static_cast<std::size_t>(q * sorted.size()))];
}

// per_output[i]: output i's errors at the states where it could be compared; worst: each
// state's largest error.
ErrorEstimate Summarise(std::vector<double> worst, std::vector<std::vector<double>> per_output,
                        const std::vector<std::string>& names, double quantile) {
  ErrorEstimate estimate;
  estimate.compared = static_cast<int>(worst.size());
  if (worst.empty()) return estimate;
  std::sort(worst.begin(), worst.end());
  estimate.p50 = SortedQuantile(worst, 0.5);
  estimate.p95 = SortedQuantile(worst, 0.95);
  estimate.max = worst.back();
  for (std::size_t i = 0; i < per_output.size(); ++i) {
    std::vector<double>& errors = per_output[i];
    if (errors.empty()) continue;
    std::sort(errors.begin(), errors.end());
    const double bound = errors[QuantileBoundRank(errors.size(), quantile)];
    if (std::isnan(estimate.bound) || bound > estimate.bound) {
      estimate.bound = bound;
      estimate.quantile = SortedQuantile(errors, quantile);
      estimate.worst_output = names[i];
    }
  }
  return estimate;
}

// ---- the pass loop --------------------------------------------------------------------------

// A pass's grid for the other ranks: u8 kind, then per axis u64 n and n f64 nodes.
std::string EncodeAxes(PassKind kind, const Axes& axes) {
  std::string bytes;
  le::PutU8(bytes, static_cast<std::uint8_t>(kind));
  for (const SceneAxis& axis : axes) {
    le::PutU64(bytes, axis.values.size());
    for (const double v : axis.values) le::PutF64(bytes, v);
  }
  return bytes;
}

PassKind DecodeAxes(const std::string& bytes, const Scene& scene, Axes* axes) {
  le::Reader in(bytes);
  const auto kind = static_cast<PassKind>(in.U8());
  if (!in.ok()) throw std::runtime_error("MPI protocol: empty refinement message");
  if (kind == PassKind::kStop) return kind;
  *axes = scene.axes;
  for (SceneAxis& axis : *axes) {
    const std::uint64_t n = in.U64();
    if (n > in.remaining() / 8) throw std::runtime_error("MPI protocol: truncated axes");
    axis.values.resize(n);
    for (double& v : axis.values) v = in.F64();
  }
  if (!in.AtEnd()) throw std::runtime_error("MPI protocol: malformed axes");
  return kind;
}

void Broadcast(Cluster* cluster, PassKind kind, const Axes& axes) {
  if (cluster == nullptr) return;
  const std::string bytes = EncodeAxes(kind, axes);
  for (int r = 1; r < cluster->size(); ++r) cluster->Send(r, kTagAxes, bytes);
  cluster->CompleteSends();
}

TableData LoadPassJournal(const fs::path& path, std::size_t points, std::size_t outputs) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const JournalContents contents = ParseJournal(bytes, path.string());
  TableData data(points, outputs);
  for (const JournalRecord& record : contents.records) {
    if (record.index < points) data.Store(record.index, record.result);
  }
  if (data.finished != points) {
    throw InputError(path.string() + ": the journal of a finished pass is incomplete; delete " +
                     path.parent_path().string() + " to start the refinement over");
  }
  return data;
}

// What pass P + 1 can take over: the grid of pass P and its midpoint samples.
class KnownPoints {
 public:
  KnownPoints(const Axes& old_axes, TableData old_data, const Axes& new_axes,
              const std::vector<RefineSample>& samples, std::vector<PointResult> sample_results)
      : old_data_(std::move(old_data)),
        old_stride_(Strides(old_axes)),
        new_axes_(new_axes),
        new_stride_(Strides(new_axes)) {
    for (std::size_t a = 0; a < new_axes.size(); ++a) {
      std::vector<long> map;
      for (const double x : new_axes[a].values) {
        const auto& old = old_axes[a].values;
        const auto it = std::lower_bound(old.begin(), old.end(), x);
        map.push_back(it != old.end() && *it == x ? static_cast<long>(it - old.begin()) : -1);
      }
      old_index_.push_back(std::move(map));
    }
    for (std::size_t s = 0; s < samples.size(); ++s) {
      if (IsNode(new_axes, samples[s].point)) {
        sampled_.emplace(PointKey(samples[s].point), std::move(sample_results[s]));
      }
    }
    taken_over_ = PointCount(old_axes) + sampled_.size();
  }

  /// Points of the new grid this supplies (the old grid, the samples that became nodes).
  std::size_t TakenOver() const { return taken_over_; }

  bool Lookup(std::uint64_t point, PointResult* result) const {
    std::uint64_t old_flat = 0;
    bool all_old = true;
    std::vector<double> coordinates(new_axes_.size());
    for (std::size_t a = 0; a < new_axes_.size(); ++a) {
      const std::size_t i = (point / new_stride_[a]) % new_axes_[a].values.size();
      coordinates[a] = new_axes_[a].values[i];
      const long old = old_index_[a][i];
      if (old < 0) {
        all_old = false;
      } else {
        old_flat += static_cast<std::uint64_t>(old) * old_stride_[a];
      }
    }
    if (all_old) {
      *result = ResultAt(old_data_, old_flat);
      return true;
    }
    const auto it = sampled_.find(PointKey(coordinates));
    if (it == sampled_.end()) return false;
    *result = it->second;
    return true;
  }

 private:
  TableData old_data_;
  std::vector<std::size_t> old_stride_;
  Axes new_axes_;
  std::vector<std::size_t> new_stride_;
  std::vector<std::vector<long>> old_index_;
  std::unordered_map<std::string, PointResult> sampled_;
  std::size_t taken_over_ = 0;

  static bool IsNode(const Axes& axes, const std::vector<double>& point) {
    for (std::size_t a = 0; a < axes.size(); ++a) {
      if (!std::binary_search(axes[a].values.begin(), axes[a].values.end(), point[a])) {
        return false;
      }
    }
    return true;
  }
};

std::string DescribeAxes(const Axes& axes) {
  std::string text;
  for (const SceneAxis& axis : axes) {
    text += (text.empty() ? "" : " × ") + axis.name + " " + std::to_string(axis.values.size());
  }
  return text;
}

class Refinement {
 public:
  Refinement(const Scene& scene, const GenerateOptions& options, Cluster* cluster)
      : scene_(scene),
        settings_(*scene.refine),
        options_(options),
        cluster_(cluster),
        work_(WorkDirectory(options.output)),
        identity_(SceneIdentity(scene)),
        model_(MakeErrorModel(scene, settings_)) {}

  GenerateSummary RunRoot();
  GenerateSummary RunOtherRank();

 private:
  bool Quiet() const { return options_.progress == ProgressMode::kOff; }
  void Say(const char* format, ...) const __attribute__((format(printf, 2, 3)));
  std::vector<Axes> StartOrResume();
  GenerateSummary RunPass(int pass, const Axes& axes, const KnownPoints* known, TableData* data);
  std::optional<SampleRun> RunSamples(int pass, const std::vector<RefineSample>& samples);
  bool SolveProbes();
  bool SolveCheckPoints();
  void SaySlopes(const std::vector<double>& errors) const;
  ErrorEstimate Estimate(const Axes& axes, const TableData& data);
  bool QuantileMet(const ErrorEstimate& estimate, const Axes& axes, const TableData& data) const;
  double NextGrowth(const PassRecord& record) const;
  void KeepPass(int pass, const Axes& axes, const TableData& data);
  TableProvenance Provenance() const;
  /// Every output at a point, interpolated as the table will be read.
  std::function<std::vector<double>(const std::vector<double>&)> Lookup(const Axes& axes,
                                                                        const TableData& data);
  GenerateSummary WriteFinal(const Axes& axes, const TableData& data, const ErrorEstimate& check,
                             const std::string& stop_reason);
  std::size_t Budget() const {
    if (options_.max_points == 0) return 0;
    return options_.max_points > computed_ ? options_.max_points - computed_ : 1;
  }
  GenerateSummary Interrupted(GenerateSummary summary) {
    Broadcast(cluster_, PassKind::kStop, {});
    summary.interrupted = true;
    summary.complete = false;
    summary.computed = computed_;
    summary.journal = work_;
    return summary;
  }

  const Scene& scene_;
  const RefineSettings& settings_;
  const GenerateOptions& options_;
  Cluster* cluster_;
  fs::path work_;
  std::string identity_;
  ErrorModel model_;
  std::size_t computed_ = 0;
  std::vector<PassRecord> records_;
  std::vector<PointResult> probes_;  ///< Exact solves at SlopeProbes(), with a slope target.
  /// The random states that judge every pass (kCheckPoints) and their exact solves.
  std::vector<std::vector<double>> check_points_;
  std::vector<PointResult> check_results_;
  double cpu_start_ = ProcessCpuSeconds();
};

void Refinement::Say(const char* format, ...) const {
  if (Quiet()) return;
  std::va_list args;
  va_start(args, format);
  std::fputs("wrc generate: ", stderr);
  std::vfprintf(stderr, format, args);
  std::fputc('\n', stderr);
  va_end(args);
}

std::vector<Axes> Refinement::StartOrResume() {
  if (fs::exists(work_ / "passes")) {
    if (!options_.resume) {
      throw InputError(work_.string() +
                       " exists: an earlier refinement of this table was interrupted. Pass "
                       "--resume to continue it (finished points are reused), or delete the "
                       "directory to start over");
    }
    return ReadPasses(work_, identity_, scene_, &records_);
  }
  fs::create_directories(work_);
  const std::vector<Axes> passes = {scene_.axes};
  WritePasses(work_, identity_, passes, records_);
  return passes;
}

GenerateSummary Refinement::RunPass(int pass, const Axes& axes, const KnownPoints* known,
                                    TableData* data) {
  GenerateOptions options = options_;
  options.output = PassOutput(work_, pass);
  options.resume = fs::exists(PassJournal(work_, pass));
  options.handle_signals = false;
  options.max_points = Budget();
  GridHooks hooks;
  if (known != nullptr) {
    hooks.known = [known](std::uint64_t point, PointResult* result) {
      return known->Lookup(point, result);
    };
  }
  hooks.write_table = false;
  hooks.data_out = data;
  hooks.watch_signals = options_.handle_signals;
  Broadcast(cluster_, PassKind::kGrid, axes);
  GenerateSummary summary = GenerateGrid(WithAxes(scene_, axes), options, cluster_, hooks);
  computed_ += summary.computed;
  return summary;
}

std::optional<SampleRun> Refinement::RunSamples(int pass,
                                                const std::vector<RefineSample>& samples) {
  std::vector<std::vector<double>> points;
  std::vector<double> z_guess;
  for (const RefineSample& sample : samples) {
    points.push_back(sample.point);
    // Cold: where fz(z) has several roots (the flange climbing), a warm start from a distant
    // node may find another root than `wrc verify` and a simulator's own solve would.
    z_guess.push_back(kNaN);
  }
  StopControl stop(options_.cancel, Budget(), options_.handle_signals);
  SampleRun run = SolvePoints(scene_, points, z_guess, SamplesJournal(work_, pass),
                              identity_ + "samples" + std::to_string(pass),
                              ThreadsFor(options_, cluster_), stop, options_.progress);
  computed_ += run.computed;
  if (!run.complete) return std::nullopt;
  return run;
}

void Refinement::SaySlopes(const std::vector<double>& errors) const {
  std::string text;
  for (std::size_t a = 0; a < errors.size(); ++a) {
    if (settings_.slope->step[a] == 0.0) continue;
    char item[96];
    std::snprintf(item, sizeof item, "%s%s %.3g", text.empty() ? "" : ", ",
                  scene_.axes[a].name.c_str(), errors[a]);
    text += item;
  }
  if (!text.empty()) Say("slope errors at the slope state (× target): %s", text.c_str());
}

// The slope target's exact solves: the same every pass, so solved once (journaled).
bool Refinement::SolveProbes() {
  if (!settings_.slope) return true;
  const std::vector<std::vector<double>> points = SlopeProbes(*settings_.slope);
  const std::vector<double> z_guess(points.size(), kNaN);
  StopControl stop(options_.cancel, 0, options_.handle_signals);
  SampleRun run = SolvePoints(scene_, points, z_guess, work_ / "slope.journal", identity_ + "slope",
                              ThreadsFor(options_, cluster_), stop, ProgressMode::kOff);
  computed_ += run.computed;
  if (!run.complete) return false;
  probes_ = std::move(run.results);
  return true;
}

// The stop rule's random states: the same every pass, so solved once (journaled).
bool Refinement::SolveCheckPoints() {
  SplitMix rng(Mix(settings_.seed, 0xC0FFEEull));
  check_points_.assign(kCheckPoints, {});
  for (auto& point : check_points_) {
    for (const SceneAxis& axis : scene_.axes) {
      point.push_back(axis.values.front() +
                      rng.Unit() * (axis.values.back() - axis.values.front()));
    }
  }
  const std::vector<double> z_guess(check_points_.size(), kNaN);
  StopControl stop(options_.cancel, 0, options_.handle_signals);
  SampleRun run =
      SolvePoints(scene_, check_points_, z_guess, work_ / "check.journal", identity_ + "check",
                  ThreadsFor(options_, cluster_), stop, ProgressMode::kOff);
  computed_ += run.computed;
  if (!run.complete) return false;
  check_results_ = std::move(run.results);
  return true;
}

// The error of the grid, read as the table will be, at the check states.
ErrorEstimate Refinement::Estimate(const Axes& axes, const TableData& data) {
  const std::function<std::vector<double>(const std::vector<double>&)> lookup = Lookup(axes, data);
  std::vector<double> worst;
  std::vector<std::vector<double>> per_output(model_.outputs.size());
  for (std::size_t i = 0; i < check_points_.size(); ++i) {
    const PointResult& exact = check_results_[i];
    if (!Usable(exact.status) || exact.values.empty()) continue;
    const std::vector<double> estimate = lookup(check_points_[i]);
    const double load = LocalLoad(model_, check_points_[i], {&exact.values, &estimate});
    const std::vector<double> errors = NormalisedErrors(model_, load, exact.values, estimate);
    double largest = kNaN;
    for (std::size_t k = 0; k < errors.size(); ++k) {
      if (std::isnan(errors[k])) continue;
      per_output[k].push_back(errors[k]);
      largest = std::isnan(largest) ? errors[k] : std::max(largest, errors[k]);
    }
    if (!std::isnan(largest)) worst.push_back(largest);
  }
  return Summarise(std::move(worst), std::move(per_output), settings_.outputs, settings_.quantile);
}

// The stop rule: the asked quantile of the check states' errors within the target with the
// rule's confidence and, with a slope target, every slope within its target. Quantile 1 leaves
// the decision to the interval midpoints alone.
bool Refinement::QuantileMet(const ErrorEstimate& estimate, const Axes& axes,
                             const TableData& data) const {
  if (settings_.quantile >= 1.0 || !(estimate.bound <= 1.0)) return false;
  if (!settings_.slope) return true;
  const std::vector<double> slopes = SlopeErrors(scene_, axes, data, probes_);
  return std::none_of(slopes.begin(), slopes.end(), [](double e) { return e > 1.0; });
}

// The growth of the next pass (kGrowthMargin): the quantile bound taken to fall as a power of the
// points, with the order measured between the previous pass and this one.
double Refinement::NextGrowth(const PassRecord& record) const {
  if (settings_.quantile >= 1.0 || records_.empty()) return kMaxGrowthPerPass;
  const PassRecord& previous = records_.back();
  const double fall = previous.quantile_bound / record.quantile_bound;
  const double growth = static_cast<double>(record.points) / static_cast<double>(previous.points);
  if (!(fall > 1.0) || !(growth > 1.0)) return kMaxGrowthPerPass;
  const double order = std::log(fall) / std::log(growth);
  const double needed = std::pow(record.quantile_bound, 1.0 / order) * kGrowthMargin;
  return std::clamp(needed, kMinGrowthPerPass, kMaxGrowthPerPass);
}

// `--keep-passes`: the grid of a pass as a table beside the output, so that one run gives the
// accuracy and size of every coarser table it passed through.
void Refinement::KeepPass(int pass, const Axes& axes, const TableData& data) {
  const fs::path path = options_.output.string() + ".pass" + std::to_string(pass) + ".h5";
  WriteTableFile(path, WithAxes(scene_, axes), data, Provenance());
}

// The provenance of a table written from a pass's grid (not the final one, which GenerateGrid
// writes).
TableProvenance Refinement::Provenance() const {
  TableProvenance provenance;
  provenance.rail_sha256 = Sha256FileHex(scene_.base.rail.path);
  provenance.wheel_sha256 = Sha256FileHex(scene_.base.wheel.path);
  provenance.created = IsoTimestampUtc();
  return provenance;
}

std::function<std::vector<double>(const std::vector<double>&)> Refinement::Lookup(
    const Axes& axes, const TableData& data) {
  if (settings_.interpolation == Interpolation::kLinear) {
    return [&axes, &data](const std::vector<double>& point) {
      std::vector<double> values(data.values.size());
      for (std::size_t k = 0; k < values.size(); ++k) {
        values[k] = InterpolateLinear(axes, data, k, point);
      }
      return values;
    };
  }
  // Cubic lookups anywhere in the grid are the runtime's: the grid written as a table in the
  // work directory and read back, so the estimate is what a simulator will get.
  const fs::path path = work_ / "check.h5";
  std::error_code ignored;
  fs::remove(path, ignored);
  WriteTableFile(path, WithAxes(scene_, axes), data, Provenance());
  auto table = std::make_shared<wrc::Table>(path.string());
  fs::remove(path, ignored);
  table->set_interpolation(wrc::Interpolation::kCubic);
  std::vector<std::size_t> order;  // the table's output index of each scene output
  for (const std::string& name : scene_.outputs) {
    order.push_back(static_cast<std::size_t>(table->output_index(name)));
  }
  return [table, order](const std::vector<double>& point) {
    const std::vector<double> out = table->eval(point);
    std::vector<double> values(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) values[k] = out[order[k]];
    return values;
  };
}

nlohmann::json JsonNumberOrNull(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json();
}

std::string TargetDescription(const RefineSettings& settings) {
  nlohmann::json target = {
      {"load_fraction", settings.load_fraction},
      {"outputs", settings.outputs},
      {"max_points", settings.max_points},
      {"max_passes", settings.max_passes},
      {"quantile", settings.quantile},
      {"samples", settings.samples},
      {"seed", settings.seed},
      {"interpolation", settings.interpolation == Interpolation::kCubic ? "cubic" : "linear"}};
  for (const auto& [name, value] : settings.absolute) target["absolute"][name] = value;
  for (const auto& [name, value] : settings.min_step) target["min_step"][name] = value;
  if (settings.slope) {
    target["slope"] = {{"fraction", settings.slope->fraction},
                       {"at", settings.slope->at},
                       {"step", settings.slope->step}};
  }
  return target.dump();
}

GenerateSummary Refinement::WriteFinal(const Axes& axes, const TableData& data,
                                       const ErrorEstimate& check, const std::string& stop_reason) {
  nlohmann::json passes = nlohmann::json::array(), cpu_seconds = nlohmann::json::array();
  for (const PassRecord& r : records_) {
    passes.push_back({{"points", r.points},
                      {"new_points", r.new_points},
                      {"samples", r.samples},
                      {"intervals_above_target", r.above_target},
                      {"worst_midpoint_error", r.worst},
                      {"quantile_error", JsonNumberOrNull(r.quantile_error)},
                      {"quantile_bound", JsonNumberOrNull(r.quantile_bound)}});
    cpu_seconds.push_back(JsonNumberOrNull(r.cpu_seconds));
  }
  nlohmann::json estimate = {{"points", check.compared},
                             {"p50", check.p50},
                             {"p95", check.p95},
                             {"max", check.max},
                             {"quantile", settings_.quantile},
                             {"quantile_error", JsonNumberOrNull(check.quantile)},
                             {"quantile_bound", JsonNumberOrNull(check.bound)},
                             {"quantile_output", check.worst_output},
                             {"unit", "target"}};
  if (settings_.slope) {
    // The slope errors at the slope state, per axis (null: not a target, or unsolved).
    const std::vector<double> errors = SlopeErrors(scene_, axes, data, probes_);
    for (std::size_t a = 0; a < axes.size(); ++a) {
      if (settings_.slope->step[a] == 0.0) continue;
      estimate["slope"][axes[a].name] =
          std::isfinite(errors[a]) ? nlohmann::json(errors[a]) : nlohmann::json();
    }
  }
  GridHooks hooks;
  const KnownPoints everything(axes, data, axes, {}, {});
  hooks.known = [&everything](std::uint64_t point, PointResult* result) {
    return everything.Lookup(point, result);
  };
  hooks.attributes = {{schema::kRefineTarget, TargetDescription(settings_)},
                      {schema::kRefinePasses, passes.dump()},
                      {schema::kRefineStop, stop_reason},
                      {schema::kRefineEstimatedError, estimate.dump()},
                      {schema::kRefineCpuSeconds, cpu_seconds.dump()}};
  hooks.watch_signals = options_.handle_signals;
  GenerateOptions options = options_;
  options.handle_signals = false;
  options.resume = fs::exists(options.output.string() + ".journal");
  Broadcast(cluster_, PassKind::kFinal, axes);
  GenerateSummary summary = GenerateGrid(WithAxes(scene_, axes), options, cluster_, hooks);
  summary.computed = computed_;
  summary.reused = 0;
  for (const PassRecord& r : records_) summary.passes.push_back({r.points, r.cpu_seconds});
  if (summary.complete) {
    std::error_code ignored;
    fs::remove_all(work_, ignored);
  }
  return summary;
}

GenerateSummary Refinement::RunRoot() {
  std::vector<Axes> passes;
  try {
    passes = StartOrResume();
  } catch (...) {
    Broadcast(cluster_, PassKind::kStop, {});
    throw;
  }
  int pass = static_cast<int>(passes.size()) - 1;
  if (!SolveProbes() || !SolveCheckPoints()) return Interrupted({});
  std::optional<KnownPoints> known;
  // The previous pass's journal is removed once this pass's decision is written; a resume
  // that finds the decision but also the old journal (a stop in between) just removes it.
  if (pass > 1) {
    std::error_code ignored;
    fs::remove(PassJournal(work_, pass - 2), ignored);
    fs::remove(SamplesJournal(work_, pass - 2), ignored);
  }
  if (pass > 0) {
    // The previous pass's grid and samples, for the points this pass takes over.
    const Axes& previous = passes[static_cast<std::size_t>(pass - 1)];
    TableData old =
        LoadPassJournal(PassJournal(work_, pass - 1), PointCount(previous), scene_.outputs.size());
    const std::vector<RefineSample> samples = DrawRefineSamples(previous, settings_, pass - 1);
    std::optional<SampleRun> run = RunSamples(pass - 1, samples);
    if (!run) return Interrupted({});
    known.emplace(previous, std::move(old), passes.back(), samples, std::move(run->results));
  }
  for (;;) {
    const Axes axes = passes.back();
    const std::size_t taken_over = known ? known->TakenOver() : 0;
    TableData data;
    GenerateSummary grid = RunPass(pass, axes, known ? &*known : nullptr, &data);
    if (!grid.complete) return Interrupted(grid);
    known.reset();
    PassRecord record;
    record.points = PointCount(axes);
    record.new_points = PointCount(axes) - taken_over;
    std::string stop_reason;
    Axes next = axes;
    std::vector<RefineSample> samples;
    std::optional<SampleRun> sample_run;
    const ErrorEstimate estimate = Estimate(axes, data);
    record.quantile_error = estimate.quantile;
    record.quantile_bound = estimate.bound;
    if (options_.keep_passes) KeepPass(pass, axes, data);
    if (pass >= settings_.max_passes) {
      stop_reason = "pass limit (" + std::to_string(settings_.max_passes) + " passes)";
    } else if (QuantileMet(estimate, axes, data)) {
      char reason[200];
      std::snprintf(reason, sizeof reason,
                    "target met: %g %% of %d random states within the target in every refined "
                    "output (upper bound of the quantile %.3g × target, %s)",
                    100 * settings_.quantile, estimate.compared, estimate.bound,
                    estimate.worst_output.c_str());
      stop_reason = reason;
    } else {
      samples = DrawRefineSamples(axes, settings_, pass);
      sample_run = RunSamples(pass, samples);
      if (!sample_run) return Interrupted(grid);
      const RefineDecision decision = DecideRefinement(
          scene_, axes, data, samples, sample_run->results, probes_, NextGrowth(record));
      SaySlopes(decision.slope_errors);
      record.worst = decision.worst;
      record.above_target = decision.above_target;
      next = decision.next;
      if (record.above_target == 0) {
        stop_reason = "target met: every sampled interval midpoint within the target";
      } else if (PointCount(next) == PointCount(axes)) {
        stop_reason = decision.refused > 0
                          ? "point budget (" + std::to_string(settings_.max_points) + " points)"
                          : "smallest steps reached where the error is above "
                            "target";
      }
    }
    record.samples = samples.size();
    record.cpu_seconds = ProcessCpuSeconds() - cpu_start_;
    records_.push_back(record);
    char midpoints[96] = "midpoints not sampled";
    if (!samples.empty()) {
      std::snprintf(midpoints, sizeof midpoints, "%zu intervals above target (worst %.3g × target)",
                    record.above_target, record.worst);
    }
    Say("refinement pass %d: %s = %zu points, %s, random states: %g %% quantile %.3g × target (%s; "
        "bound %.3g)",
        pass, DescribeAxes(axes).c_str(), record.points, midpoints, 100 * settings_.quantile,
        estimate.quantile, estimate.worst_output.c_str(), estimate.bound);
    if (!stop_reason.empty()) {
      Say("refinement stops: %s", stop_reason.c_str());
      Say("estimated error over %d random points: p95 %.3g, max %.3g × target", estimate.compared,
          estimate.p95, estimate.max);
      return WriteFinal(axes, data, estimate, stop_reason);
    }
    passes.push_back(next);
    WritePasses(work_, identity_, passes, records_);
    // Only now is the previous pass redundant: until the decision is on disk, a resume
    // rebuilds this pass's record from it.
    if (pass > 0) {
      std::error_code ignored;
      fs::remove(PassJournal(work_, pass - 1), ignored);
      fs::remove(SamplesJournal(work_, pass - 1), ignored);
    }
    known.emplace(axes, std::move(data), next, samples, std::move(sample_run->results));
    ++pass;
  }
}

GenerateSummary Refinement::RunOtherRank() {
  GenerateSummary summary;
  for (;;) {
    int source = 0, tag = 0;
    std::string bytes;
    while (!cluster_->Receive(&source, &tag, &bytes)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    if (tag != kTagAxes) {
      throw std::runtime_error("MPI protocol: unexpected message tag " + std::to_string(tag) +
                               " between refinement passes");
    }
    Axes axes;
    const PassKind kind = DecodeAxes(bytes, scene_, &axes);
    if (kind == PassKind::kStop) {
      summary.is_root = false;
      summary.interrupted = true;
      return summary;
    }
    GenerateOptions options = options_;
    options.handle_signals = false;
    options.resume = true;
    GridHooks hooks;
    hooks.watch_signals = options_.handle_signals;
    summary = GenerateGrid(WithAxes(scene_, axes), options, cluster_, hooks);
    if (kind == PassKind::kFinal || summary.interrupted) return summary;
  }
}

}  // namespace

double InterpolateLinear(const std::vector<SceneAxis>& axes, const TableData& data, std::size_t k,
                         const std::vector<double>& point) {
  const std::vector<std::size_t> stride = Strides(axes);
  std::vector<std::size_t> lower(axes.size());
  std::vector<double> t(axes.size(), 0.0);
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const std::vector<double>& v = axes[a].values;
    if (v.size() == 1) continue;
    const double x = std::clamp(point[a], v.front(), v.back());
    std::size_t i = static_cast<std::size_t>(std::upper_bound(v.begin(), v.end(), x) - v.begin());
    i = std::min(std::max<std::size_t>(i, 1), v.size() - 1) - 1;
    lower[a] = i;
    t[a] = (x - v[i]) / (v[i + 1] - v[i]);
  }
  double sum = 0.0;
  for (std::size_t corner = 0; corner < (std::size_t{1} << axes.size()); ++corner) {
    double weight = 1.0;
    std::uint64_t flat = 0;
    for (std::size_t a = 0; a < axes.size(); ++a) {
      const bool up = (corner >> a) & 1;
      if (axes[a].values.size() == 1 && up) {
        weight = 0.0;
        break;
      }
      weight *= up ? t[a] : 1.0 - t[a];
      flat += (lower[a] + (up ? 1 : 0)) * stride[a];
    }
    if (weight == 0.0) continue;
    sum += weight * data.values[k][flat];
  }
  return sum;
}

std::vector<std::vector<double>> SlopeProbes(const RefineSettings::Slope& slope) {
  std::vector<std::vector<double>> points;
  for (std::size_t a = 0; a < slope.at.size(); ++a) {
    for (int k = 1; k <= slope.SamplesPerSide(a); ++k) {
      for (const double sign : {-1.0, 1.0}) {
        points.push_back(slope.at);
        points.back()[a] += sign * k * slope.step[a];
      }
    }
  }
  return points;
}

namespace {

// One targeted axis' slope check: its error in units of the target and, on each side of the
// state, the sample where the table is furthest from the solver (in units of the output's
// pointwise tolerance): the node that mends the most.
struct SlopeCheck {
  double error = 0.0;
  double worst[2] = {kNaN, kNaN};  ///< Below, above the state; NaN: none.
};

// The least-squares slope through samples symmetric about the state: Σ x (f(+x) − f(−x)) over
// 2 Σ x², the state itself carrying no weight.
double SymmetricSlope(const std::vector<double>& offsets, const std::vector<double>& below,
                      const std::vector<double>& above) {
  double num = 0.0, den = 0.0;
  for (std::size_t k = 0; k < offsets.size(); ++k) {
    num += offsets[k] * (above[k] - below[k]);
    den += 2.0 * offsets[k] * offsets[k];
  }
  return num / den;
}

// The flat index of the node at `point` (a node on every axis, as the slope state is).
std::uint64_t NodeAt(const Axes& axes, const std::vector<std::size_t>& stride,
                     const std::vector<double>& point) {
  std::uint64_t flat = 0;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const std::vector<double>& v = axes[a].values;
    const auto it = std::lower_bound(v.begin(), v.end(), point[a]);
    if (it == v.end() || *it != point[a]) {
      throw std::logic_error("NodeAt: the point is not a node of axis " + axes[a].name);
    }
    flat += static_cast<std::uint64_t>(it - v.begin()) * stride[a];
  }
  return flat;
}

// The runtime's cubic lookup of output k at the node `node` moved to x along axis a.
double CubicAt(const Axes& axes, const std::vector<std::size_t>& stride, const TableData& data,
               std::size_t k, std::uint64_t node, std::size_t a, double x) {
  const std::vector<double>& v = axes[a].values;
  x = std::clamp(x, v.front(), v.back());
  std::size_t j = static_cast<std::size_t>(std::upper_bound(v.begin(), v.end(), x) - v.begin());
  j = std::min(std::max<std::size_t>(j, 1), v.size() - 1) - 1;
  return CubicAlongAxis(axes, stride, data.values[k], node, a, j, (x - v[j]) / (v[j + 1] - v[j]));
}

std::vector<SlopeCheck> CheckSlopes(const Scene& scene, const std::vector<SceneAxis>& axes,
                                    const TableData& data, const std::vector<PointResult>& probes) {
  const RefineSettings::Slope& slope = *scene.refine->slope;
  const ErrorModel model = MakeErrorModel(scene, *scene.refine);
  const bool cubic = scene.refine->interpolation == Interpolation::kCubic;
  const std::vector<std::size_t> stride = Strides(axes);
  const std::uint64_t state_node = NodeAt(axes, stride, slope.at);
  std::vector<SlopeCheck> checks(axes.size());
  std::size_t probe = 0;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const int n = slope.SamplesPerSide(a);
    if (n == 0) continue;
    std::vector<const PointResult*> side[2];     // below, above; SlopeProbes order
    std::vector<std::vector<double>> points[2];  // the same samples' coordinates
    std::vector<double> offsets;
    bool usable = true;
    for (int k = 1; k <= n; ++k) {
      offsets.push_back(k * slope.step[a]);
      for (int s = 0; s < 2; ++s) {
        side[s].push_back(&probes[probe++]);
        usable = usable && Usable(side[s].back()->status);
        points[s].push_back(slope.at);
        points[s].back()[a] += (s == 0 ? -1.0 : 1.0) * offsets.back();
      }
    }
    if (!usable) {
      checks[a].error = kNaN;
      continue;
    }
    const double load = LocalLoad(model, slope.at, {&side[0][0]->values, &side[1][0]->values});
    const double range = axes[a].values.back() - axes[a].values.front();
    double worst_residual[2] = {0.0, 0.0};
    for (std::size_t i = 0; i < model.outputs.size(); ++i) {
      const std::size_t k = model.outputs[i];
      std::vector<double> exact[2], table[2];
      for (int s = 0; s < 2; ++s) {
        for (int j = 0; j < n; ++j) {
          exact[s].push_back(side[s][j]->values[k]);
          table[s].push_back(cubic ? CubicAt(axes, stride, data, k, state_node, a, points[s][j][a])
                                   : InterpolateLinear(axes, data, k, points[s][j]));
        }
      }
      const double exact_slope = SymmetricSlope(offsets, exact[0], exact[1]);
      const double table_slope = SymmetricSlope(offsets, table[0], table[1]);
      // Relative to the solver's slope; a slope that moves the output by less than its
      // pointwise target across the whole range is as good as flat.
      const double value_tolerance =
          std::isnan(model.absolute[i]) ? model.load_fraction * load : model.absolute[i];
      const double scale = std::max(std::fabs(exact_slope), value_tolerance / range);
      if (!std::isfinite(exact_slope) || !std::isfinite(table_slope) || !(scale > 0.0)) continue;
      checks[a].error = std::max(checks[a].error,
                                 std::fabs(table_slope - exact_slope) / (slope.fraction * scale));
      for (int s = 0; s < 2; ++s) {
        for (int j = 0; j < n; ++j) {
          const double residual = std::fabs(table[s][j] - exact[s][j]) / value_tolerance;
          if (residual > worst_residual[s]) {
            worst_residual[s] = residual;
            checks[a].worst[s] = points[s][j][a];
          }
        }
      }
    }
  }
  return checks;
}

// The nodes the slope target adds: on every axis whose slope misses, the worst sample on each
// side of the state. With one sample a side that is the state ± step, after which the table's
// central difference reads solved values only (the state is a node of every axis), the
// solver's own; with a window, each pass pins the table to the solver where it strays most,
// until the fitted slopes agree. (A slope that misses with its samples all nodes differs from
// the solver's by the solver's own noise.)
std::vector<std::vector<double>> SlopeNodes(const std::vector<SlopeCheck>& checks,
                                            const Axes& axes) {
  std::vector<std::vector<double>> nodes(axes.size());
  for (std::size_t a = 0; a < axes.size(); ++a) {
    if (!(checks[a].error > 1.0)) continue;
    for (const double x : checks[a].worst) {
      const auto& v = axes[a].values;
      if (!std::isnan(x) && std::find(v.begin(), v.end(), x) == v.end()) nodes[a].push_back(x);
    }
  }
  return nodes;
}

}  // namespace

std::vector<double> SlopeErrors(const Scene& scene, const std::vector<SceneAxis>& axes,
                                const TableData& data, const std::vector<PointResult>& probes) {
  std::vector<double> errors;
  for (const SlopeCheck& c : CheckSlopes(scene, axes, data, probes)) errors.push_back(c.error);
  return errors;
}

RefineDecision DecideRefinement(const Scene& scene, const std::vector<SceneAxis>& axes,
                                const TableData& data, const std::vector<RefineSample>& samples,
                                const std::vector<PointResult>& results,
                                const std::vector<PointResult>& probes, double max_growth) {
  const RefineSettings& settings = *scene.refine;
  if (!(max_growth > 1.0)) max_growth = kMaxGrowthPerPass;
  const bool for_quantile = settings.quantile < 1.0;
  const auto scores = ScoreIntervals(axes, data, samples, results, MakeErrorModel(scene, settings),
                                     settings.interpolation);
  RefineDecision decision;
  for (const auto& axis_scores : scores) {
    for (const IntervalScore& s : axis_scores) {
      decision.worst = std::max(decision.worst, s.max_error);
      decision.above_target += s.max_error > 1.0 ? 1 : 0;
    }
  }
  if (!settings.slope) {
    decision.next = SplitIntervals(axes, scores, settings.max_points, max_growth, for_quantile,
                                   &decision.refused);
    return decision;
  }
  const std::vector<SlopeCheck> checks = CheckSlopes(scene, axes, data, probes);
  for (const SlopeCheck& c : checks) {
    decision.slope_errors.push_back(c.error);
    decision.worst = std::max(decision.worst, c.error);
    decision.above_target += c.error > 1.0 ? 1 : 0;
  }
  // The slope's nodes first: the splits get the budget they leave.
  const std::vector<std::vector<double>> nodes = SlopeNodes(checks, axes);
  const auto split_budget =
      static_cast<std::size_t>(static_cast<double>(settings.max_points) / SlopeGrowth(nodes, axes));
  decision.next =
      SplitIntervals(axes, scores, split_budget, max_growth, for_quantile, &decision.refused);
  AddSlopeNodes(nodes, settings.max_points, &decision.next, &decision.refused);
  return decision;
}

GenerateSummary RefineTable(const Scene& scene, const GenerateOptions& options, Cluster* cluster) {
  std::optional<InterruptHandlers> handlers;
  if (options.handle_signals) {
    ClearInterrupt();
    handlers.emplace();
  }
  const auto start = std::chrono::steady_clock::now();
  Refinement refinement(scene, options, cluster);
  GenerateSummary summary = (cluster != nullptr && cluster->rank() != 0) ? refinement.RunOtherRank()
                                                                         : refinement.RunRoot();
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace wrc::gen
