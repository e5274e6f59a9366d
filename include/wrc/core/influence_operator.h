#pragma once
/// @file influence_operator.h
/// Matrix-free application of the influence matrices u = A·p on a grid, by zero-padded FFT
/// convolution (the matrices are block-Toeplitz, paper §2.7), plus a dense version kept as the
/// test oracle.

#include <array>
#include <atomic>
#include <complex>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "wrc/core/grid.h"
#include "wrc/core/influence.h"
#include "wrc/core/material.h"

namespace wrc {

namespace fftw {
class PaddedPlan2d;
}

/// Scratch memory for FftInfluenceOperator, owned by the caller so that one operator can serve
/// several threads (each with its own workspace) and repeated solves allocate nothing.
class ConvolutionWorkspace {
 public:
  ConvolutionWorkspace();
  ~ConvolutionWorkspace();
  ConvolutionWorkspace(ConvolutionWorkspace&&) noexcept;
  ConvolutionWorkspace& operator=(ConvolutionWorkspace&&) noexcept;

 private:
  friend class FftInfluenceOperator;
  struct Buffers;
  std::unique_ptr<Buffers> buffers_;
};

/// The 3 × 3 centre of the inverse of a convolution, scaled to a centre weight of 1: the
/// weights at offsets (0, 0), (±1, 0), (0, ±1) and (±1, ±1) in (x, y) elements.
struct LocalInverseStencil {
  double centre = 1.0;
  double x = 0.0;
  double y = 0.0;
  double diagonal = 0.0;
};

/// Applies the influence coefficients of one grid by FFT. The plan and the kernels' spectra are
/// made once, at the first product or workspace (thread-safe): a tangential operator whose solve
/// keeps its slips current by direct updates may never need them. Plans execute on workspace
/// buffers.
class FftInfluenceOperator {
 public:
  /// Prepares the kernels listed in `components` (others cannot be applied).
  FftInfluenceOperator(const Grid& grid, const CombinedElasticity& material,
                       const std::vector<InfluenceComponent>& components);
  ~FftInfluenceOperator();
  FftInfluenceOperator(const FftInfluenceOperator&) = delete;
  FftInfluenceOperator& operator=(const FftInfluenceOperator&) = delete;

  const Grid& grid() const { return grid_; }
  const CombinedElasticity& material() const { return material_; }
  bool has(InfluenceComponent c) const { return prepared_components_[Index(c)]; }
  /// Points of the padded transform (n0·n1): the cost of a product scales with it.
  std::size_t transform_points() const;
  /// Estimated instructions of one product (Apply), from FFTW's measured costs per length.
  double ProductCost() const;

  /// A workspace sized for this operator.
  ConvolutionWorkspace MakeWorkspace() const;
  /// Whether `ws` was made for an operator of this operator's FFT size.
  bool Fits(const ConvolutionWorkspace& ws) const;

  /// out = A_c · in, both of grid().size() values.
  void Apply(InfluenceComponent c, const double* in, double* out, ConvolutionWorkspace& ws) const;

  /// The 3 × 3 centre of the inverse of component c's kernel on this grid (a windowed 16 × 16
  /// torus approximates the infinite grid): a preconditioner for the normal CG that costs a few
  /// operations per element. Empty if the stencil is not positive definite (not seen; a guard).
  /// Component c must be even in x and y (kNN).
  std::optional<LocalInverseStencil> LocalInverse(InfluenceComponent c) const;

  /// Makes the plan and the spectra now (otherwise the first product or workspace does; once
  /// either way), e.g. so that their cost is timed apart from the solves.
  void Prepare() const;

  /// The tangential block [ux; uy] = [[Axx, Axy]; [Axy, Ayy]]·[px; py] with two forward and two
  /// backward transforms instead of eight.
  void ApplyTangential(const double* px, const double* py, double* ux, double* uy,
                       ConvolutionWorkspace& ws) const;

 private:
  static std::size_t Index(InfluenceComponent c) { return static_cast<std::size_t>(c); }
  std::optional<LocalInverseStencil> ComputeLocalInverse(InfluenceComponent c) const;
  void Forward(const double* in, std::complex<double>* spectrum, ConvolutionWorkspace& ws) const;
  void Backward(std::complex<double>* spectrum, double* out, ConvolutionWorkspace& ws) const;

  Grid grid_;
  CombinedElasticity material_;
  int n0_ = 0, n1_ = 0;  // padded transform size
  std::array<bool, 6> prepared_components_{};
  // Not std::call_once: an exception (out of memory) thrown through it unwinds through
  // pthread_once, which needs glibc to load libgcc_s, and that fails when memory is short.
  mutable std::mutex prepare_mutex_;
  mutable std::atomic<bool> prepared_{false};
  mutable std::shared_ptr<const fftw::PaddedPlan2d> plan_;
  // Kernel spectra, scaled by 1/N so that Backward needs no extra pass; empty when not prepared.
  mutable std::array<std::vector<std::complex<double>>, 6> spectra_;
};

/// The same operator as a dense matrix-vector product: O(n²), for tests only.
class DenseInfluenceOperator {
 public:
  DenseInfluenceOperator(const Grid& grid, const CombinedElasticity& material);
  void Apply(InfluenceComponent c, const double* in, double* out) const;

 private:
  Grid grid_;
  CombinedElasticity material_;
};

}  // namespace wrc
