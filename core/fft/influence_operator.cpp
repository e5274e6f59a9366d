#include "wrc/influence_operator.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "core/fft/fftw.h"

namespace wrc {

struct ConvolutionWorkspace::Buffers {
  fftw::RealBuffer padded;
  fftw::ComplexBuffer spectrum_a;
  fftw::ComplexBuffer spectrum_b;
  fftw::ComplexBuffer spectrum_c;
};

ConvolutionWorkspace::ConvolutionWorkspace() = default;
ConvolutionWorkspace::~ConvolutionWorkspace() = default;
ConvolutionWorkspace::ConvolutionWorkspace(ConvolutionWorkspace&&) noexcept = default;
ConvolutionWorkspace& ConvolutionWorkspace::operator=(ConvolutionWorkspace&&) noexcept = default;

FftInfluenceOperator::FftInfluenceOperator(const Grid& grid, const CombinedElasticity& material,
                                           const std::vector<InfluenceComponent>& components)
    : grid_(grid), material_(material) {
  grid_.Validate();
  // Linear convolution of n values with offsets −(n−1)…(n−1) is exact as a circular one of
  // length >= 2n − 1; rounded up to a size FFTW transforms fast.
  const int n1 = fftw::Plan2d::FastSize(2 * grid_.nx - 1);
  const int n0 = fftw::Plan2d::FastSize(2 * grid_.ny - 1);
  plan_ = fftw::Plan2d::Shared(n0, n1);

  fftw::RealBuffer kernel(plan_->real_size());
  fftw::ComplexBuffer spectrum(plan_->complex_size());
  const double inv_n = 1.0 / static_cast<double>(plan_->real_size());
  for (InfluenceComponent c : components) {
    if (has(c)) continue;
    const InfluenceCoefficients coeffs(grid_, material_, c);
    std::fill(kernel.data(), kernel.data() + kernel.size(), 0.0);
    for (int dj = -(grid_.ny - 1); dj <= grid_.ny - 1; ++dj) {
      const int row = (dj + n0) % n0;
      for (int di = -(grid_.nx - 1); di <= grid_.nx - 1; ++di) {
        kernel[static_cast<std::size_t>(row) * n1 + (di + n1) % n1] = coeffs.at(di, dj);
      }
    }
    plan_->Forward(kernel.data(), spectrum.data());
    auto& s = spectra_[Index(c)];
    s.assign(spectrum.data(), spectrum.data() + spectrum.size());
    for (auto& v : s) v *= inv_n;
  }
}

FftInfluenceOperator::~FftInfluenceOperator() = default;

ConvolutionWorkspace FftInfluenceOperator::MakeWorkspace() const {
  ConvolutionWorkspace ws;
  ws.buffers_ = std::make_unique<ConvolutionWorkspace::Buffers>();
  ws.buffers_->padded = fftw::RealBuffer(plan_->real_size());
  ws.buffers_->spectrum_a = fftw::ComplexBuffer(plan_->complex_size());
  ws.buffers_->spectrum_b = fftw::ComplexBuffer(plan_->complex_size());
  ws.buffers_->spectrum_c = fftw::ComplexBuffer(plan_->complex_size());
  return ws;
}

bool FftInfluenceOperator::Fits(const ConvolutionWorkspace& ws) const {
  return ws.buffers_ && ws.buffers_->padded.size() == plan_->real_size();
}

void FftInfluenceOperator::Forward(const double* in, std::complex<double>* spectrum,
                                   ConvolutionWorkspace& ws) const {
  double* padded = ws.buffers_->padded.data();
  const int n1 = plan_->n1();
  std::fill(padded, padded + plan_->real_size(), 0.0);
  for (int j = 0; j < grid_.ny; ++j) {
    std::memcpy(padded + static_cast<std::size_t>(j) * n1, in + grid_.index(0, j),
                sizeof(double) * grid_.nx);
  }
  plan_->Forward(padded, spectrum);
}

void FftInfluenceOperator::Backward(std::complex<double>* spectrum, double* out,
                                    ConvolutionWorkspace& ws) const {
  double* padded = ws.buffers_->padded.data();
  const int n1 = plan_->n1();
  plan_->Backward(spectrum, padded);
  for (int j = 0; j < grid_.ny; ++j) {
    std::memcpy(out + grid_.index(0, j), padded + static_cast<std::size_t>(j) * n1,
                sizeof(double) * grid_.nx);
  }
}

void FftInfluenceOperator::Apply(InfluenceComponent c, const double* in, double* out,
                                 ConvolutionWorkspace& ws) const {
  if (!has(c)) throw std::logic_error("influence component not prepared for this operator");
  if (!Fits(ws)) throw std::logic_error("convolution workspace does not fit this operator");
  std::complex<double>* s = ws.buffers_->spectrum_a.data();
  Forward(in, s, ws);
  const auto& k = spectra_[Index(c)];
  for (std::size_t i = 0; i < k.size(); ++i) s[i] *= k[i];
  Backward(s, out, ws);
}

void FftInfluenceOperator::ApplyTangential(const double* px, const double* py, double* ux,
                                           double* uy, ConvolutionWorkspace& ws) const {
  using C = InfluenceComponent;
  if (!has(C::kXX) || !has(C::kYY) || !has(C::kXY)) {
    throw std::logic_error("tangential influence components not prepared for this operator");
  }
  if (!Fits(ws)) throw std::logic_error("convolution workspace does not fit this operator");
  std::complex<double>* sx = ws.buffers_->spectrum_a.data();
  std::complex<double>* sy = ws.buffers_->spectrum_b.data();
  std::complex<double>* su = ws.buffers_->spectrum_c.data();
  Forward(px, sx, ws);
  Forward(py, sy, ws);
  const auto& kxx = spectra_[Index(C::kXX)];
  const auto& kyy = spectra_[Index(C::kYY)];
  const auto& kxy = spectra_[Index(C::kXY)];
  const std::size_t n = kxx.size();
  for (std::size_t i = 0; i < n; ++i) su[i] = kxx[i] * sx[i] + kxy[i] * sy[i];
  Backward(su, ux, ws);
  for (std::size_t i = 0; i < n; ++i) su[i] = kxy[i] * sx[i] + kyy[i] * sy[i];
  Backward(su, uy, ws);
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
