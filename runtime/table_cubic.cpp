// Cubic mode: tensor-product cubic Hermite interpolation with monotonicity-preserving slopes.
//
// Node data. Along one grid line, the slope at node j is first estimated by differentiating the
// interpolating polynomial through the (up to) five nearest nodes, a window centred on j where
// the axis allows (degree 4: exact for cubics, on any spacing, also at the ends). It is then
// limited (Fritsch–Carlson, in the simple box form of Hyman 1983) with the secants d⁻, d⁺ of
// the two adjacent cells:
//   - d⁻·d⁺ <= 0 (data extremum or a flat side): slope 0;
//   - slope against the direction of the data: 0;
//   - otherwise |slope| <= 3·min(|d⁻|, |d⁺|) (at an end node: 3·|d|).
// With both end slopes of a cell in [0, 3d] the cubic on that cell is monotone, so along every
// grid line the interpolant stays between the cell's two node values: no overshoot at contact
// jumps, and flat (no-contact) plateaus stay flat. Where the data are monotone-consistent (the
// estimate has the secants' sign and lies within the bound) the estimate is used unchanged, and
// a function that is cubic along the axis is reproduced exactly. At data extrema the limiter sets
// the slope to 0: there exactness is traded for the no-overshoot property (the error is then
// at most h·|f'(node)|·4/27 per cell, 4/27 = max|h10|); tests/runtime states both.
//
// In N dimensions each node stores, per output, the value and all mixed derivatives
// D_S f = ∂^|S| f / ∏_{j∈S} ∂x_j for every subset S of the active axes, obtained by applying the
// limited slope operator along the axes of S in increasing order to the value field. The tensor-
// product Hermite interpolant of that data is C¹ everywhere in the table (on a cell face, the
// function and its derivatives depend only on the data at the nodes of that face) and reproduces
// functions that are cubic along each axis wherever no limiter acts. The cost is 2^D numbers per
// node and output, built when a handle is switched to cubic mode (Table::SetInterpolation: the
// one allocation of cubic mode; evaluation allocates nothing).
//
// Node data are stored [node][output][subset], starting on a cache-line boundary: the data of
// one output at one node (2^D doubles, 128 bytes for 4 axes) are contiguous, and the kernel
// (kernels.inc) reads the subsets of the lower half of the axes as one vector. Evaluation sums
// the 4^D terms (two nodes × {value, slope} per axis); the kernel forms the weights from the
// per-axis Hermite bases computed here. A lookup on a 4-D table with 6 outputs reads 16 nodes ×
// 16 × 6 doubles = 12 KiB, which dominates its cost when the cells are not cached. Scratch space
// is fixed-size on the stack; nothing is allocated.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "runtime/interp/cubic_line.h"
#include "runtime/kernels.h"
#include "runtime/table.h"

namespace wrc::runtime {
namespace {

using cubic::kWindow;
using cubic::WindowStart;

// Limited slopes of one grid line (cubic::NodeSlope at every node).
void LineSlopes(const double* x, int n, const double* f, double* slope) {
  for (int j = 0; j < n; ++j) slope[j] = cubic::NodeSlope(x, n, f, j);
}

}  // namespace

void Table::BuildCubic() {
  const int n_active = static_cast<int>(active_axes_.size());
  const std::size_t n_out = outputs_.size();
  const std::size_t n_subsets = std::size_t{1} << n_active;
  const std::size_t block = n_subsets * n_out;
  // Layout [node][output][subset]: the kernels read the lower-axes subsets of one output as one
  // vector (kernels.inc). kLineDoubles of slack let the data start on a cache-line boundary, so
  // that a node's block (a multiple of 64 bytes for 4 axes and 6 outputs) spans as few lines as
  // possible.
  constexpr std::size_t kLineDoubles = 64 / sizeof(double);
  NodeMemory<double> data(num_nodes_ * block + kLineDoubles);
  const std::size_t misalignment =
      reinterpret_cast<std::uintptr_t>(data.data()) / sizeof(double) % kLineDoubles;
  const std::size_t start = (kLineDoubles - misalignment) % kLineDoubles;
  const auto at = [&](std::size_t node, std::size_t k, std::size_t subset) -> double& {
    return data[start + node * block + k * n_subsets + subset];
  };
  for (std::size_t node = 0; node < num_nodes_; ++node) {
    for (std::size_t k = 0; k < n_out; ++k) at(node, k, 0) = values_[node * n_out + k];
  }
  std::size_t longest = 1;
  for (const Axis& axis : axes_) longest = std::max(longest, axis.values.size());
  std::vector<double> line(longest);
  std::vector<double> slopes(longest);
  for (std::size_t subset = 1; subset < n_subsets; ++subset) {
    // D_S f = L_j(D_{S∖j} f) with j the highest axis in S: axes applied in increasing order.
    int j = n_active - 1;
    while ((subset >> j & 1) == 0) --j;
    const std::size_t source = subset ^ (std::size_t{1} << j);
    const Axis& axis = axes_[static_cast<std::size_t>(active_axes_[static_cast<std::size_t>(j)])];
    const int n = static_cast<int>(axis.values.size());
    const std::size_t stride =
        node_stride_[static_cast<std::size_t>(active_axes_[static_cast<std::size_t>(j)])];
    for (std::size_t first = 0; first < num_nodes_; ++first) {
      if (first / stride % static_cast<std::size_t>(n) != 0) continue;  // Not the start of a line.
      for (std::size_t k = 0; k < n_out; ++k) {
        for (int i = 0; i < n; ++i) {
          line[static_cast<std::size_t>(i)] =
              at(first + static_cast<std::size_t>(i) * stride, k, source);
        }
        LineSlopes(axis.values.data(), n, line.data(), slopes.data());
        for (int i = 0; i < n; ++i) {
          at(first + static_cast<std::size_t>(i) * stride, k, subset) =
              slopes[static_cast<std::size_t>(i)];
        }
      }
    }
  }

  CornerOffsets(block, cubic_offset_);

  // Status flags per cell: every node inside the slope windows of the cell's corners enters the
  // result; the window ranges of the two corners along each axis are OR-ed, axis by axis.
  std::vector<std::uint8_t> flags(num_nodes_);
  for (std::size_t node = 0; node < num_nodes_; ++node) {
    flags[node] = status_[node] != 0 ? kCellStatus : 0;
  }
  std::vector<std::uint8_t> dilated(num_nodes_);
  for (int a : active_axes_) {
    const int n = static_cast<int>(axes_[static_cast<std::size_t>(a)].values.size());
    const std::size_t stride = node_stride_[static_cast<std::size_t>(a)];
    const int width = std::min(kWindow, n);
    for (std::size_t node = 0; node < num_nodes_; ++node) {
      const int i = static_cast<int>(node / stride % static_cast<std::size_t>(n));
      const int upper = std::min(i + 1, n - 1);
      const int lo =
          WindowStart(i, std::max(0, i - (kWindow - 1)), std::min(n - 1, i + kWindow - 1));
      const int hi = WindowStart(upper, std::max(0, upper - (kWindow - 1)),
                                 std::min(n - 1, upper + kWindow - 1)) +
                     width - 1;
      std::uint8_t combined = 0;
      for (int m = lo; m <= hi; ++m) {
        combined |= flags[node + static_cast<std::size_t>(m) * stride -
                          static_cast<std::size_t>(i) * stride];
      }
      dilated[node] = combined;
    }
    flags.swap(dilated);
  }
  for (std::size_t node = 0; node < num_nodes_; ++node) {
    flags[node] |= linear_flags_[node] & kCellNonFinite;
  }
  hermite_ = std::move(data);  // The buffer, hence its alignment, moves along.
  hermite_start_ = start;
  cubic_flags_.swap(flags);
}

void Table::EvalCubic(const Located& located, double* out, double* d_out) const noexcept {
  CubicTerms terms;
  terms.n_outputs = outputs_.size();
  terms.n_axes = axes_.size();
  terms.n_active = static_cast<int>(active_axes_.size());
  const std::size_t block = (std::size_t{1} << terms.n_active) * terms.n_outputs;
  const bool float32 = storage_ == WRC_STORAGE_FLOAT32;
  const std::size_t first = hermite_start_ + located.base_node * block;
  terms.base = float32 ? nullptr : hermite_.data() + first;
  terms.base32 = float32 ? hermite32_.data() + first : nullptr;
  if (d_out != nullptr) {
    for (std::size_t i = 0; i < terms.n_outputs * terms.n_axes; ++i) d_out[i] = 0.0;
  }
  if (terms.n_active == 0) {  // A single node.
    for (std::size_t k = 0; k < terms.n_outputs; ++k) {
      out[k] = float32 ? static_cast<double>(terms.base32[k]) : terms.base[k];
    }
    return;
  }
  terms.lower_offset = cubic_offset_[0];
  terms.upper_offset = cubic_offset_[1];
  for (int j = 0; j < terms.n_active; ++j) {
    const double t = located.cell[j].t;
    const double t2 = t * t;
    cubic::HermiteBasis(t, located.cell[j].step, terms.basis[j]);
    terms.axis[j] = active_axes_[static_cast<std::size_t>(j)];
    terms.derivative_zero[j] = located.derivative_zero[j];
    if (d_out == nullptr) continue;
    const double inverse_h = located.cell[j].inverse_step;
    double* d_basis = terms.d_basis[j];
    d_basis[0] = (6.0 * t2 - 6.0 * t) * inverse_h;
    d_basis[1] = 3.0 * t2 - 4.0 * t + 1.0;
    d_basis[2] = (6.0 * t - 6.0 * t2) * inverse_h;
    d_basis[3] = 3.0 * t2 - 2.0 * t;
  }
  (float32 ? kernels_->cubic32 : kernels_->cubic)(terms, out, d_out);
}

}  // namespace wrc::runtime
