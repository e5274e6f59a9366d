// Point location and multilinear interpolation. Nothing here allocates: all scratch space is
// fixed-size on the stack (bounded by kMaxAxes).

#include <algorithm>
#include <cmath>

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
  for (int a = 0; a < n_axes; ++a) {
    if (std::isnan(point[a])) return ReportNan(a);
  }
  int flags = 0;
  std::size_t base_node = 0;
  const int n_active = static_cast<int>(active_axes_.size());
  for (int j = 0; j < n_active; ++j) {
    const AxisLookup& axis = lookup_[j];
    const double* v = axis.nodes;
    const int n = axis.size;
    double x = point[active_axes_[static_cast<std::size_t>(j)]];
    bool outside = false;
    if (x < v[0]) {
      x = v[0];
      outside = true;
    } else if (x > v[n - 1]) {
      x = v[n - 1];
      outside = true;
    }
    if (outside) flags |= WRC_FLAG_CLAMPED;
    located.derivative_zero[j] = outside;  // The returned f(clamp(x)) is flat out there.
    int i = 0;
    if (axis.nearly_uniform) {
      // x is inside [v[0], v[n-1]] now, so the guess is finite and non-negative.
      i = static_cast<int>((x - v[0]) * axis.inverse_mean_step);
      if (i > n - 2) i = n - 2;
      while (i > 0 && x < v[i]) --i;
      while (i < n - 2 && x >= v[i + 1]) ++i;
    } else {
      i = static_cast<int>(std::upper_bound(v, v + n, x) - v) - 1;
      i = std::clamp(i, 0, n - 2);
    }
    CellCoordinate& cell = located.cell[j];
    cell.index = i;
    cell.step = v[i + 1] - v[i];
    cell.inverse_step = axis.inverse_steps[i];
    // Multiplying by the stored inverse may round (x - v[i]) / h just past 1 or, at the last
    // node, just below it; the end nodes must give t exactly 0 and 1 so that node values come
    // out exact.
    const double t = (x - v[i]) * cell.inverse_step;
    cell.t = x >= v[i + 1] ? 1.0 : (t < 1.0 ? t : 1.0);
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

void Table::EvalLinear(const Located& located, double* out, double* d_out) const noexcept {
  LinearTerms terms;
  terms.n_outputs = outputs_.size();
  terms.n_axes = axes_.size();
  terms.values = values_.data() + located.base_node * terms.n_outputs;
  terms.n_active = static_cast<int>(active_axes_.size());
  if (d_out != nullptr) {
    for (std::size_t i = 0; i < terms.n_outputs * terms.n_axes; ++i) d_out[i] = 0.0;
  }
  if (terms.n_active == 0) {  // A single node.
    for (std::size_t k = 0; k < terms.n_outputs; ++k) out[k] = terms.values[k];
    return;
  }
  terms.n_lower_axes = (terms.n_active + 1) / 2;
  terms.n_upper = std::size_t{1} << (terms.n_active - terms.n_lower_axes);
  // Corner weights of the active axes [begin, end): the outer product of (1 - t_j, t_j), with
  // the factor of axis `differentiated` (if in range) replaced by (-1/h, 1/h).
  const auto corner_weights = [&](int begin, int end, int differentiated, double* weight) {
    weight[0] = 1.0;
    for (int j = begin; j < end; ++j) {
      const std::size_t half = std::size_t{1} << (j - begin);
      const double t = located.cell[j].t;
      const double inverse_step = located.cell[j].inverse_step;
      const bool derivative = j == differentiated;
      const double upper = derivative ? inverse_step : t;
      const double lower = derivative ? -inverse_step : 1.0 - t;
      for (std::size_t c = 0; c < half; ++c) {
        weight[c + half] = weight[c] * upper;
        weight[c] *= lower;
      }
    }
  };
  const auto corner_offsets = [&](int begin, int end, std::size_t* offset) {
    offset[0] = 0;
    for (int j = begin; j < end; ++j) {
      const std::size_t half = std::size_t{1} << (j - begin);
      const std::size_t step = lookup_[j].node_stride * terms.n_outputs;
      for (std::size_t c = 0; c < half; ++c) offset[c + half] = offset[c] + step;
    }
  };
  corner_weights(0, terms.n_lower_axes, kMaxAxes, terms.lower_weight);  // No derivative.
  corner_weights(terms.n_lower_axes, terms.n_active, kMaxAxes, terms.upper_weight);
  corner_offsets(0, terms.n_lower_axes, terms.lower_offset);
  corner_offsets(terms.n_lower_axes, terms.n_active, terms.upper_offset);
  if (d_out != nullptr) {
    for (int j = 0; j < terms.n_active; ++j) {
      terms.axis[j] = active_axes_[static_cast<std::size_t>(j)];
      terms.derivative_zero[j] = located.derivative_zero[j];
      if (j < terms.n_lower_axes) {
        corner_weights(0, terms.n_lower_axes, j, terms.d_weight[j]);
      } else {
        corner_weights(terms.n_lower_axes, terms.n_active, j, terms.d_weight[j]);
      }
    }
  }
  kernels_->linear(terms, out, d_out);
}

int Table::CheckFinite(int flags, const double* out, const double* d_out) const noexcept {
  const std::size_t n_out = outputs_.size();
  for (std::size_t k = 0; k < n_out; ++k) {
    bool finite = std::isfinite(out[k]);
    if (d_out != nullptr) {
      for (std::size_t a = 0; a < axes_.size(); ++a)
        finite &= std::isfinite(d_out[k * axes_.size() + a]);
    }
    if (!finite) {
      SetLastError(
          "wrc_table_eval: %s: output '%s' has no finite value here: a node of the cell holds "
          "NaN (a failed solve, /status != 0)",
          path_.c_str(), outputs_[k].name.c_str());
      return WRC_ERR_NO_DATA;
    }
  }
  return flags;
}

int Table::Eval(const double* point, double* out, double* d_out) const noexcept {
  Located located;
  const int located_code = Locate(point, located);
  if (located_code < 0) return located_code;
  std::uint8_t cell_flags = 0;
  if (interpolation_ == WRC_INTERP_CUBIC) {
    EvalCubic(located, out, d_out);
    cell_flags = cubic_flags_[located.base_node];
  } else {
    EvalLinear(located, out, d_out);
    cell_flags = linear_flags_[located.base_node];
  }
  const int flags = located.flags | (cell_flags & kCellStatus);
  if ((cell_flags & kCellNonFinite) != 0) return CheckFinite(flags, out, d_out);
  return flags;
}

void Table::SetInterpolation(int mode) {
  if (mode == WRC_INTERP_CUBIC && hermite_.empty()) BuildCubic();
  interpolation_ = mode;
}

}  // namespace wrc::runtime
