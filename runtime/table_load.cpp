// A table file (either format: runtime/format/table_content.h) indexed for lookups.

#include <algorithm>
#include <cmath>

#include "runtime/format/table_content.h"
#include "runtime/hdf5/table_schema.h"
#include "runtime/kernels.h"
#include "runtime/table.h"

namespace wrc::runtime {
namespace {

constexpr auto kOkStatus = static_cast<std::int8_t>(schema::StoredStatus::kOk);

// Buckets of equal width over a non-uniform axis, each holding the cell of its left end: Eval
// finds a cell from one multiplication and a walk over the nodes inside the bucket. Buckets no
// wider than the smallest step (up to 64 per node) make that walk at most one node long, which
// keeps a refined axis as fast to search as a uniform one.
void IndexBuckets(Axis& axis) {
  const std::size_t n = axis.values.size();
  double smallest = axis.values[1] - axis.values[0];
  for (std::size_t i = 2; i < n; ++i)
    smallest = std::min(smallest, axis.values[i] - axis.values[i - 1]);
  const double range = axis.values[n - 1] - axis.values[0];
  const double wanted = std::ceil(range / smallest);
  const std::size_t buckets =
      static_cast<std::size_t>(std::clamp(wanted, 1.0, 64.0 * static_cast<double>(n)));
  axis.inverse_bucket_width = static_cast<double>(buckets) / range;
  axis.bucket_cell.resize(buckets + 1);
  std::size_t cell = 0;
  for (std::size_t k = 0; k <= buckets; ++k) {
    const double x = axis.values[0] + static_cast<double>(k) / axis.inverse_bucket_width;
    while (cell + 2 < n && axis.values[cell + 1] <= x) ++cell;
    axis.bucket_cell[k] = static_cast<int>(cell);
  }
}

// An axis of checked nodes with what locating a coordinate on it needs.
Axis IndexedAxis(format::AxisContent content) {
  Axis axis;
  axis.name = std::move(content.name);
  axis.unit = std::move(content.unit);
  axis.values = std::move(content.values);
  const std::size_t n = axis.values.size();
  if (n < 2) return axis;
  const double mean_step = (axis.values[n - 1] - axis.values[0]) / static_cast<double>(n - 1);
  double max_deviation = 0.0;
  for (std::size_t i = 1; i < n; ++i) {
    max_deviation =
        std::max(max_deviation, std::abs(axis.values[i] - axis.values[i - 1] - mean_step));
  }
  // Node i deviates from first + i·mean_step by at most n·max_deviation; when that is under
  // half a step, the index computed from the mean step is off by at most one cell and a short
  // walk finds the cell. Otherwise Eval uses binary search.
  axis.nearly_uniform = max_deviation * static_cast<double>(n) <= 0.5 * mean_step;
  axis.inverse_mean_step = 1.0 / mean_step;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    axis.inverse_steps.push_back(1.0 / (axis.values[i + 1] - axis.values[i]));
  }
  if (!axis.nearly_uniform) IndexBuckets(axis);
  return axis;
}

}  // namespace

void Table::IndexAxes() {
  // Node layout: row-major, the last axis varies fastest (HDF5's order).
  const std::size_t n_axes = axes_.size();
  node_stride_.assign(n_axes, 1);
  for (std::size_t a = n_axes - 1; a > 0; --a) {
    node_stride_[a - 1] = node_stride_[a] * axes_[a].values.size();
  }
  num_nodes_ = node_stride_[0] * axes_[0].values.size();
  active_axes_.clear();
  for (std::size_t a = 0; a < n_axes; ++a) {
    const Axis& axis = axes_[a];
    if (axis.values.size() < 2) continue;
    AxisLookup& lookup = lookup_[active_axes_.size()];
    lookup.nodes = axis.values.data();
    lookup.inverse_steps = axis.inverse_steps.data();
    lookup.first = axis.values.front();
    lookup.last = axis.values.back();
    lookup.size = static_cast<int>(axis.values.size());
    lookup.axis = static_cast<int>(a);
    lookup.nearly_uniform = axis.nearly_uniform;
    lookup.inverse_mean_step = axis.inverse_mean_step;
    lookup.bucket_cell = axis.bucket_cell.data();
    lookup.buckets = static_cast<int>(axis.bucket_cell.size()) - 1;
    lookup.inverse_bucket_width = axis.inverse_bucket_width;
    lookup.node_stride = node_stride_[a];
    active_axes_.push_back(static_cast<int>(a));
  }
  kernels_ = &SelectKernels();
}

void Table::CornerOffsets(std::size_t node_block, std::size_t (*offset)[kMaxHalfCorners]) const {
  const int n_active = static_cast<int>(active_axes_.size());
  const int n_lower_axes = (n_active + 1) / 2;
  for (int half = 0; half < 2; ++half) {
    offset[half][0] = 0;
    const int begin = half == 0 ? 0 : n_lower_axes;
    const int end = half == 0 ? n_lower_axes : n_active;
    for (int j = begin; j < end; ++j) {
      const std::size_t corners = std::size_t{1} << (j - begin);
      const std::size_t step = lookup_[j].node_stride * node_block;
      for (std::size_t c = 0; c < corners; ++c) offset[half][c + corners] = offset[half][c] + step;
    }
  }
}

Table Table::Load(const std::string& path) { return FromContent(format::ReadTableContent(path)); }

Table Table::FromContent(format::TableContent content) {
  Table table;
  table.path_ = std::move(content.path);
  table.warning_ = std::move(content.warning);
  table.attributes_ = std::move(content.attributes);
  table.numbers_ = std::move(content.numbers);
  for (format::AxisContent& axis : content.axes)
    table.axes_.push_back(IndexedAxis(std::move(axis)));
  for (format::OutputContent& output : content.outputs) {
    table.outputs_.push_back(Output{std::move(output.name), std::move(output.unit)});
  }
  table.IndexAxes();
  const std::size_t n_out = table.outputs_.size();
  // Copied into memory of its own (node_memory.h), the padding zero.
  table.values_ = NodeMemory<double>(table.num_nodes_ * n_out + kReadPadding);
  std::copy(content.values.begin(), content.values.end(), table.values_.data());
  content.values = std::vector<double>();
  table.status_ = std::move(content.status);
  table.CornerOffsets(n_out, table.linear_offset_);

  std::vector<std::uint8_t> node_flags(table.num_nodes_, 0);
  for (std::size_t node = 0; node < table.num_nodes_; ++node) {
    if (table.status_[node] != kOkStatus) node_flags[node] |= kCellStatus;
    for (std::size_t k = 0; k < n_out; ++k) {
      if (!std::isfinite(table.values_[node * n_out + k])) node_flags[node] |= kCellNonFinite;
    }
  }
  // Per-cell flags for multilinear interpolation: OR over the 2^D cell corners.
  table.linear_flags_ = node_flags;
  for (int a : table.active_axes_) {
    const std::size_t stride = table.node_stride_[static_cast<std::size_t>(a)];
    const std::size_t size = table.axes_[static_cast<std::size_t>(a)].values.size();
    for (std::size_t node = 0; node < table.num_nodes_; ++node) {
      if (node / stride % size + 1 < size)
        table.linear_flags_[node] |= table.linear_flags_[node + stride];
    }
  }
  return table;
}

}  // namespace wrc::runtime
