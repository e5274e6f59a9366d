#include "wrc/core/influence_operator.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <tuple>

#include "core/common/portable_simd.h"
#include "core/fft/fftw.h"

namespace wrc {

struct ConvolutionWorkspace::Buffers {
  explicit Buffers(const fftw::PaddedPlan2d& plan) : staging(plan) {}
  fftw::PaddedPlan2d::Staging staging;
  fftw::ComplexBuffer rows;
  fftw::ComplexBuffer spectrum_a;
  fftw::ComplexBuffer spectrum_b;
  fftw::ComplexBuffer spectrum_c;
};

ConvolutionWorkspace::ConvolutionWorkspace() = default;
ConvolutionWorkspace::~ConvolutionWorkspace() = default;
ConvolutionWorkspace::ConvolutionWorkspace(ConvolutionWorkspace&&) noexcept = default;
ConvolutionWorkspace& ConvolutionWorkspace::operator=(ConvolutionWorkspace&&) noexcept = default;

namespace {

// Complex products written out: std::complex's operator* checks for NaN/∞ operands (C99 Annex G)
// and does not vectorise; spectra here are finite.
// Built for AVX2 as well as the baseline x86-64 ISA, chosen at load time (as the tangential
// solver's inner loops): one product per transform pair, over the whole padded spectrum.
WRC_CLONE_FOR_AVX2
void MultiplyInPlace(const std::vector<std::complex<double>>& k, std::complex<double>* s) {
  const double* a = reinterpret_cast<const double*>(k.data());
  double* b = reinterpret_cast<double*>(s);
  for (std::size_t i = 0; i < k.size(); ++i) {
    const double ar = a[2 * i], ai = a[2 * i + 1], br = b[2 * i], bi = b[2 * i + 1];
    b[2 * i] = ar * br - ai * bi;
    b[2 * i + 1] = ar * bi + ai * br;
  }
}

// out = k1·s1 + k2·s2, element by element.
WRC_CLONE_FOR_AVX2
void MultiplyAdd(const std::complex<double>* k1, const std::complex<double>* s1,
                 const std::complex<double>* k2, const std::complex<double>* s2,
                 std::complex<double>* out, std::size_t n) {
  const double* a = reinterpret_cast<const double*>(k1);
  const double* b = reinterpret_cast<const double*>(s1);
  const double* c = reinterpret_cast<const double*>(k2);
  const double* d = reinterpret_cast<const double*>(s2);
  double* o = reinterpret_cast<double*>(out);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t r = 2 * i, m = 2 * i + 1;
    o[r] = a[r] * b[r] - a[m] * b[m] + c[r] * d[r] - c[m] * d[m];
    o[m] = a[r] * b[m] + a[m] * b[r] + c[r] * d[m] + c[m] * d[r];
  }
}

}  // namespace

FftInfluenceOperator::FftInfluenceOperator(const Grid& grid, const CombinedElasticity& material,
                                           const std::vector<InfluenceComponent>& components)
    : grid_(grid), material_(material) {
  grid_.Validate();
  // Linear convolution of n values with offsets −(n−1)…(n−1) is exact as a circular one of
  // length >= 2n − 1; rounded up to a size FFTW transforms fast.
  std::tie(n0_, n1_) = fftw::PaddedPlan2d::FastSizes(2 * grid_.ny - 1, 2 * grid_.nx - 1);
  for (InfluenceComponent c : components) prepared_components_[Index(c)] = true;
}

void FftInfluenceOperator::Prepare() const {
  if (prepared_.load(std::memory_order_acquire)) return;
  const std::lock_guard<std::mutex> lock(prepare_mutex_);
  if (prepared_.load(std::memory_order_relaxed)) return;
  plan_ = fftw::PaddedPlan2d::Shared(n0_, n1_);
  fftw::RealBuffer kernel(static_cast<std::size_t>(n0_) * n1_, fftw::Uninitialized{});
  fftw::ComplexBuffer spectrum(plan_->complex_size(), fftw::Uninitialized{});
  fftw::ComplexBuffer rows(plan_->row_buffer_size(), fftw::Uninitialized{});
  fftw::PaddedPlan2d::Staging staging(*plan_);
  const double inv_n = 1.0 / static_cast<double>(kernel.size());
  for (std::size_t index = 0; index < spectra_.size(); ++index) {
    if (!prepared_components_[index]) continue;
    const InfluenceCoefficients coeffs(grid_, material_, static_cast<InfluenceComponent>(index));
    std::fill(kernel.data(), kernel.data() + kernel.size(), 0.0);
    for (int dj = -(grid_.ny - 1); dj <= grid_.ny - 1; ++dj) {
      const int row = (dj + n0_) % n0_;
      for (int di = -(grid_.nx - 1); di <= grid_.nx - 1; ++di) {
        kernel[static_cast<std::size_t>(row) * n1_ + (di + n1_) % n1_] = coeffs.at(di, dj);
      }
    }
    plan_->Forward(kernel.data(), n0_, n1_, spectrum.data(), rows.data(), staging);
    auto& s = spectra_[index];
    s.assign(spectrum.data(), spectrum.data() + spectrum.size());
    for (auto& v : s) v *= inv_n;
  }
  prepared_.store(true, std::memory_order_release);
}

FftInfluenceOperator::~FftInfluenceOperator() = default;

std::size_t FftInfluenceOperator::transform_points() const {
  return static_cast<std::size_t>(n0_) * static_cast<std::size_t>(n1_);
}

double FftInfluenceOperator::ProductCost() const { return fftw::PaddedPlan2d::PairCost(n0_, n1_); }

ConvolutionWorkspace FftInfluenceOperator::MakeWorkspace() const {
  Prepare();
  ConvolutionWorkspace ws;
  ws.buffers_ = std::make_unique<ConvolutionWorkspace::Buffers>(*plan_);
  // Each product writes them before reading them.
  const fftw::Uninitialized written_first;
  ws.buffers_->rows = fftw::ComplexBuffer(plan_->row_buffer_size(), written_first);
  ws.buffers_->spectrum_a = fftw::ComplexBuffer(plan_->complex_size(), written_first);
  if (has(InfluenceComponent::kXX)) {  // ApplyTangential's other two spectra (~0.5 MB each)
    ws.buffers_->spectrum_b = fftw::ComplexBuffer(plan_->complex_size(), written_first);
    ws.buffers_->spectrum_c = fftw::ComplexBuffer(plan_->complex_size(), written_first);
  }
  return ws;
}

bool FftInfluenceOperator::Fits(const ConvolutionWorkspace& ws) const {
  // The sizes PaddedPlan2d gives (complex_size, row_buffer_size), without needing the plan.
  const std::size_t complex_size = static_cast<std::size_t>(n0_) * (n1_ / 2 + 1);
  return ws.buffers_ && ws.buffers_->spectrum_a.size() == complex_size &&
         ws.buffers_->rows.size() == static_cast<std::size_t>(n1_) &&
         (!has(InfluenceComponent::kXX) || ws.buffers_->spectrum_c.size() == complex_size);
}

void FftInfluenceOperator::Forward(const double* in, std::complex<double>* spectrum,
                                   ConvolutionWorkspace& ws) const {
  plan_->Forward(in, grid_.ny, grid_.nx, spectrum, ws.buffers_->rows.data(), ws.buffers_->staging);
}

void FftInfluenceOperator::Backward(std::complex<double>* spectrum, double* out,
                                    ConvolutionWorkspace& ws) const {
  plan_->Backward(spectrum, grid_.ny, grid_.nx, out, ws.buffers_->rows.data());
}

void FftInfluenceOperator::Apply(InfluenceComponent c, const double* in, double* out,
                                 ConvolutionWorkspace& ws) const {
  if (!has(c)) throw std::logic_error("influence component not prepared for this operator");
  if (!Fits(ws)) throw std::logic_error("convolution workspace does not fit this operator");
  Prepare();
  std::complex<double>* s = ws.buffers_->spectrum_a.data();
  Forward(in, s, ws);
  MultiplyInPlace(spectra_[Index(c)], s);
  Backward(s, out, ws);
}

void FftInfluenceOperator::ApplyTangential(const double* px, const double* py, double* ux,
                                           double* uy, ConvolutionWorkspace& ws) const {
  using C = InfluenceComponent;
  if (!has(C::kXX) || !has(C::kYY) || !has(C::kXY)) {
    throw std::logic_error("tangential influence components not prepared for this operator");
  }
  if (!Fits(ws)) throw std::logic_error("convolution workspace does not fit this operator");
  Prepare();
  std::complex<double>* sx = ws.buffers_->spectrum_a.data();
  std::complex<double>* sy = ws.buffers_->spectrum_b.data();
  std::complex<double>* su = ws.buffers_->spectrum_c.data();
  Forward(px, sx, ws);
  Forward(py, sy, ws);
  const auto& kxx = spectra_[Index(C::kXX)];
  const auto& kyy = spectra_[Index(C::kYY)];
  const auto& kxy = spectra_[Index(C::kXY)];
  const std::size_t n = kxx.size();
  MultiplyAdd(kxx.data(), sx, kxy.data(), sy, su, n);
  Backward(su, ux, ws);
  MultiplyAdd(kxy.data(), sx, kyy.data(), sy, su, n);
  Backward(su, uy, ws);
}

namespace {

// The stencil of one (component, dx, dy, material), computed once per process: it costs ~0.5 M
// instructions (225 closed-form coefficients and a small transform), a tenth of a table point's
// solve, and every normal solve asks for it.
using StencilKey = std::tuple<int, double, double, double, double, double>;
std::mutex& StencilMutex() {
  static std::mutex m;
  return m;
}
std::map<StencilKey, std::optional<LocalInverseStencil>>& StencilCache() {
  static std::map<StencilKey, std::optional<LocalInverseStencil>> cache;
  return cache;
}

}  // namespace

std::optional<LocalInverseStencil> FftInfluenceOperator::LocalInverse(InfluenceComponent c) const {
  const StencilKey key{static_cast<int>(c),     grid_.dx,          grid_.dy,
                       material_.shear_modulus, material_.poisson, material_.kappa};
  {
    std::lock_guard<std::mutex> lock(StencilMutex());
    const auto found = StencilCache().find(key);
    if (found != StencilCache().end()) return found->second;
  }
  const std::optional<LocalInverseStencil> stencil = ComputeLocalInverse(c);
  std::lock_guard<std::mutex> lock(StencilMutex());
  // A pathological sweep over many grids would grow the cache without bound; a few thousand
  // entries are ~0.2 MB.
  if (StencilCache().size() > 4096) StencilCache().clear();
  StencilCache().emplace(key, stencil);
  return stencil;
}

std::optional<LocalInverseStencil> FftInfluenceOperator::ComputeLocalInverse(
    InfluenceComponent c) const {
  // The inverse of the kernel on the infinite grid, approximated on a 16 × 16 torus: the kernel
  // times a triangle window of half-width 8 (so that nothing wraps around). Windowing convolves
  // the kernel's symbol, which is positive (the influence matrix is positive definite), with the
  // non-negative Fejér kernel, so the torus spectrum stays positive; the padded operator's own
  // spectrum does not (its box-truncated kernel rings below zero on long patches). The inverse's
  // centre hardly depends on the torus: 16, 32 and 64 give iterations within ±2 on heavy haul.
  constexpr int kTorus = 16, kHalfWidth = kTorus / 2;
  const auto plan = fftw::PaddedPlan2d::Shared(kTorus, kTorus);
  fftw::RealBuffer kernel(static_cast<std::size_t>(kTorus) * kTorus);
  std::fill(kernel.data(), kernel.data() + kernel.size(), 0.0);
  const double a = 0.5 * grid_.dx, b = 0.5 * grid_.dy;
  for (int dj = 1 - kHalfWidth; dj < kHalfWidth; ++dj) {
    for (int di = 1 - kHalfWidth; di < kHalfWidth; ++di) {
      const double window = (1.0 - std::abs(di) / static_cast<double>(kHalfWidth)) *
                            (1.0 - std::abs(dj) / static_cast<double>(kHalfWidth));
      kernel[static_cast<std::size_t>((dj + kTorus) % kTorus) * kTorus + (di + kTorus) % kTorus] =
          window * RectangleInfluence(c, material_, di * grid_.dx, dj * grid_.dy, a, b);
    }
  }
  fftw::ComplexBuffer spectrum(plan->complex_size());
  fftw::ComplexBuffer rows(plan->row_buffer_size());
  fftw::PaddedPlan2d::Staging staging(*plan);
  plan->Forward(kernel.data(), kTorus, kTorus, spectrum.data(), rows.data(), staging);

  // An even kernel has a real spectrum S, and the inverse at offset (a, b) rows and columns is
  // Σ cos(2π·k0·a/n)·cos(2π·k1·b/n) / S(k0, k1) up to a factor that the scaling to a centre of
  // 1 removes. The stored half spectrum (k1 <= n/2) counts its inner columns twice.
  constexpr int kHalf = kTorus / 2 + 1;
  constexpr double kTwoPi = 6.28318530717958647692;
  double sum00 = 0.0, sum01 = 0.0, sum10 = 0.0, sum11 = 0.0;
  for (int k0 = 0; k0 < kTorus; ++k0) {
    double row0 = 0.0, row1 = 0.0;  // Σ over k1 of 1/S and of cos(2π·k1/n)/S
    for (int k1 = 0; k1 < kHalf; ++k1) {
      const double v = spectrum[static_cast<std::size_t>(k0) * kHalf + k1].real();
      if (!(v > 0.0)) return std::nullopt;
      const double weight = (k1 == 0 || 2 * k1 == kTorus) ? 1.0 : 2.0;
      row0 += weight / v;
      row1 += weight * std::cos(kTwoPi * k1 / kTorus) / v;
    }
    const double c0 = std::cos(kTwoPi * k0 / kTorus);
    sum00 += row0;
    sum01 += row1;
    sum10 += c0 * row0;
    sum11 += c0 * row1;
  }
  LocalInverseStencil stencil;
  stencil.x = sum01 / sum00;
  stencil.y = sum10 / sum00;
  stencil.diagonal = sum11 / sum00;
  // Positive definite restricted to any set of elements when its symbol
  // 1 + 2x·cos θx + 2y·cos θy + 4d·cos θx·cos θy is positive; being bilinear in the cosines,
  // its minimum is at one of the four corners (±1, ±1).
  for (double cx : {-1.0, 1.0}) {
    for (double cy : {-1.0, 1.0}) {
      const double symbol =
          1.0 + 2.0 * stencil.x * cx + 2.0 * stencil.y * cy + 4.0 * stencil.diagonal * cx * cy;
      if (!(symbol > 1e-3)) return std::nullopt;
    }
  }
  return stencil;
}

DenseInfluenceOperator::DenseInfluenceOperator(const Grid& grid, const CombinedElasticity& material)
    : grid_(grid), material_(material) {
  grid_.Validate();
}

void DenseInfluenceOperator::Apply(InfluenceComponent c, const double* in, double* out) const {
  const InfluenceCoefficients coeffs(grid_, material_, c);
  for (int j = 0; j < grid_.ny; ++j) {
    for (int i = 0; i < grid_.nx; ++i) {
      double sum = 0.0;
      for (int l = 0; l < grid_.ny; ++l) {
        for (int k = 0; k < grid_.nx; ++k) sum += coeffs.at(i - k, j - l) * in[grid_.index(k, l)];
      }
      out[grid_.index(i, j)] = sum;
    }
  }
}

}  // namespace wrc
