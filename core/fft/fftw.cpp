#include "core/fft/fftw.h"

#include <fftw3.h>

#include <algorithm>
#include <map>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>

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
Buffer<T>::Buffer(std::size_t n) : size_(n) {
  void* p = fftw_malloc(sizeof(T) * (n > 0 ? n : 1));
  if (p == nullptr) throw std::bad_alloc();
  data_.reset(static_cast<T*>(p));
  for (std::size_t i = 0; i < n; ++i) data_[i] = T{};
}
template class Buffer<double>;
template class Buffer<std::complex<double>>;

PaddedPlan2d::PaddedPlan2d(int n0, int n1) : n0_(n0), n1_(n1) {
  if (n0 < 2 || n1 < 2 || n0 % 2 != 0 || n1 % 2 != 0) {
    throw std::invalid_argument("padded FFT size " + std::to_string(n0) + " x " +
                                std::to_string(n1) + ": both must be even and >= 2");
  }
  // Plans run later on other fftw_malloc'ed buffers, which have the same alignment.
  ComplexBuffer rows(row_buffer_size());
  ComplexBuffer spectrum(complex_size());
  auto* r = reinterpret_cast<fftw_complex*>(rows.data());
  auto* c = reinterpret_cast<fftw_complex*>(spectrum.data());
  const int nc = n1 / 2 + 1;
  std::lock_guard<std::mutex> lock(PlannerMutex());
  row_forward_ = fftw_plan_dft_1d(n1, r, r, FFTW_FORWARD, FFTW_ESTIMATE);
  row_backward_ = fftw_plan_dft_1d(n1, r, r, FFTW_BACKWARD, FFTW_ESTIMATE);
  column_forward_ = fftw_plan_many_dft(1, &n0, nc, c, nullptr, nc, 1, c, nullptr, nc, 1,
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

void PaddedPlan2d::Forward(const double* in, int ny, int nx, std::complex<double>* spectrum,
                           std::complex<double>* rows) const {
  using Complex = std::complex<double>;
  const int nc = n1_ / 2 + 1;
  const int pairs = (ny + 1) / 2;
  Complex* z = rows;
  for (int m = 0; m < pairs; ++m) {
    // Rows a = 2m and b = 2m + 1 as one complex row a + i·b.
    const double* a = in + static_cast<std::size_t>(2 * m) * nx;
    const double* b = 2 * m + 1 < ny ? a + nx : nullptr;
    for (int k = 0; k < nx; ++k) z[k] = Complex(a[k], b ? b[k] : 0.0);
    std::fill(z + nx, z + n1_, Complex(0.0, 0.0));
    fftw_execute_dft(static_cast<fftw_plan>(row_forward_), reinterpret_cast<fftw_complex*>(z),
                     reinterpret_cast<fftw_complex*>(z));
    // Split by the symmetry of real rows: A_k = (Z_k + conj Z_−k)/2, B_k = (Z_k − conj Z_−k)/2i.
    Complex* sa = spectrum + static_cast<std::size_t>(2 * m) * nc;
    Complex* sb = sa + nc;  // row 2m + 1 < n0: n0 is even and 2m < ny <= n0
    for (int k = 0; k < nc; ++k) {
      const Complex zk = z[k];
      const Complex zm = std::conj(z[k == 0 ? 0 : n1_ - k]);
      sa[k] = 0.5 * (zk + zm);
      const Complex d = zk - zm;
      sb[k] = Complex(0.5 * d.imag(), -0.5 * d.real());
    }
  }
  std::fill(spectrum + static_cast<std::size_t>(2 * pairs) * nc, spectrum + complex_size(),
            Complex(0.0, 0.0));
  fftw_execute_dft(static_cast<fftw_plan>(column_forward_),
                   reinterpret_cast<fftw_complex*>(spectrum),
                   reinterpret_cast<fftw_complex*>(spectrum));
}

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
