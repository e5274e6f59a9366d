#include "core/fft/fftw.h"

#include <fftw3.h>

#include <algorithm>
#include <map>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/common/portable_simd.h"

namespace wrc::fftw {
namespace {
// FFTW's planner is not thread-safe (only fftw_execute* is): serialise plan creation and
// destruction across the generator's worker threads.
std::mutex& PlannerMutex() {
  static std::mutex m;
  return m;
}
}  // namespace

void FreeDeleter::operator()(void* p) const { fftw_free(p); }

template <typename T>
Buffer<T>::Buffer(std::size_t n, Uninitialized) : size_(n) {
  void* p = fftw_malloc(sizeof(T) * (n > 0 ? n : 1));
  if (p == nullptr) throw std::bad_alloc();
  data_.reset(static_cast<T*>(p));
}
template <typename T>
Buffer<T>::Buffer(std::size_t n) : Buffer(n, Uninitialized{}) {
  std::fill(data_.get(), data_.get() + n, T{});
}
template class Buffer<double>;
template class Buffer<std::complex<double>>;

PaddedPlan2d::PaddedPlan2d(int n0, int n1) : n0_(n0), n1_(n1) {
  if (n0 < 2 || n1 < 2 || n0 % 2 != 0 || n1 % 2 != 0) {
    throw std::invalid_argument("padded FFT size " + std::to_string(n0) + " x " +
                                std::to_string(n1) + ": both must be even and >= 2");
  }
  // Plans run later on other fftw_malloc'ed buffers, which have the same alignment.
  // FFTW_ESTIMATE plans without touching the arrays.
  ComplexBuffer rows(row_buffer_size(), Uninitialized{});
  ComplexBuffer spectrum(complex_size(), Uninitialized{});
  ComplexBuffer staging(complex_size(), Uninitialized{});
  auto* r = reinterpret_cast<fftw_complex*>(rows.data());
  auto* c = reinterpret_cast<fftw_complex*>(spectrum.data());
  auto* st = reinterpret_cast<fftw_complex*>(staging.data());
  const int nc = n1 / 2 + 1;
  std::lock_guard<std::mutex> lock(PlannerMutex());
  row_forward_ = fftw_plan_dft_1d(n1, r, r, FFTW_FORWARD, FFTW_ESTIMATE);
  row_backward_ = fftw_plan_dft_1d(n1, r, r, FFTW_BACKWARD, FFTW_ESTIMATE);
  // Out of place: FFTW keeps the input of an out-of-place complex transform unless told
  // otherwise (FFTW_PRESERVE_INPUT is the default there), which keeps the staging padding zero.
  column_forward_ = fftw_plan_many_dft(1, &n0, nc, st, nullptr, nc, 1, c, nullptr, nc, 1,
                                       FFTW_FORWARD, FFTW_ESTIMATE);
  column_backward_ = fftw_plan_many_dft(1, &n0, nc, c, nullptr, nc, 1, c, nullptr, nc, 1,
                                        FFTW_BACKWARD, FFTW_ESTIMATE);
  if (!row_forward_ || !row_backward_ || !column_forward_ || !column_backward_) {
    for (void* p : {row_forward_, row_backward_, column_forward_, column_backward_}) {
      if (p) fftw_destroy_plan(static_cast<fftw_plan>(p));
    }
    throw std::runtime_error("FFTW could not plan a " + std::to_string(n0) + " x " +
                             std::to_string(n1) + " transform");
  }
}

PaddedPlan2d::~PaddedPlan2d() {
  std::lock_guard<std::mutex> lock(PlannerMutex());
  for (void* p : {row_forward_, row_backward_, column_forward_, column_backward_}) {
    fftw_destroy_plan(static_cast<fftw_plan>(p));
  }
}

// The row loops around the FFTW calls built for AVX2 as well as the baseline ISA.
WRC_CLONE_FOR_AVX2
void PaddedPlan2d::Forward(const double* in, int ny, int nx, std::complex<double>* spectrum,
                           std::complex<double>* rows, Staging& staging) const {
  using Complex = std::complex<double>;
  if (staging.values.size() != complex_size() ||
      staging.zero_pairs.size() != static_cast<std::size_t>(n0_ / 2)) {
    throw std::logic_error("FFT staging buffer made for another transform size");
  }
  const int nc = n1_ / 2 + 1;
  const int pairs = (ny + 1) / 2;
  Complex* z = rows;
  for (int m = 0; m < pairs; ++m) {
    // Rows a = 2m and b = 2m + 1 as one complex row a + i·b.
    const double* a = in + static_cast<std::size_t>(2 * m) * nx;
    const double* b = 2 * m + 1 < ny ? a + nx : nullptr;
    Complex* sa = staging.values.data() + static_cast<std::size_t>(2 * m) * nc;
    Complex* sb = sa + nc;  // row 2m + 1 < n0: n0 is even and 2m < ny <= n0
    // Rows of zeros (the contact's gaps, or elements out of contact in a CG direction) have a
    // zero spectrum: a scan of the values costs far less than their transform.
    const bool zero = std::all_of(a, a + nx, [](double v) { return v == 0.0; }) &&
                      (!b || std::all_of(b, b + nx, [](double v) { return v == 0.0; }));
    if (zero) {
      if (!staging.zero_pairs[m]) {
        std::fill(sa, sa + 2 * nc, Complex(0.0, 0.0));
        staging.zero_pairs[m] = 1;
      }
      continue;
    }
    staging.zero_pairs[m] = 0;
    for (int k = 0; k < nx; ++k) z[k] = Complex(a[k], b ? b[k] : 0.0);
    std::fill(z + nx, z + n1_, Complex(0.0, 0.0));
    fftw_execute_dft(static_cast<fftw_plan>(row_forward_), reinterpret_cast<fftw_complex*>(z),
                     reinterpret_cast<fftw_complex*>(z));
    // Split by the symmetry of real rows: A_k = (Z_k + conj Z_−k)/2, B_k = (Z_k − conj Z_−k)/2i.
    for (int k = 0; k < nc; ++k) {
      const Complex zk = z[k];
      const Complex zm = std::conj(z[k == 0 ? 0 : n1_ - k]);
      sa[k] = 0.5 * (zk + zm);
      const Complex d = zk - zm;
      sb[k] = Complex(0.5 * d.imag(), -0.5 * d.real());
    }
  }
  // Rows past 2·pairs are zero unless an earlier transform of more rows left values there.
  for (int m = pairs; m < n0_ / 2; ++m) {
    if (!staging.zero_pairs[m]) {
      Complex* sa = staging.values.data() + static_cast<std::size_t>(2 * m) * nc;
      std::fill(sa, sa + 2 * nc, Complex(0.0, 0.0));
      staging.zero_pairs[m] = 1;
    }
  }
  fftw_execute_dft(static_cast<fftw_plan>(column_forward_),
                   reinterpret_cast<fftw_complex*>(staging.values.data()),
                   reinterpret_cast<fftw_complex*>(spectrum));
}

// The row loops around the FFTW calls built for AVX2 as well as the baseline ISA.
WRC_CLONE_FOR_AVX2
void PaddedPlan2d::Backward(std::complex<double>* spectrum, int ny, int nx, double* out,
                            std::complex<double>* rows) const {
  using Complex = std::complex<double>;
  const int nc = n1_ / 2 + 1;
  fftw_execute_dft(static_cast<fftw_plan>(column_backward_),
                   reinterpret_cast<fftw_complex*>(spectrum),
                   reinterpret_cast<fftw_complex*>(spectrum));
  const int pairs = (ny + 1) / 2;
  Complex* z = rows;
  for (int m = 0; m < pairs; ++m) {
    // Two half spectra of real rows A, B into the full spectrum of the complex row a + i·b.
    const Complex* sa = spectrum + static_cast<std::size_t>(2 * m) * nc;
    const Complex* sb = sa + nc;
    for (int k = 0; k < nc; ++k) {
      z[k] = Complex(sa[k].real() - sb[k].imag(), sa[k].imag() + sb[k].real());
    }
    for (int k = nc; k < n1_; ++k) {
      const Complex a = sa[n1_ - k], b = sb[n1_ - k];  // conj(a) + i·conj(b)
      z[k] = Complex(a.real() + b.imag(), b.real() - a.imag());
    }
    fftw_execute_dft(static_cast<fftw_plan>(row_backward_), reinterpret_cast<fftw_complex*>(z),
                     reinterpret_cast<fftw_complex*>(z));
    double* oa = out + static_cast<std::size_t>(2 * m) * nx;
    for (int k = 0; k < nx; ++k) oa[k] = z[k].real();
    if (2 * m + 1 < ny) {
      double* ob = oa + nx;
      for (int k = 0; k < nx; ++k) ob[k] = z[k].imag();
    }
  }
}

namespace {

// Costs of the padded transforms per length n (every even 13-smooth n up to 1024), from
// bench/bench_fft_sizes run under callgrind (tools/fft_size_table.sh), in instructions:
//   row, column: per point of the padded array for a Forward + Backward pair, with n as the
//                row length (n1) or the column length (n0);
//   row_plan, column_plan: millions, to plan a PaddedPlan2d with n as row or column length.
// Instruction counts are deterministic, unlike timings on a shared machine (which scatter by
// 30 % between runs here and follow these counts with correlation 0.75-0.8), and FFTW_ESTIMATE
// picks the same codelets and plans for a length on every run. Planning is what sets some
// lengths apart: 72 costs 16 million instructions against 3 for 80, multiples of 11² or 13²
// 40-370 million.
struct LengthCost {
  int n;
  double row, column, row_plan, column_plan;
};
constexpr LengthCost kLengthCosts[] = {
    {16, 39.3, 37.0, 0.3, 1.2},        {18, 63.0, 81.3, 8.4, 16.0},
    {20, 38.5, 38.0, 4.9, 1.2},        {22, 55.8, 77.5, 2.3, 8.2},
    {24, 42.0, 64.2, 11.2, 21.1},      {26, 52.3, 74.7, 2.3, 7.4},
    {28, 43.5, 68.3, 6.2, 13.6},       {30, 54.3, 124.6, 1.1, 7.2},
    {32, 35.6, 38.4, 4.9, 1.2},        {36, 41.3, 88.3, 4.2, 5.7},
    {40, 52.4, 85.9, 2.8, 5.3},        {42, 46.0, 72.5, 2.8, 4.4},
    {44, 40.5, 64.9, 5.3, 7.2},        {48, 36.4, 62.8, 8.9, 6.6},
    {50, 45.8, 77.6, 3.9, 4.8},        {52, 39.5, 63.4, 5.7, 7.5},
    {54, 56.2, 88.8, 4.3, 5.6},        {56, 36.4, 64.2, 4.4, 5.6},
    {60, 46.1, 74.7, 2.0, 4.3},        {64, 40.0, 40.0, 1.3, 1.3},
    {66, 43.7, 69.6, 2.4, 4.0},        {70, 43.6, 78.4, 1.2, 4.3},
    {72, 38.7, 64.8, 15.7, 6.4},       {78, 42.3, 68.2, 2.4, 4.0},
    {80, 43.1, 71.2, 2.8, 4.5},        {84, 46.4, 77.8, 7.0, 4.1},
    {88, 41.8, 67.4, 8.2, 5.6},        {90, 52.4, 89.6, 2.3, 5.5},
    {96, 37.7, 69.2, 2.0, 3.6},        {98, 41.0, 69.7, 1.2, 3.4},
    {100, 38.3, 70.5, 2.1, 3.7},       {104, 40.7, 66.1, 8.3, 5.6},
    {108, 52.4, 93.9, 8.5, 5.4},       {110, 47.6, 72.5, 1.7, 4.0},
    {112, 37.1, 63.8, 1.2, 3.4},       {120, 37.3, 67.6, 2.0, 3.6},
    {126, 39.5, 68.3, 1.2, 3.4},       {128, 38.0, 40.9, 4.1, 1.3},
    {130, 46.6, 71.3, 1.7, 4.0},       {132, 44.0, 76.7, 6.1, 4.6},
    {140, 36.8, 63.5, 1.2, 3.5},       {144, 49.2, 88.9, 2.4, 4.8},
    {150, 39.1, 69.7, 2.5, 3.9},       {154, 46.3, 86.0, 1.8, 4.1},
    {156, 41.6, 76.0, 6.1, 4.8},       {160, 37.7, 66.7, 2.1, 3.7},
    {162, 49.3, 90.7, 2.4, 4.9},       {168, 43.1, 77.2, 7.4, 5.5},
    {176, 45.4, 80.8, 1.8, 4.1},       {180, 48.6, 96.5, 2.4, 4.9},
    {182, 45.6, 83.3, 1.8, 4.2},       {192, 46.3, 91.9, 6.8, 6.2},
    {196, 40.9, 74.0, 5.6, 5.2},       {198, 45.7, 85.9, 1.8, 4.1},
    {200, 36.2, 67.6, 2.9, 3.8},       {208, 44.6, 89.1, 1.8, 4.3},
    {210, 43.9, 103.0, 1.8, 4.7},      {216, 47.8, 87.8, 9.9, 8.0},
    {220, 45.1, 80.5, 1.8, 4.1},       {224, 35.6, 80.6, 3.1, 4.9},
    {234, 45.1, 83.4, 1.8, 4.3},       {240, 36.3, 92.4, 3.9, 5.8},
    {242, 52.6, 116.1, 43.0, 86.7},    {250, 38.0, 77.8, 2.8, 4.1},
    {252, 39.6, 73.1, 6.5, 5.3},       {256, 35.0, 58.1, 2.2, 4.2},
    {260, 45.7, 87.6, 1.8, 4.3},       {264, 45.4, 94.4, 7.4, 5.9},
    {270, 52.1, 97.4, 2.9, 5.9},       {280, 36.6, 80.7, 3.1, 5.0},
    {286, 53.3, 117.9, 54.1, 96.6},    {288, 49.1, 90.3, 2.5, 4.8},
    {294, 44.7, 82.0, 1.8, 4.3},       {300, 44.3, 74.7, 2.4, 4.0},
    {308, 45.1, 82.0, 6.2, 5.9},       {312, 45.0, 93.1, 7.5, 5.9},
    {320, 36.8, 63.7, 2.1, 3.8},       {324, 51.6, 95.3, 6.4, 6.1},
    {330, 44.0, 95.1, 2.2, 4.9},       {336, 44.0, 85.5, 1.8, 4.4},
    {338, 52.6, 115.3, 43.0, 87.0},    {350, 40.1, 94.1, 2.6, 4.4},
    {352, 45.5, 85.6, 1.9, 5.5},       {360, 49.3, 102.6, 3.8, 5.8},
    {364, 44.2, 80.1, 6.2, 5.9},       {378, 44.6, 81.8, 1.9, 4.3},
    {384, 47.1, 58.9, 4.1, 7.0},       {390, 42.6, 92.0, 2.2, 5.0},
    {392, 41.1, 89.9, 8.0, 6.6},       {396, 45.1, 81.9, 6.3, 5.9},
    {400, 37.4, 67.1, 2.3, 4.2},       {416, 45.1, 83.1, 1.9, 5.5},
    {420, 44.2, 84.7, 1.9, 4.4},       {432, 51.3, 96.9, 3.0, 8.0},
    {440, 45.8, 85.4, 1.9, 5.5},       {448, 36.2, 73.3, 3.2, 5.8},
    {450, 62.3, 90.6, 11.3, 5.8},      {462, 44.0, 81.2, 2.3, 4.7},
    {468, 44.2, 80.5, 6.3, 6.0},       {480, 47.4, 75.7, 3.3, 6.6},
    {484, 54.1, 117.2, 174.5, 261.6},  {486, 52.0, 98.8, 3.1, 5.5},
    {490, 42.4, 88.7, 1.7, 4.3},       {500, 43.1, 82.0, 2.6, 4.4},
    {504, 43.6, 79.4, 7.8, 6.9},       {512, 36.6, 58.1, 2.2, 4.4},
    {520, 45.5, 82.7, 2.0, 10.6},      {528, 43.4, 83.6, 2.4, 13.0},
    {540, 51.6, 90.8, 3.2, 12.8},      {546, 42.7, 81.6, 2.4, 5.4},
    {550, 59.8, 88.4, 6.4, 7.8},       {560, 42.2, 76.3, 2.7, 12.8},
    {572, 53.1, 119.3, 194.8, 295.5},  {576, 49.1, 71.9, 4.2, 17.7},
    {588, 45.6, 86.6, 6.8, 9.6},       {594, 44.1, 81.6, 2.5, 6.9},
    {600, 44.4, 80.3, 4.6, 19.7},      {616, 43.4, 88.6, 10.1, 11.3},
    {624, 42.1, 70.5, 2.4, 13.0},      {630, 41.5, 87.2, 1.9, 9.2},
    {640, 37.1, 65.7, 1.5, 12.6},      {648, 51.1, 97.7, 10.6, 20.0},
    {650, 48.3, 87.0, 2.1, 7.6},       {660, 43.7, 84.5, 2.5, 10.6},
    {672, 43.9, 89.4, 2.1, 14.7},      {676, 52.5, 117.0, 184.2, 289.0},
    {686, 42.6, 79.0, 2.0, 4.6},       {700, 45.0, 71.3, 2.7, 12.7},
    {702, 42.8, 81.5, 2.6, 6.8},       {704, 44.0, 74.5, 4.3, 14.6},
    {720, 52.3, 77.7, 3.3, 20.5},      {726, 61.4, 104.2, 117.5, 120.2},
    {728, 42.8, 86.2, 10.3, 11.4},     {750, 47.0, 85.6, 1.9, 9.2},
    {756, 46.2, 86.4, 7.0, 14.6},      {768, 39.8, 58.3, 5.3, 18.4},
    {770, 49.6, 89.2, 2.5, 6.4},       {780, 42.5, 72.5, 2.5, 10.4},
    {784, 41.9, 80.5, 2.0, 11.1},      {792, 43.2, 79.9, 9.8, 16.8},
    {800, 40.4, 80.5, 1.7, 13.4},      {810, 52.2, 87.3, 3.2, 10.2},
    {832, 43.3, 73.7, 4.4, 15.0},      {840, 44.4, 88.9, 2.2, 14.2},
    {858, 59.8, 104.7, 131.7, 127.0},  {864, 51.4, 98.1, 3.4, 24.3},
    {880, 44.5, 82.8, 3.3, 13.5},      {882, 42.8, 79.5, 2.1, 6.8},
    {896, 40.1, 60.0, 4.3, 14.8},      {900, 55.2, 101.6, 3.4, 16.3},
    {910, 48.0, 87.4, 2.6, 6.4},       {924, 68.2, 85.3, 7.6, 10.6},
    {936, 42.0, 79.0, 10.0, 16.9},     {960, 40.2, 76.6, 4.4, 19.3},
    {968, 53.9, 103.0, 368.1, 256.5},  {972, 53.9, 103.1, 8.5, 15.4},
    {980, 42.4, 80.9, 2.1, 8.9},       {990, 49.2, 87.2, 2.7, 8.8},
    {1000, 46.5, 76.6, 2.3, 12.8},     {1008, 41.1, 76.8, 2.1, 18.6},
    {1014, 59.8, 103.4, 117.8, 120.8}, {1024, 37.2, 58.6, 1.8, 9.6}};

// Transform pairs an operator of one size runs in a solve, to weigh execution against planning:
// a force iteration's normal solves reuse an operator for ~100 products, a first small box ~20.
constexpr double kPairsPerOperator = 50.0;

}  // namespace

std::pair<int, int> PaddedPlan2d::FastSizes(int m0, int m1) {
  // The pair (n0, n1), each in [m, 2m], of least planning + kPairsPerOperator pairs of
  // execution.
  double least = 0.0;
  std::pair<int, int> best{0, 0};
  for (const LengthCost& c0 : kLengthCosts) {
    if (c0.n < m0 || c0.n > 2 * m0) continue;
    for (const LengthCost& c1 : kLengthCosts) {
      if (c1.n < m1 || c1.n > 2 * m1) continue;
      const double points = static_cast<double>(c0.n) * c1.n;
      const double cost = 1e6 * (c0.column_plan + c1.row_plan) +
                          kPairsPerOperator * points * 0.5 * (c0.column + c1.row);
      if (best.first == 0 || cost < least) {
        least = cost;
        best = {c0.n, c1.n};
      }
    }
  }
  if (best.first == 0) return {FastSize(m0), FastSize(m1)};  // beyond the table
  return best;
}

double PaddedPlan2d::PairCost(int n0, int n1) {
  const LengthCost* c0 = nullptr;
  const LengthCost* c1 = nullptr;
  for (const LengthCost& c : kLengthCosts) {
    if (c.n == n0) c0 = &c;
    if (c.n == n1) c1 = &c;
  }
  if (!c0 || !c1) return 0.0;
  return static_cast<double>(n0) * n1 * 0.5 * (c0->column + c1->row);
}

int PaddedPlan2d::FastSize(int m) {
  if (m <= 2) return 2;
  for (int n = m + (m % 2);; n += 2) {
    int r = n;
    while (r % 2 == 0) r /= 2;
    if (r == 1 || r == 3 || r == 5) return n;
  }
}

std::shared_ptr<const PaddedPlan2d> PaddedPlan2d::Shared(int n0, int n1) {
  // Planning costs 0.5–3 ms even with FFTW_ESTIMATE, as much as a few dozen transforms of a
  // contact grid; a solve makes operators of the same few sizes again and again (each step of
  // a force iteration, each point of a table), so plans are made once per process. A plan only
  // reads its own data when executed on new arrays, so one plan serves every thread.
  static std::mutex mutex;
  static std::map<std::pair<int, int>, std::shared_ptr<const PaddedPlan2d>> plans;
  // Distinct sizes stay few (they follow the patch sizes of a case or scene); the bound only
  // keeps a pathological sweep over thousands of sizes from holding all their plans.
  constexpr std::size_t kMaxPlans = 256;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = plans[{n0, n1}];
  if (!slot) {
    if (plans.size() > kMaxPlans) {
      plans.clear();  // plans still in use live on in their operators
      return plans[{n0, n1}] = std::make_shared<const PaddedPlan2d>(n0, n1);
    }
    slot = std::make_shared<const PaddedPlan2d>(n0, n1);
  }
  return slot;
}

}  // namespace wrc::fftw
