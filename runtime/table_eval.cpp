// Point location and multilinear interpolation. Nothing here allocates: all scratch space is
// fixed-size on the stack (bounded by kMaxAxes).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

#include "runtime/kernels.h"
#include "runtime/table.h"

namespace wrc::runtime {

int Table::ReportNan(int axis) const noexcept {
  SetLastError("wrc_table_eval: %s: point[%d] (axis '%s') is NaN", path_.c_str(), axis,
               axes_[static_cast<std::size_t>(axis)].name.c_str());
  return WRC_ERR_NAN_INPUT;
}

int Table::Locate(const double* point, Located& located) const noexcept {
  const int n_axes = num_axes();
  bool nan = false;  // One branch for all axes; the rare error path finds which one.
  for (int a = 0; a < n_axes; ++a) nan |= std::isnan(point[a]);
  if (nan) {
    for (int a = 0; a < n_axes; ++a) {
      if (std::isnan(point[a])) return ReportNan(a);
    }
  }
  int flags = 0;
  std::size_t base_node = 0;
  const int n_active = static_cast<int>(active_axes_.size());
  for (int j = 0; j < n_active; ++j) {
    const AxisLookup& axis = lookup_[j];
    const double* v = axis.nodes;
    const int n = axis.size;
    const double raw = point[axis.axis];
    // Clamped without branches (minsd/maxsd): out-of-range points are rare but not predictable.
    const double x = std::min(std::max(raw, axis.first), axis.last);
    const bool outside = x != raw;
    flags |= outside ? WRC_FLAG_CLAMPED : 0;
    located.derivative_zero[j] = outside;  // The returned f(clamp(x)) is flat out there.
    int i = 0;
    if (axis.nearly_uniform) {
      // x is inside [first, last] now, so the guess is finite and non-negative; it is at most one
      // cell off (table_load.cpp), and the loops below almost never run.
      i = std::min(static_cast<int>((x - axis.first) * axis.inverse_mean_step), n - 2);
      while (i > 0 && x < v[i]) --i;
      while (i < n - 2 && x >= v[i + 1]) ++i;
    } else {
      // x is inside [first, last], so the bucket exists; its cell is at or left of x's.
      const int k =
          std::min(static_cast<int>((x - axis.first) * axis.inverse_bucket_width), axis.buckets);
      i = axis.bucket_cell[k];
      while (i > 0 && x < v[i]) --i;  // k rounded up past a bucket end that is a node
      while (i < n - 2 && x >= v[i + 1]) ++i;
    }
    CellCoordinate& cell = located.cell[j];
    const double lower = v[i];
    const double upper = v[i + 1];
    cell.index = i;
    cell.step = upper - lower;
    cell.inverse_step = axis.inverse_steps[i];
    // Multiplying by the stored inverse may round (x - v[i]) / h just past 1 or, at the last
    // node, just below it; the end nodes must give t exactly 0 and 1 so that node values come
    // out exact.
    const double t = (x - lower) * cell.inverse_step;
    cell.t = x >= upper ? 1.0 : std::min(t, 1.0);
    base_node += static_cast<std::size_t>(i) * axis.node_stride;
  }
  if (n_active != n_axes) {  // Axes with a single node: only that coordinate is inside.
    for (int a = 0; a < n_axes; ++a) {
      const Axis& axis = axes_[static_cast<std::size_t>(a)];
      if (axis.values.size() == 1 && point[a] != axis.values[0]) flags |= WRC_FLAG_CLAMPED;
    }
  }
  located.flags = flags;
  located.base_node = base_node;
  return 0;
}

namespace {

// weight[c] = ∏_{j < kCount} (bit j of c ? upper[j] : lower[j]). A compile-time count unrolls
// the loops completely (with a run-time count the compiler vectorises these tiny loops, with
// prologues and epilogues that cost more than the products).
template <int kCount>
inline void CornerWeights(const double* lower, const double* upper, double* weight) {
  weight[0] = 1.0;
  for (int j = 0; j < kCount; ++j) {
    const int half = 1 << j;
    for (int c = 0; c < half; ++c) {
      weight[c + half] = weight[c] * upper[j];
      weight[c] *= lower[j];
    }
  }
}

void CornerWeights(int count, const double* lower, const double* upper, double* weight) {
  static_assert((kMaxAxes + 1) / 2 <= 4, "CornerWeights covers at most 4 axes");
  switch (count) {
    case 0:
      weight[0] = 1.0;
      break;
    case 1:
      CornerWeights<1>(lower, upper, weight);
      break;
    case 2:
      CornerWeights<2>(lower, upper, weight);
      break;
    case 3:
      CornerWeights<3>(lower, upper, weight);
      break;
    default:
      CornerWeights<4>(lower, upper, weight);
      break;
  }
}

// A lookup in cells that are not cached waits on memory: every corner's row is asked for
// before the kernel reads the first, so that the misses overlap instead of following the
// kernel's order. (A row of 11 outputs spans two cache lines at most; its pair along the last
// axis is the next row.)
template <typename T>
void PrefetchCorners(const LinearTerms& terms, const T* values) {
  const std::size_t n_lower = std::size_t{1} << terms.n_lower_axes;
  for (std::size_t u = 0; u < terms.n_upper; ++u) {
    const T* block = values + terms.upper_offset[u];
    for (std::size_t l = 0; l < n_lower; ++l) {
      const T* row = block + terms.lower_offset[l];
      __builtin_prefetch(row);
      __builtin_prefetch(row + terms.n_outputs - 1);
    }
  }
}

}  // namespace

void Table::EvalLinear(const Located& located, double* out, double* d_out) const noexcept {
  LinearTerms terms;
  terms.n_outputs = outputs_.size();
  terms.n_axes = axes_.size();
  terms.values = values_.data() + located.base_node * terms.n_outputs;
  const bool float32 = storage_ == WRC_STORAGE_FLOAT32;
  terms.values32 = float32 ? values32_.data() + located.base_node * terms.n_outputs : nullptr;
  terms.n_active = static_cast<int>(active_axes_.size());
  if (d_out != nullptr) {
    for (std::size_t i = 0; i < terms.n_outputs * terms.n_axes; ++i) d_out[i] = 0.0;
  }
  if (terms.n_active == 0) {  // A single node.
    for (std::size_t k = 0; k < terms.n_outputs; ++k) out[k] = terms.values[k];
    return;
  }
  const int n_lower_axes = (terms.n_active + 1) / 2;
  const int n_upper_axes = terms.n_active - n_lower_axes;
  terms.n_lower_axes = n_lower_axes;
  terms.n_upper = std::size_t{1} << n_upper_axes;
  terms.lower_offset = linear_offset_[0];
  terms.upper_offset = linear_offset_[1];
  // Per axis the factors of the lower and the upper corner: 1 - t and t. (Zeroed: GCC cannot
  // see that only the first n_active entries are read.)
  double lower[kMaxAxes] = {};
  double upper[kMaxAxes] = {};
  for (int j = 0; j < terms.n_active; ++j) {
    lower[j] = 1.0 - located.cell[j].t;
    upper[j] = located.cell[j].t;
  }
  if (float32) {
    PrefetchCorners(terms, terms.values32);
  } else {
    PrefetchCorners(terms, terms.values);
  }
  CornerWeights(n_lower_axes, lower, upper, terms.lower_weight);
  CornerWeights(n_upper_axes, lower + n_lower_axes, upper + n_lower_axes, terms.upper_weight);
  if (d_out != nullptr) {
    // ∂/∂x_j: axis j's factors become -1/h and 1/h.
    for (int j = 0; j < terms.n_active; ++j) {
      terms.axis[j] = active_axes_[static_cast<std::size_t>(j)];
      terms.derivative_zero[j] = located.derivative_zero[j];
      const double saved_lower = lower[j];
      const double saved_upper = upper[j];
      lower[j] = -located.cell[j].inverse_step;
      upper[j] = located.cell[j].inverse_step;
      if (j < n_lower_axes) {
        CornerWeights(n_lower_axes, lower, upper, terms.d_weight[j]);
      } else {
        CornerWeights(n_upper_axes, lower + n_lower_axes, upper + n_lower_axes, terms.d_weight[j]);
      }
      lower[j] = saved_lower;
      upper[j] = saved_upper;
    }
  }
  (float32 ? kernels_->linear32 : kernels_->linear)(terms, out, d_out);
}

namespace {

// Corner weights of the fallback at one point and their sums over the finite corners of one
// output; the derivative sums only when asked for.
struct ValidCornerSums {
  double weight = 0.0;  // Σ w_c
  double value = 0.0;   // Σ w_c f_c
  double d_weight[kMaxAxes] = {};
  double d_value[kMaxAxes] = {};
};

// Σ over the cell's corners c whose datum values[offset_c] is finite, with corner weights
// w_c = ∏_j (bit j of c ? t_j : 1 - t_j) and their derivatives along each active axis.
ValidCornerSums SumValidCorners(const double* values, const std::size_t* corner_offset,
                                int n_active, const double* t, const double* inverse_step,
                                bool derivatives) {
  ValidCornerSums sums;
  const std::size_t n_corners = std::size_t{1} << n_active;
  for (std::size_t c = 0; c < n_corners; ++c) {
    const double f = values[corner_offset[c]];
    if (!std::isfinite(f)) continue;
    double w = 1.0;
    for (int j = 0; j < n_active; ++j) w *= (c >> j & 1) != 0 ? t[j] : 1.0 - t[j];
    sums.weight += w;
    sums.value += w * f;
    if (!derivatives) continue;
    for (int j = 0; j < n_active; ++j) {
      // ∂w_c/∂x_j: axis j's factor becomes ±1/h.
      double dw = (c >> j & 1) != 0 ? inverse_step[j] : -inverse_step[j];
      for (int m = 0; m < n_active; ++m) {
        if (m != j) dw *= (c >> m & 1) != 0 ? t[m] : 1.0 - t[m];
      }
      sums.d_weight[j] += dw;
      sums.d_value[j] += dw * f;
    }
  }
  return sums;
}

}  // namespace

int Table::EvalValidCorners(const Located& located, int flags, double* out,
                            double* d_out) const noexcept {
  const std::size_t n_out = outputs_.size();
  const std::size_t n_axes = axes_.size();
  const int n_active = static_cast<int>(active_axes_.size());
  const double* cell = values_.data() + located.base_node * n_out;
  if (d_out != nullptr) {
    for (std::size_t i = 0; i < n_out * n_axes; ++i) d_out[i] = 0.0;
  }
  // Offsets of the 2^D corners from the lower one (bit j of c: upper node on active axis j).
  std::size_t corner_offset[std::size_t{1} << kMaxAxes];
  corner_offset[0] = 0;
  for (int j = 0; j < n_active; ++j) {
    const std::size_t half = std::size_t{1} << j;
    for (std::size_t c = 0; c < half; ++c) {
      corner_offset[c + half] = corner_offset[c] + lookup_[j].node_stride * n_out;
    }
  }
  double t[kMaxAxes] = {};
  double edge_t[kMaxAxes] = {};
  double inverse_step[kMaxAxes] = {};
  for (int j = 0; j < n_active; ++j) {
    t[j] = located.cell[j].t;
    // Only where every corner of non-zero weight failed (the point on a face or at a node of
    // failed corners): t kept 1e-6 inside the cell gives each finite corner a weight of at
    // least 1e-6^8 = 1e-48, far above underflow, so the nearest finite corners decide.
    constexpr double kInside = 1e-6;
    edge_t[j] = std::clamp(t[j], kInside, 1.0 - kInside);
    inverse_step[j] = located.cell[j].inverse_step;
  }
  int missing = -1;  // An output whose every corner failed.
  for (std::size_t k = 0; k < n_out; ++k) {
    ValidCornerSums sums =
        SumValidCorners(cell + k, corner_offset, n_active, t, inverse_step, d_out != nullptr);
    if (sums.weight == 0.0) {
      sums = SumValidCorners(cell + k, corner_offset, n_active, edge_t, inverse_step,
                             d_out != nullptr);
    }
    if (sums.weight == 0.0) {
      missing = static_cast<int>(k);
      out[k] = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    out[k] = sums.value / sums.weight;
    if (d_out == nullptr) continue;
    for (int j = 0; j < n_active; ++j) {
      if (located.derivative_zero[j]) continue;
      const std::size_t a = static_cast<std::size_t>(active_axes_[static_cast<std::size_t>(j)]);
      // Quotient rule on Σ w f / Σ w.
      d_out[k * n_axes + a] = (sums.d_value[j] - out[k] * sums.d_weight[j]) / sums.weight;
    }
  }
  if (missing >= 0) {
    SetLastError(
        "wrc_table_eval: %s: output '%s' has no data here: every node of the cell failed "
        "(/status != 0 and NaN)",
        path_.c_str(), outputs_[static_cast<std::size_t>(missing)].name.c_str());
    return WRC_ERR_NO_DATA;
  }
  return flags;
}

int Table::Eval(const double* point, double* out, double* d_out) const noexcept {
  Located located;
  const int located_code = Locate(point, located);
  if (located_code < 0) return located_code;
  const bool cubic = interpolation_ == WRC_INTERP_CUBIC;
  const std::uint8_t cell_flags =
      cubic ? cubic_flags_[located.base_node] : linear_flags_[located.base_node];
  const int flags = located.flags | (cell_flags & kCellStatus);
  // A cell with a failed corner takes the slow path in both modes; all others the kernels.
  if ((cell_flags & kCellNonFinite) != 0) return EvalValidCorners(located, flags, out, d_out);
  if (cubic) {
    EvalCubic(located, out, d_out);
  } else {
    EvalLinear(located, out, d_out);
  }
  return flags;
}

namespace {

NodeMemory<float> FloatCopy(const NodeMemory<double>& from) {
  NodeMemory<float> copy(from.size());
  for (std::size_t i = 0; i < from.size(); ++i) copy[i] = static_cast<float>(from[i]);
  return copy;
}

}  // namespace

// The cubic data exist in one storage at a time: a table switched to float32 keeps only the
// float copy (half the memory; they are the largest data of a cubic table).
void Table::SetInterpolation(int mode) {
  if (mode == WRC_INTERP_CUBIC && hermite_.empty() && hermite32_.empty()) {
    BuildCubic();
    if (storage_ == WRC_STORAGE_FLOAT32) hermite32_ = FloatCopy(std::exchange(hermite_, {}));
  }
  interpolation_ = mode;
}

void Table::SetStorage(int storage) {
  if (storage == WRC_STORAGE_FLOAT32) {
    if (values32_.empty()) values32_ = FloatCopy(values_);
    if (!hermite_.empty()) hermite32_ = FloatCopy(std::exchange(hermite_, {}));
  } else {
    values32_ = {};
    if (!hermite32_.empty()) {
      hermite32_ = {};
      BuildCubic();
    }
  }
  storage_ = storage;
}

}  // namespace wrc::runtime
