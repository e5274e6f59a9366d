// Cost of one table lookup (wrc_table_eval / wrc_table_eval_deriv) on a 4-D table of the size a
// scene produces (y × roll × yaw × spin = 41 × 5 × 5 × 9, 6 outputs), multilinear and cubic,
// with and without derivatives, for random and for coherent (trajectory-like) query order.
// Targets: <= 100 ns multilinear, <= 500 ns cubic (values only). BM_Wheelset: one evaluation
// of a whole wheelset (two lookups and the mapping around them). BM_Refined: random multilinear
// lookups on a 5-D table with the node counts and the kind of clustering the error-driven
// refinement gives the shipped Manchester scene, against BM_Uniform, the same node counts
// equally spaced (WRC_BENCH_TABLE=FILE replaces the synthetic refined table by a real one).
//
//   build-runtime/bench/bench_runtime --benchmark_min_time=0.5

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <vector>

#include "tests/runtime/table_writer.h"
#include "tests/runtime/wheelset_table.h"
#include "wrc/runtime.h"

namespace {

constexpr int kAxes = 4;
constexpr int kOutputs = 6;
constexpr int kPoints = 1 << 14;  // Query points per set, cycled through.
constexpr double kTwoPi = 6.283185307179586;

enum class Order { kRandom, kCoherent };

// One table file and two handles, made on first use and kept for the process.
struct Fixture {
  wrc::test::ScratchFile file{"bench"};
  wrc_table* linear = nullptr;
  wrc_table* cubic = nullptr;
  std::vector<double> random_points;
  std::vector<double> coherent_points;

  Fixture() {
    wrc::test::TableContent content;
    content.axes = wrc::test::WheelsetAxes(41);
    content.outputs = {"fx", "fy", "fz", "mx", "my", "mz"};
    // Smooth creep-force-like shapes with a flange-contact rise in y.
    content.function = [](int k, const std::vector<double>& x) {
      const double flange = x[0] > 6.0 ? 2000.0 * (x[0] - 6.0) : 0.0;
      return (k + 1) * (3000.0 * std::tanh(300.0 * x[3]) + 200.0 * x[0] + 1e5 * x[2]) +
             flange * (k == 1) + 1e6 * x[1];
    };
    wrc::test::WriteTable(file.path(), content);
    if (wrc_table_open(file.path().c_str(), &linear) != 0 ||
        wrc_table_open(file.path().c_str(), &cubic) != 0 ||
        wrc_table_set_interpolation(cubic, WRC_INTERP_CUBIC) != 0) {
      std::fprintf(stderr, "bench_runtime: %s\n", wrc_last_error());
      std::abort();
    }
    std::mt19937 random(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int i = 0; i < kPoints; ++i) {
      random_points.insert(random_points.end(), {10.0 * unit(random), 0.002 * unit(random),
                                                 0.01 * unit(random), 0.01 * unit(random)});
    }
    // A wheelset hunting along the track: slow lateral oscillation, small steps between calls
    // (an integrator's successive stages), so consecutive lookups hit the same or nearby cells.
    for (int i = 0; i < kPoints; ++i) {
      const double s = kTwoPi * i / 4096.0;
      coherent_points.insert(coherent_points.end(),
                             {8.0 * std::sin(s), 0.0015 * std::sin(2.0 * s + 0.3),
                              0.008 * std::cos(s), 0.006 * std::sin(3.0 * s)});
    }
  }
  ~Fixture() {
    wrc_table_close(linear);
    wrc_table_close(cubic);
  }
};

Fixture& GetFixture() {
  static Fixture fixture;
  return fixture;
}

void BM_Lookup(benchmark::State& state, int mode, Order order, bool derivatives) {
  Fixture& fixture = GetFixture();
  const wrc_table* table = mode == WRC_INTERP_CUBIC ? fixture.cubic : fixture.linear;
  const std::vector<double>& points =
      order == Order::kRandom ? fixture.random_points : fixture.coherent_points;
  double out[kOutputs];
  double d_out[kOutputs * kAxes];
  std::size_t i = 0;
  for (auto _ : state) {
    const double* point = &points[i * kAxes];
    const int flags = derivatives ? wrc_table_eval_deriv(table, point, out, d_out)
                                  : wrc_table_eval(table, point, out);
    benchmark::DoNotOptimize(flags);
    benchmark::DoNotOptimize(out);
    benchmark::DoNotOptimize(d_out);
    i = (i + 1) & (kPoints - 1);
  }
  state.SetItemsProcessed(state.iterations());
}

BENCHMARK_CAPTURE(BM_Lookup, linear / random, WRC_INTERP_LINEAR, Order::kRandom, false);
BENCHMARK_CAPTURE(BM_Lookup, linear / coherent, WRC_INTERP_LINEAR, Order::kCoherent, false);
BENCHMARK_CAPTURE(BM_Lookup, linear / random / deriv, WRC_INTERP_LINEAR, Order::kRandom, true);
BENCHMARK_CAPTURE(BM_Lookup, linear / coherent / deriv, WRC_INTERP_LINEAR, Order::kCoherent, true);
BENCHMARK_CAPTURE(BM_Lookup, cubic / random, WRC_INTERP_CUBIC, Order::kRandom, false);
BENCHMARK_CAPTURE(BM_Lookup, cubic / coherent, WRC_INTERP_CUBIC, Order::kCoherent, false);
BENCHMARK_CAPTURE(BM_Lookup, cubic / random / deriv, WRC_INTERP_CUBIC, Order::kRandom, true);
BENCHMARK_CAPTURE(BM_Lookup, cubic / coherent / deriv, WRC_INTERP_CUBIC, Order::kCoherent, true);

}  // namespace

// One wheelset evaluation: both wheels (the left one mirrored) from one 41 × 5 × 5 × 9 table
// with 8 outputs, states along the hunting trajectory above, at a speed other than the
// table's (so that velocities are rescaled).
void BM_Wheelset(benchmark::State& state, int mode) {
  static wrc::test::ScratchFile file("bench-wheelset");
  static const bool written = (wrc::test::WriteWheelsetTable(file.path()), true);
  (void)written;
  wrc_table* table = nullptr;
  wrc_wheelset* wheelset = nullptr;
  if (wrc_table_open(file.path().c_str(), &table) != 0 ||
      wrc_table_set_interpolation(table, mode) != 0 ||
      wrc_wheelset_create(nullptr, table, &wheelset) != 0) {
    std::fprintf(stderr, "bench_runtime: %s\n", wrc_last_error());
    std::abort();
  }
  const std::vector<double>& points = GetFixture().coherent_points;
  std::vector<wrc_wheelset_state> states(kPoints);
  for (int i = 0; i < kPoints; ++i) {
    wrc_wheelset_state_init(&states[i]);
    const double* p = &points[static_cast<std::size_t>(i) * kAxes];
    states[i].y = p[0];
    states[i].roll = p[1];
    states[i].yaw = p[2];
    states[i].velocity = 30000.0;
    states[i].omega = -(30000.0 / 460.0) * (1.0 + p[3]);
  }
  wrc_wheelset_result result;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(wrc_wheelset_eval(wheelset, &states[i], &result));
    benchmark::DoNotOptimize(result.force[1]);
    i = (i + 1) & (kPoints - 1);
  }
  wrc_wheelset_destroy(wheelset);
  wrc_table_close(table);
}
BENCHMARK_CAPTURE(BM_Wheelset, linear, WRC_INTERP_LINEAR);

// Nodes clustered the way refinement clusters them: fine where x is near `at` (a creep knee or
// the flange transition), coarse elsewhere; n nodes over [first, last].
std::vector<double> Clustered(double first, double last, int n, double at) {
  std::vector<double> v(static_cast<std::size_t>(n));
  const double a = std::asinh(4.0 * (first - at) / (last - first));
  const double b = std::asinh(4.0 * (last - at) / (last - first));
  for (int i = 0; i < n; ++i) {
    const double s = a + (b - a) * i / (n - 1);
    v[static_cast<std::size_t>(i)] = at + (last - first) / 4.0 * std::sinh(s);
  }
  v.front() = first;
  v.back() = last;
  return v;
}

// A 5-D table (y_wheel, fz, roll, yaw, spin) with 6 outputs; `clustered` picks the node layout.
struct FiveAxisTable {
  wrc::test::ScratchFile file;
  wrc_table* table = nullptr;
  std::vector<double> points;
  std::vector<std::vector<double>> axes;

  explicit FiveAxisTable(bool clustered) : file(clustered ? "refined" : "uniform") {
    const char* real = std::getenv("WRC_BENCH_TABLE");
    if (clustered && real != nullptr) {
      Open(real);
    } else {
      Write(clustered);
      Open(file.path().c_str());
    }
    std::mt19937 random(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int i = 0; i < kPoints; ++i) {
      for (const auto& axis : axes)
        points.push_back(axis.front() + unit(random) * (axis.back() - axis.front()));
    }
  }
  ~FiveAxisTable() { wrc_table_close(table); }

  void Write(bool clustered) {
    // The node counts of a refined Manchester table; a real table passed in WRC_BENCH_TABLE
    // sets them for the uniform twin too.
    std::vector<int> counts = {25, 8, 5, 20, 16};
    const std::vector<double> first = {-10.92, 5000.0, -0.002, -0.01, -0.01};
    const std::vector<double> last = {10.92, 20000.0, 0.002, 0.01, 0.01};
    const std::vector<double> at = {6.0, 5000.0, 0.0, 0.0, 0.0};
    if (const char* real = std::getenv("WRC_BENCH_TABLE")) {
      wrc_table* t = nullptr;
      if (wrc_table_open(real, &t) == 0) {
        for (int a = 0; a < 5 && a < wrc_table_num_axes(t); ++a)
          counts[a] = wrc_table_axis_size(t, a);
        wrc_table_close(t);
      }
    }
    const char* names[] = {"y_wheel", "fz", "roll", "yaw", "spin"};
    wrc::test::TableContent content;
    for (int a = 0; a < 5; ++a) {
      content.axes.push_back({names[a],
                              clustered ? Clustered(first[a], last[a], counts[a], at[a])
                                        : wrc::test::Linspace(first[a], last[a], counts[a]),
                              "-"});
    }
    content.outputs = {"fx", "fy", "fz", "mx", "my", "mz"};
    content.function = [](int k, const std::vector<double>& x) {
      return (k + 1) * (3000.0 * std::tanh(300.0 * x[3]) + 200.0 * x[0] + 0.1 * x[1]) + 1e6 * x[2] +
             1e4 * x[4];
    };
    wrc::test::WriteTable(file.path(), content);
  }

  void Open(const char* path) {
    if (wrc_table_open(path, &table) != 0) {
      std::fprintf(stderr, "bench_runtime: %s\n", wrc_last_error());
      std::abort();
    }
    for (int a = 0; a < wrc_table_num_axes(table); ++a) {
      const double* v = wrc_table_axis_values(table, a);
      axes.emplace_back(v, v + wrc_table_axis_size(table, a));
    }
  }
};

void BM_FiveAxis(benchmark::State& state, bool clustered) {
  static FiveAxisTable refined(true), uniform(false);
  FiveAxisTable& t = clustered ? refined : uniform;
  const std::size_t n_axes = t.axes.size();
  std::vector<double> out(static_cast<std::size_t>(wrc_table_num_outputs(t.table)));
  std::size_t i = 0;
  for (auto _ : state) {
    const int flags = wrc_table_eval(t.table, &t.points[i * n_axes], out.data());
    benchmark::DoNotOptimize(flags);
    benchmark::DoNotOptimize(out.data());
    i = (i + 1) & (kPoints - 1);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["nodes"] = static_cast<double>(wrc_table_axis_size(t.table, 0));
}
BENCHMARK_CAPTURE(BM_FiveAxis, refined / linear / random, true);
BENCHMARK_CAPTURE(BM_FiveAxis, uniform / linear / random, false);
BENCHMARK_CAPTURE(BM_Wheelset, cubic, WRC_INTERP_CUBIC);

BENCHMARK_MAIN();
