// Lookup latency on a real table, mean and 99.9th percentile, for one or more builds of the
// runtime in the same process: each shared runtime given is loaded with dlopen (RTLD_LOCAL, so
// that their wrc_* functions do not clash) and the cases run on each in turn, round after round,
// so that a comparison of two builds sees the same machine state.
//
//   bench_lookup_latency TABLE.h5 [RUNTIME.so[:float32] ...]    (default: this build's runtime)
//
// ":float32" reads the node data as floats (wrc_table_set_storage, where the runtime has it).
//
// Cases, on the table's own axes (one wheel) and on a wheelset reading it for both wheels:
//  - random: points uniform over the axis box (every lookup a new cell, mostly from DRAM);
//  - trajectory: a wheelset hunting at 1.5 Hz, sampled at 4 kHz (an integrator's stages at
//    1 kHz), every axis swept by a slow sine: consecutive lookups in the same or the next cell.
// "mean" is the time per lookup of an untimed loop (throughput, as a simulator calling in a loop
// sees it); "p99.9" the 99.9th percentile of lookups timed one by one with the time-stamp
// counter (serialised: latency), less the counter's own overhead.

#include <dlfcn.h>
#include <x86intrin.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "wrc/runtime.h"

namespace {

constexpr int kPoints = 1 << 16;  // per set, cycled through
constexpr int kRounds = 5;
constexpr double kTwoPi = 6.283185307179586;

struct Runtime {
  std::string path;
  void* handle = nullptr;
  decltype(&wrc_table_open) open;
  decltype(&wrc_table_close) close;
  decltype(&wrc_table_eval) eval;
  decltype(&wrc_table_set_interpolation) set_interpolation;
  decltype(&wrc_table_num_axes) num_axes;
  decltype(&wrc_table_num_outputs) num_outputs;
  decltype(&wrc_table_axis_size) axis_size;
  decltype(&wrc_table_axis_values) axis_values;
  decltype(&wrc_last_error) last_error;
  decltype(&wrc_wheelset_create) wheelset_create;
  decltype(&wrc_wheelset_destroy) wheelset_destroy;
  decltype(&wrc_wheelset_eval) wheelset_eval;
  decltype(&wrc_wheelset_state_init) state_init;
  bool float32 = false;
  wrc_table* linear = nullptr;
  wrc_table* cubic = nullptr;
  wrc_wheelset* wheelset_linear = nullptr;
  wrc_wheelset* wheelset_cubic = nullptr;
};

template <typename F>
void Bind(void* handle, const char* name, F* f) {
  *f = reinterpret_cast<F>(dlsym(handle, name));
  if (*f == nullptr) {
    std::fprintf(stderr, "bench_lookup_latency: %s\n", dlerror());
    std::exit(2);
  }
}

void Fail(const Runtime& r, const char* what) {
  std::fprintf(stderr, "bench_lookup_latency: %s: %s: %s\n", r.path.c_str(), what, r.last_error());
  std::exit(2);
}

Runtime Load(const std::string& argument, const char* table) {
  Runtime r;
  r.path = argument;
  std::string path = argument;
  if (const auto colon = path.rfind(":float32"); colon != std::string::npos) {
    path.erase(colon);
    r.float32 = true;
  }
  r.handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (r.handle == nullptr) {
    std::fprintf(stderr, "bench_lookup_latency: %s\n", dlerror());
    std::exit(2);
  }
  Bind(r.handle, "wrc_table_open", &r.open);
  Bind(r.handle, "wrc_table_close", &r.close);
  Bind(r.handle, "wrc_table_eval", &r.eval);
  Bind(r.handle, "wrc_table_set_interpolation", &r.set_interpolation);
  Bind(r.handle, "wrc_table_num_axes", &r.num_axes);
  Bind(r.handle, "wrc_table_num_outputs", &r.num_outputs);
  Bind(r.handle, "wrc_table_axis_size", &r.axis_size);
  Bind(r.handle, "wrc_table_axis_values", &r.axis_values);
  Bind(r.handle, "wrc_last_error", &r.last_error);
  Bind(r.handle, "wrc_wheelset_create", &r.wheelset_create);
  Bind(r.handle, "wrc_wheelset_destroy", &r.wheelset_destroy);
  Bind(r.handle, "wrc_wheelset_eval", &r.wheelset_eval);
  Bind(r.handle, "wrc_wheelset_state_init", &r.state_init);
  if (r.open(table, &r.linear) != 0 || r.open(table, &r.cubic) != 0 ||
      r.set_interpolation(r.cubic, WRC_INTERP_CUBIC) != 0) {
    Fail(r, "open");
  }
  if (r.float32) {
    decltype(&wrc_table_set_storage) set_storage = nullptr;
    Bind(r.handle, "wrc_table_set_storage", &set_storage);
    if (set_storage(r.linear, WRC_STORAGE_FLOAT32) != 0 ||
        set_storage(r.cubic, WRC_STORAGE_FLOAT32) != 0) {
      Fail(r, "float32");
    }
  }
  if (r.wheelset_create(nullptr, r.linear, &r.wheelset_linear) != 0 ||
      r.wheelset_create(nullptr, r.cubic, &r.wheelset_cubic) != 0) {
    Fail(r, "wheelset");
  }
  return r;
}

// ---- the query points -------------------------------------------------------------------------

struct Points {
  int n_axes = 0;
  std::vector<double> random, trajectory;
  std::vector<wrc_wheelset_state> wheelset_random, wheelset_trajectory;
};

Points MakePoints(const Runtime& r) {
  Points p;
  p.n_axes = r.num_axes(r.linear);
  std::vector<double> first, last;
  for (int a = 0; a < p.n_axes; ++a) {
    first.push_back(r.axis_values(r.linear, a)[0]);
    last.push_back(r.axis_values(r.linear, a)[r.axis_size(r.linear, a) - 1]);
  }
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < kPoints; ++i) {
    for (int a = 0; a < p.n_axes; ++a) {
      p.random.push_back(first[a] + unit(random) * (last[a] - first[a]));
    }
  }
  for (int i = 0; i < kPoints; ++i) {
    const double t = i / 4000.0;  // s, 4 kHz
    for (int a = 0; a < p.n_axes; ++a) {
      const double mid = 0.5 * (first[a] + last[a]), half = 0.5 * (last[a] - first[a]);
      p.trajectory.push_back(mid + 0.6 * half * std::sin(kTwoPi * (1.5 + 0.37 * a) * t + a));
    }
  }
  // Wheelsets: lateral ±6 mm, loads 9.5–15.5 kN, roll ±1 mrad, yaw ±4 mrad, spin ±0.3 %, at 30 m/s.
  auto state = [&](double y, double roll, double yaw, double spin, double load_left,
                   double load_right) {
    wrc_wheelset_state s;
    r.state_init(&s);
    s.y = y, s.roll = roll, s.yaw = yaw, s.velocity = 30000.0;
    s.omega = -(30000.0 / 460.0) * (1.0 + spin);
    s.fz[WRC_LEFT] = load_left, s.fz[WRC_RIGHT] = load_right;
    return s;
  };
  std::uniform_real_distribution<double> sym(-1.0, 1.0);
  for (int i = 0; i < kPoints; ++i) {
    p.wheelset_random.push_back(state(6.0 * sym(random), 0.001 * sym(random), 0.004 * sym(random),
                                      0.003 * sym(random), 12500.0 + 3000.0 * sym(random),
                                      12500.0 + 3000.0 * sym(random)));
    const double w = kTwoPi * 1.5 * i / 4000.0;
    p.wheelset_trajectory.push_back(state(
        6.0 * std::sin(w), 0.001 * std::sin(w), 0.004 * std::cos(w), 0.003 * std::sin(2.0 * w),
        12500.0 - 3000.0 * std::sin(w), 12500.0 + 3000.0 * std::sin(w)));
  }
  return p;
}

// ---- timing ---------------------------------------------------------------------------------

double TicksPerNs() {
  const auto t0 = std::chrono::steady_clock::now();
  const unsigned long long c0 = __rdtsc();
  while (std::chrono::steady_clock::now() - t0 < std::chrono::milliseconds(200)) {
  }
  const unsigned long long c1 = __rdtsc();
  const double ns =
      std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
  return static_cast<double>(c1 - c0) / ns;
}

unsigned long long TimerOverhead() {
  unsigned aux = 0;
  unsigned long long best = ~0ull;
  for (int i = 0; i < 10000; ++i) {
    const unsigned long long a = __rdtscp(&aux);
    const unsigned long long b = __rdtscp(&aux);
    best = std::min(best, b - a);
  }
  return best;
}

struct Sample {
  std::vector<double> means;      // ns, one per round
  std::vector<double> latencies;  // ns, every timed call of every round
};

// One round of a case: an untimed loop (mean), then every call timed (latency).
template <typename Call>
void Round(Call&& call, double ticks_per_ns, unsigned long long overhead, Sample* sample) {
  for (int i = 0; i < kPoints / 4; ++i) call(i);  // warm-up
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < kPoints; ++i) call(i);
  const double ns =
      std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
  sample->means.push_back(ns / kPoints);
  unsigned aux = 0;
  for (int i = 0; i < kPoints; ++i) {
    const unsigned long long a = __rdtscp(&aux);
    call(i);
    const unsigned long long b = __rdtscp(&aux);
    sample->latencies.push_back(static_cast<double>(b - a - std::min(overhead, b - a)) /
                                ticks_per_ns);
  }
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double Percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s TABLE.h5 [RUNTIME.so ...]\n", argv[0]);
    return 2;
  }
  std::vector<Runtime> runtimes;
  for (int i = 2; i < argc; ++i) runtimes.push_back(Load(argv[i], argv[1]));
  if (runtimes.empty()) runtimes.push_back(Load(WRC_RUNTIME_SHARED, argv[1]));
  const Points points = MakePoints(runtimes[0]);
  const double ticks_per_ns = TicksPerNs();
  const unsigned long long overhead = TimerOverhead();
  const int n_axes = points.n_axes;
  std::vector<double> out(static_cast<std::size_t>(runtimes[0].num_outputs(runtimes[0].linear)));

  const char* names[] = {"linear random",
                         "linear trajectory",
                         "cubic random",
                         "cubic trajectory",
                         "wheelset linear random",
                         "wheelset linear trajectory",
                         "wheelset cubic trajectory"};
  constexpr int kCases = 7;
  std::vector<std::vector<Sample>> samples(runtimes.size(), std::vector<Sample>(kCases));
  volatile double sink = 0.0;
  for (int round = 0; round < kRounds; ++round) {
    for (std::size_t r = 0; r < runtimes.size(); ++r) {
      const Runtime& rt = runtimes[r];
      for (int c = 0; c < kCases; ++c) {
        const bool cubic = c == 2 || c == 3 || c == 6;
        const wrc_table* table = cubic ? rt.cubic : rt.linear;
        const std::vector<double>& pts = (c == 0 || c == 2) ? points.random : points.trajectory;
        const wrc_wheelset* ws = c == 6 ? rt.wheelset_cubic : rt.wheelset_linear;
        const auto& states = c == 4 ? points.wheelset_random : points.wheelset_trajectory;
        wrc_wheelset_result result;
        if (c < 4) {
          Round([&](int i) { sink = sink + rt.eval(table, &pts[i * n_axes], out.data()); },
                ticks_per_ns, overhead, &samples[r][c]);
        } else {
          Round([&](int i) { sink = sink + rt.wheelset_eval(ws, &states[i], &result); },
                ticks_per_ns, overhead, &samples[r][c]);
        }
      }
    }
  }
  std::printf("%-28s", "case (ns per lookup)");
  for (std::size_t r = 0; r < runtimes.size(); ++r) std::printf(" | %8s %8s", "mean", "p99.9");
  std::printf("\n");
  for (int c = 0; c < kCases; ++c) {
    std::printf("%-28s", names[c]);
    for (std::size_t r = 0; r < runtimes.size(); ++r) {
      std::printf(" | %8.1f %8.1f", Median(samples[r][c].means),
                  Percentile(samples[r][c].latencies, 0.999));
    }
    std::printf("\n");
  }
  for (std::size_t r = 0; r < runtimes.size(); ++r) {
    std::printf("runtime %zu: %s\n", r + 1, runtimes[r].path.c_str());
  }
  return 0;
}
