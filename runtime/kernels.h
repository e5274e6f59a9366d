#pragma once
/// @file kernels.h
/// The innermost sums of multilinear and cubic interpolation. Table::EvalLinear/EvalCubic
/// reduce a point to weights and data offsets (the *Terms below); a kernel forms the weighted
/// sums. Kernels are compiled twice (kernels.inc): for the baseline instruction set and, on
/// x86-64 with GCC or Clang, for x86-64-v3 (AVX2 + FMA); SelectKernels() picks one by CPU
/// detection when a table is loaded. Internal to wrc_runtime.
///
/// Both sums split the D active axes into a lower half (active axes 0 .. L-1, L = ceil(D/2))
/// and an upper half. A datum's weight is the product of a lower-half and an upper-half weight,
/// and the sum is arranged as
///   Σ_upper U · (Σ_lower L · data),
/// so that a derivative along an upper axis merely rescales the inner sums. The multilinear
/// kernel vectorises over outputs (inner loops of compile-time length: 2^L corners, kChunk
/// outputs); the cubic kernel, whose data are stored subset-innermost, vectorises over the 2^L
/// lower-half subsets of one output, with D a compile-time constant.

#include <cstddef>

#include "runtime/table.h"

namespace wrc::runtime {

/// Largest number of lower-half (or upper-half) combinations: 2^ceil(kMaxAxes / 2).
constexpr std::size_t kMaxHalf = kMaxHalfCorners;

/// Multilinear interpolation at one point: the 2^D corners of the cell.
struct LinearTerms {
  const double* values;   ///< First output of the cell's lower corner node.
  const float* values32;  ///< The same in the float32 copy (float32 storage), else null.
  std::size_t n_outputs;
  std::size_t n_axes;
  int n_active;                   ///< D >= 1.
  int n_lower_axes;               ///< L = ceil(D / 2).
  std::size_t n_upper;            ///< 2^(D-L) upper-half corners (2^L lower ones).
  double lower_weight[kMaxHalf];  ///< ∏ over lower axes of (1 - t_j or t_j).
  double upper_weight[kMaxHalf];
  const std::size_t* lower_offset;  ///< Of each lower-half corner, in doubles (2^L entries).
  const std::size_t* upper_offset;  ///< Of each upper-half corner.
  /// Per active axis j: its half's weights with axis j's factor replaced by ∓1/h.
  double d_weight[kMaxAxes][kMaxHalf];
  int axis[kMaxAxes];              ///< Axis index of active axis j.
  bool derivative_zero[kMaxAxes];  ///< Clamped on active axis j: derivative 0.
};

/// Cubic Hermite interpolation at one point: 2^D corners × 2^D data (subsets S) per corner.
/// A node's Hermite data are laid out [output][subset] (Table::BuildCubic), so the 2^L subsets of
/// the lower axes (subset bits 0 .. L-1) of one output and upper subset are contiguous: the
/// kernel reads them as one vector and weights them by a vector of lower-half weights. The
/// weight of corner c and subset s is ∏ over the axes j of basis[j][2·c_j + s_j]; the kernel
/// forms these products itself, with D known at compile time.
struct CubicTerms {
  const double* base;   ///< Hermite data of the cell's lower corner node, first output.
  const float* base32;  ///< The same in the float32 copy (float32 storage), else null.
  std::size_t n_outputs;
  std::size_t n_axes;
  int n_active;
  const std::size_t* lower_offset;  ///< Of each lower-half corner, in doubles (2^L entries).
  const std::size_t* upper_offset;  ///< Of each upper-half corner (2^(D-L) entries).
  /// Per active axis at t_j: (h00, h·h10, h01, h·h11) and their derivatives in x_j (the latter
  /// only read when derivatives are asked for).
  double basis[kMaxAxes][4];
  double d_basis[kMaxAxes][4];
  int axis[kMaxAxes];
  bool derivative_zero[kMaxAxes];
};

/// Writes out (n_outputs values) and, unless d_out is null, the active axes' entries of d_out
/// (other entries untouched; callers zero them).
/// The *32 kernels read the float32 copies (values32, base32) and sum in double.
struct Kernels {
  void (*linear)(const LinearTerms& terms, double* out, double* d_out);
  void (*cubic)(const CubicTerms& terms, double* out, double* d_out);
  void (*linear32)(const LinearTerms& terms, double* out, double* d_out);
  void (*cubic32)(const CubicTerms& terms, double* out, double* d_out);
};

namespace generic {
extern const Kernels kKernels;
}
#if defined(WRC_RUNTIME_X86_64_V3)
namespace x86_64_v3 {
extern const Kernels kKernels;
}
#endif

/// The fastest kernels this CPU runs.
const Kernels& SelectKernels();

}  // namespace wrc::runtime
