#pragma once
// Thin checked RAII wrappers around FFTW3 (double precision). No fftw_* call outside core/fft/.

#include <complex>
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

namespace wrc::fftw {

/// Frees memory from fftw_malloc.
struct FreeDeleter {
  void operator()(void* p) const;
};

/// Tag for a buffer that its first use overwrites entirely (a transform's output, a row that is
/// filled before each transform): it is not zero-filled first.
struct Uninitialized {};

/// An fftw_malloc'ed array: SIMD-aligned, so that plans made on one buffer run on any other
/// (fftw_execute_dft_r2c with new arrays requires the same alignment as at planning time).
template <typename T>
class Buffer {
 public:
  Buffer() = default;
  /// n values, zero.
  explicit Buffer(std::size_t n);
  /// n values, not initialised.
  Buffer(std::size_t n, Uninitialized);
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

/// The 2-D DFT of n0 × n1 (row-major, n1 fastest) of a real field that is zero outside its
/// first ny rows and nx columns, and its inverse restricted to those rows and columns: the two
/// halves of a zero-padded linear convolution. Executed on caller-owned buffers.
///
/// Why not FFTW's 2-D r2c plan: the padding makes at least half of the rows zero on the way in
/// and unwanted on the way out, and a row-column transform skips them (FFTW has no pruned
/// transforms); two real rows go through one complex transform, whose plans FFTW_ESTIMATE makes
/// 3–5x faster than real ones (0.2–0.5 ms against 0.5–1.6 ms per new length, measured); and
/// the 2-D r2c plans of ESTIMATE copy the array twice per transform (fftw_cpy2d). Measured on
/// grids of 64 x 80 to 192 x 160: 1.6–2.5x faster per transform pair.
///
/// Planning uses FFTW_ESTIMATE: fast and deterministic, so results are bit-identical whichever
/// thread or run made the plan (FFTW_MEASURE may pick different algorithms, with different
/// rounding, from one run to the next).
class PaddedPlan2d {
 public:
  PaddedPlan2d(int n0, int n1);
  ~PaddedPlan2d();
  PaddedPlan2d(const PaddedPlan2d&) = delete;
  PaddedPlan2d& operator=(const PaddedPlan2d&) = delete;

  int n0() const { return n0_; }
  int n1() const { return n1_; }
  /// Values of a spectrum: n0 rows of n1/2 + 1 (the other half follows from symmetry).
  std::size_t complex_size() const { return static_cast<std::size_t>(n0_) * (n1_ / 2 + 1); }
  /// Complex values of the row buffer both transforms need (one row).
  std::size_t row_buffer_size() const { return static_cast<std::size_t>(n1_); }

  /// Where Forward puts its row stage before the columns are transformed out of place into
  /// the spectrum. Which pairs of rows hold zeros is tracked, so that the zero padding (at
  /// least half of the rows) and the zero rows of the input (the gaps between contact regions,
  /// the elements out of contact in a CG direction) are not cleared again for every transform.
  struct Staging {
    explicit Staging(const PaddedPlan2d& plan)
        : values(plan.complex_size()), zero_pairs(static_cast<std::size_t>(plan.n0() / 2), 1) {}
    ComplexBuffer values;          // zero-initialised
    std::vector<char> zero_pairs;  // rows 2m and 2m + 1 hold zeros only
  };

  /// Unnormalised forward transform of `in` (ny rows of nx values, row stride nx; zero
  /// elsewhere; ny <= n0, nx <= n1) into `spectrum` (complex_size). `rows`: row_buffer_size;
  /// `staging`: made for this plan's size.
  void Forward(const double* in, int ny, int nx, std::complex<double>* spectrum,
               std::complex<double>* rows, Staging& staging) const;
  /// Unnormalised backward transform of `spectrum` (overwritten), of which only the first ny
  /// rows and nx columns are written to `out` (row stride nx).
  void Backward(std::complex<double>* spectrum, int ny, int nx, double* out,
                std::complex<double>* rows) const;

  /// Smallest even n >= m of the form 2^a, 3·2^a or 5·2^a. FFTW_ESTIMATE plans for these run
  /// faster than for other 2-3-5-7 sizes (measured 5.8–6.8 against 9–25 ns per point for a
  /// 2-D transform pair): the few percent more points cost less than the slower codelets.
  static int FastSize(int m);
  /// Padded sizes (n0, n1) for at least (m0, m1) values that cost least to plan and run, from
  /// a table of measured costs per length (fftw.cpp); FastSize beyond the table. E.g. for the
  /// 84 x 73 box of a heavy-haul patch (m1 = 167, m0 = 145): 150 x 200 instead of 160 x 192,
  /// a third fewer instructions per transform pair.
  static std::pair<int, int> FastSizes(int m0, int m1);
  /// Instructions of one Forward + Backward pair of the full n0 × n1 transform, from the same
  /// measured table as FastSizes (0 for lengths beyond it).
  static double PairCost(int n0, int n1);
  /// The process-wide plan of this size (made on first use; thread-safe).
  static std::shared_ptr<const PaddedPlan2d> Shared(int n0, int n1);

 private:
  int n0_;
  int n1_;
  void* row_forward_ = nullptr;      // fftw_plan: one complex row of n1
  void* row_backward_ = nullptr;     // fftw_plan
  void* column_forward_ = nullptr;   // fftw_plan: n1/2 + 1 columns of n0, staging → spectrum
  void* column_backward_ = nullptr;  // fftw_plan
};

}  // namespace wrc::fftw
