// Cost of the padded transforms per transform length: the measurement behind the size table of
// core/fft/fftw.cpp (PaddedPlan2d::FastSizes).
//
//   build/bench/bench_fft_sizes            # n  row_ns  column_ns per point, every length
//   build/bench/bench_fft_sizes pair N0 N1 # one Forward + Backward pair in MeasuredPairs()
//   build/bench/bench_fft_sizes plan N0 N1 # one PaddedPlan2d(N0, N1) made in MeasuredPlan()
//
// Without arguments it times, for every even 13-smooth length n up to 1024, a Forward +
// Backward pair of PaddedPlan2d with n as the row length (n1 = n, n0 = 64) and as the column
// length (n0 = n, n1 = 64), half-filled as in a convolution, and prints ns per point of the
// padded array, the best of several rounds. The table in fftw.cpp holds instruction counts
// instead (tools/fft_size_table.sh runs the pair and plan modes under callgrind): on a shared
// machine timings scatter by 30 % between runs, instruction counts not at all.
//
// FFTW_ESTIMATE picks the same algorithm for a length on every run, so the relative costs are a
// property of the FFTW build more than of the machine; lengths with a prime factor above 13
// (FFTW's generic or Rader codelets) cost 3-10x more per point and are not listed.

#include <algorithm>
#include <chrono>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/fft/fftw.h"

namespace {

bool Smooth13(int n) {
  for (int p : {2, 3, 5, 7, 11, 13}) {
    while (n % p == 0) n /= p;
  }
  return n == 1;
}

// Best time of a Forward + Backward pair, in ns per point of the n0 × n1 array.
double PairCost(int n0, int n1) {
  using wrc::fftw::ComplexBuffer;
  using wrc::fftw::PaddedPlan2d;
  using wrc::fftw::RealBuffer;
  const PaddedPlan2d plan(n0, n1);
  const int ny = n0 / 2, nx = n1 / 2;
  RealBuffer field(static_cast<std::size_t>(ny) * nx);
  for (std::size_t k = 0; k < field.size(); ++k) field[k] = static_cast<double>(k % 17) - 8.0;
  ComplexBuffer spectrum(plan.complex_size());
  ComplexBuffer rows(plan.row_buffer_size());
  PaddedPlan2d::Staging staging(plan);
  const double points = static_cast<double>(n0) * n1;
  const int reps = std::max(4, static_cast<int>(2e6 / points));
  double best = 1e300;
  for (int round = 0; round < 5; ++round) {
    const auto start = std::chrono::steady_clock::now();
    for (int r = 0; r < reps; ++r) {
      plan.Forward(field.data(), ny, nx, spectrum.data(), rows.data(), staging);
      plan.Backward(spectrum.data(), ny, nx, field.data(), rows.data());
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    best = std::min(best, seconds / reps / points * 1e9);
  }
  return best;
}

}  // namespace

// Four Forward + Backward pairs, for callgrind --toggle-collect=MeasuredPairs*.
__attribute__((noinline)) double MeasuredPairs(const wrc::fftw::PaddedPlan2d& plan,
                                               wrc::fftw::RealBuffer& field,
                                               wrc::fftw::ComplexBuffer& spectrum,
                                               wrc::fftw::ComplexBuffer& rows,
                                               wrc::fftw::PaddedPlan2d::Staging& staging) {
  const int ny = plan.n0() / 2, nx = plan.n1() / 2;
  for (int k = 0; k < 4; ++k) {
    plan.Forward(field.data(), ny, nx, spectrum.data(), rows.data(), staging);
    plan.Backward(spectrum.data(), ny, nx, field.data(), rows.data());
  }
  return field[0];
}

// One plan, for callgrind --toggle-collect=MeasuredPlan*.
__attribute__((noinline)) int MeasuredPlan(int n0, int n1) {
  const wrc::fftw::PaddedPlan2d plan(n0, n1);
  return plan.n0();
}

int main(int argc, char** argv) {
  if (argc == 4) {
    const std::string mode = argv[1];
    const int n0 = std::atoi(argv[2]), n1 = std::atoi(argv[3]);
    { const wrc::fftw::PaddedPlan2d warm(6, 6); }  // FFTW's one-time set-up, not counted
    if (mode == "plan") return MeasuredPlan(n0, n1) == n0 ? 0 : 1;
    const wrc::fftw::PaddedPlan2d plan(n0, n1);
    wrc::fftw::RealBuffer field(static_cast<std::size_t>(n0 / 2) * (n1 / 2));
    for (std::size_t k = 0; k < field.size(); ++k) field[k] = static_cast<double>(k % 17) - 8.0;
    wrc::fftw::ComplexBuffer spectrum(plan.complex_size()), rows(plan.row_buffer_size());
    wrc::fftw::PaddedPlan2d::Staging staging(plan);
    // First touch of the buffers, not counted.
    plan.Forward(field.data(), n0 / 2, n1 / 2, spectrum.data(), rows.data(), staging);
    plan.Backward(spectrum.data(), n0 / 2, n1 / 2, field.data(), rows.data());
    std::printf("%g\n", MeasuredPairs(plan, field, spectrum, rows, staging));
    return 0;
  }
  constexpr int kOther = 64;  // the other dimension, a fast length
  for (int n = 16; n <= 1024; n += 2) {
    if (!Smooth13(n)) continue;
    std::printf("%d %.3f %.3f\n", n, PairCost(kOther, n), PairCost(n, kOther));
  }
  return 0;
}
