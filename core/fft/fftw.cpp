#include "core/fft/fftw.h"

#include <fftw3.h>

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

Plan2d::Plan2d(int n0, int n1) : n0_(n0), n1_(n1) {
  if (n0 < 1 || n1 < 1) {
    throw std::invalid_argument("FFT size " + std::to_string(n0) + " x " + std::to_string(n1));
  }
  RealBuffer real(real_size());
  ComplexBuffer spectrum(complex_size());
  auto* c = reinterpret_cast<fftw_complex*>(spectrum.data());
  std::lock_guard<std::mutex> lock(PlannerMutex());
  forward_ = fftw_plan_dft_r2c_2d(n0, n1, real.data(), c, FFTW_ESTIMATE);
  backward_ = fftw_plan_dft_c2r_2d(n0, n1, c, real.data(), FFTW_ESTIMATE);
  if (forward_ == nullptr || backward_ == nullptr) {
    if (forward_) fftw_destroy_plan(static_cast<fftw_plan>(forward_));
    if (backward_) fftw_destroy_plan(static_cast<fftw_plan>(backward_));
    throw std::runtime_error("FFTW could not plan a " + std::to_string(n0) + " x " +
                             std::to_string(n1) + " transform");
  }
}

Plan2d::~Plan2d() {
  std::lock_guard<std::mutex> lock(PlannerMutex());
  fftw_destroy_plan(static_cast<fftw_plan>(forward_));
  fftw_destroy_plan(static_cast<fftw_plan>(backward_));
}

void Plan2d::Forward(double* in, std::complex<double>* out) const {
  fftw_execute_dft_r2c(static_cast<fftw_plan>(forward_), in, reinterpret_cast<fftw_complex*>(out));
}

void Plan2d::Backward(std::complex<double>* in, double* out) const {
  fftw_execute_dft_c2r(static_cast<fftw_plan>(backward_), reinterpret_cast<fftw_complex*>(in), out);
}

int Plan2d::FastSize(int m) {
  if (m <= 2) return 2;
  for (int n = m + (m % 2);; n += 2) {
    int r = n;
    while (r % 2 == 0) r /= 2;
    if (r == 1 || r == 3 || r == 5) return n;
  }
}

std::shared_ptr<const Plan2d> Plan2d::Shared(int n0, int n1) {
  // Planning costs 0.5–3 ms even with FFTW_ESTIMATE, as much as a few dozen transforms of a
  // contact grid; a solve makes operators of the same few sizes again and again (each step of
  // a force iteration, each point of a table), so plans are made once per process. A plan only
  // reads its own data when executed on new arrays, so one plan serves every thread.
  static std::mutex mutex;
  static std::map<std::pair<int, int>, std::shared_ptr<const Plan2d>> plans;
  // Distinct sizes stay few (they follow the patch sizes of a case or scene); the bound only
  // keeps a pathological sweep over thousands of sizes from holding all their plans.
  constexpr std::size_t kMaxPlans = 256;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = plans[{n0, n1}];
  if (!slot) {
    if (plans.size() > kMaxPlans) {
      plans.clear();  // plans still in use live on in their operators
      return plans[{n0, n1}] = std::make_shared<const Plan2d>(n0, n1);
    }
    slot = std::make_shared<const Plan2d>(n0, n1);
  }
  return slot;
}

}  // namespace wrc::fftw
