#pragma once
// Thin checked RAII wrappers around FFTW3 (double precision). No fftw_* call outside core/fft/.

#include <complex>
#include <cstddef>
#include <memory>

namespace wrc::fftw {

/// Frees memory from fftw_malloc.
struct FreeDeleter {
  void operator()(void* p) const;
};

/// An fftw_malloc'ed array: SIMD-aligned, so that plans made on one buffer run on any other
/// (fftw_execute_dft_r2c with new arrays requires the same alignment as at planning time).
template <typename T>
class Buffer {
 public:
  Buffer() = default;
  explicit Buffer(std::size_t n);
  T* data() { return data_.get(); }
  const T* data() const { return data_.get(); }
  std::size_t size() const { return size_; }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }

 private:
  std::unique_ptr<T[], FreeDeleter> data_;
  std::size_t size_ = 0;
};

using RealBuffer = Buffer<double>;
using ComplexBuffer = Buffer<std::complex<double>>;

/// A 2-D real-to-complex and complex-to-real plan pair of n0 × n1 (row-major, n1 fastest),
/// executed on caller-owned buffers. Planning uses FFTW_ESTIMATE: it is fast and deterministic,
/// so results are bit-identical whichever thread or run made the plan (FFTW_MEASURE may pick
/// different algorithms, with different rounding, from one run to the next).
class Plan2d {
 public:
  Plan2d(int n0, int n1);
  ~Plan2d();
  Plan2d(const Plan2d&) = delete;
  Plan2d& operator=(const Plan2d&) = delete;

  int n0() const { return n0_; }
  int n1() const { return n1_; }
  std::size_t real_size() const { return static_cast<std::size_t>(n0_) * n1_; }
  std::size_t complex_size() const { return static_cast<std::size_t>(n0_) * (n1_ / 2 + 1); }

  /// Unnormalised forward transform: in (real_size) → out (complex_size).
  void Forward(double* in, std::complex<double>* out) const;
  /// Unnormalised backward transform: in (complex_size, overwritten) → out (real_size).
  void Backward(std::complex<double>* in, double* out) const;

  /// Smallest even n >= m of the form 2^a, 3·2^a or 5·2^a. FFTW_ESTIMATE plans for these
  /// run at 5.8–6.8 ns per point for a transform pair of a typical contact grid (192 x 384,
  /// 192 x 400, 192 x 512), against 9–25 ns for other 2-3-5-7 sizes (192 x 360, 216 x 360,
  /// 189 x 343 measured): the few percent more points cost less than the slower codelets.
  static int FastSize(int m);
  /// The process-wide plan of this size (made on first use; thread-safe).
  static std::shared_ptr<const Plan2d> Shared(int n0, int n1);

 private:
  int n0_;
  int n1_;
  void* forward_ = nullptr;   // fftw_plan
  void* backward_ = nullptr;  // fftw_plan
};

}  // namespace wrc::fftw
