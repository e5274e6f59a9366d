// Loading and validation of a table file (docs/reference/table-layout.md) into a runtime::Table.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <set>
#include <sstream>

#include "runtime/hdf5/hdf5.h"
#include "runtime/hdf5/seal.h"
#include "runtime/hdf5/table_schema.h"
#include "runtime/kernels.h"
#include "runtime/table.h"

namespace wrc::runtime {
namespace {

using schema::kFormatName;
using schema::kFormatVersion;
constexpr auto kOkStatus = static_cast<std::int8_t>(schema::StoredStatus::kOk);

std::string ShapeText(const std::vector<h5::Size>& shape) {
  std::ostringstream text;
  text << '[';
  for (std::size_t i = 0; i < shape.size(); ++i) text << (i ? "," : "") << shape[i];
  text << ']';
  return text.str();
}

std::string NodeText(std::size_t node, const std::vector<Axis>& axes,
                     const std::vector<std::size_t>& stride) {
  std::ostringstream text;
  text << '(';
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const std::size_t index = node / stride[a] % axes[a].values.size();
    text << (a ? ", " : "") << axes[a].name << '=' << axes[a].values[index];
  }
  text << ')';
  return text.str();
}

// Most nodes on one axis: 2^24. Generated axes have tens to thousands of nodes; a longer one
// can only be a damaged dataspace, refused before anything is allocated for it.
constexpr h5::Size kMaxAxisNodes = h5::Size{1} << 24;

// Most nodes in a table: 2^32, 34 GB per output. Any table a machine can hold is far smaller;
// the bound keeps the node count and every offset within std::size_t.
constexpr h5::Size kMaxTableNodes = h5::Size{1} << 32;

[[noreturn]] void Invalid(const std::string& where, const std::string& problem) {
  throw TableError(WRC_ERR_FORMAT, where + ": " + problem);
}

const char* TypeName(h5::ElementType type) {
  return type == h5::ElementType::kFloat64 ? "floating point (float64)" : "integer (int8)";
}

// The stored type must be exactly the standard one (either byte order), checked before any
// read: HDF5 would otherwise convert through whatever a damaged datatype message says.
void RequireType(const h5::Dataset& dataset, h5::ElementType type, const std::string& where) {
  const h5::Datatype stored = dataset.Type();
  if (!stored.Is(type)) {
    Invalid(where, std::string("must be ") + TypeName(type) + ", is " + stored.Describe() +
                       (stored.IsStandardNumeric() ? "" : " (not a standard type)"));
  }
}

std::string OptionalStringAttribute(const h5::Object& object, const std::string& name) {
  return object.HasAttribute(name) ? object.ReadStringAttribute(name) : std::string();
}

void CheckRootAttributes(const h5::File& file) {
  const std::string where = file.FileName() + ":/";
  if (!file.HasAttribute(schema::kFormat)) {
    Invalid(where, "attribute 'format' is missing: not a wrc table");
  }
  const std::string format = file.ReadStringAttribute(schema::kFormat);
  if (format != kFormatName) {
    Invalid(where, "attribute 'format' is \"" + format + "\", expected \"" + kFormatName + "\"");
  }
  if (!file.HasAttribute(schema::kFormatVersionAttribute))
    Invalid(where, "attribute 'format_version' is missing");
  const std::int64_t version = file.ReadIntAttribute(schema::kFormatVersionAttribute);
  if (version != kFormatVersion) {
    Invalid(where, "attribute 'format_version' is " + std::to_string(version) +
                       ", this runtime reads version " + std::to_string(kFormatVersion));
  }
}

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

// A grid dataset's attribute 'dimensions' (written since tables name them) must list the axes
// of /axes 'order': a reordered 'order' with equal axis lengths would otherwise pass the shape
// check and transpose the data. Tables without the attribute are read as before.
void CheckDimensions(const h5::Dataset& dataset, const std::vector<std::string>& axis_names,
                     const std::string& where) {
  if (!dataset.HasAttribute(schema::kDimensions)) return;
  const std::vector<std::string> dimensions = dataset.ReadStringArrayAttribute(schema::kDimensions);
  if (dimensions == axis_names) return;
  std::string listed;
  for (const std::string& name : dimensions) listed += (listed.empty() ? "" : ", ") + name;
  std::string ordered;
  for (const std::string& name : axis_names) ordered += (ordered.empty() ? "" : ", ") + name;
  Invalid(where, "its dimensions are (" + listed + ") but /axes 'order' lists (" + ordered + ")");
}

// `name` in `group` is what the layout asks for: `missing` when absent, else why not (a link to
// elsewhere is refused before anything follows it).
void RequireKind(const h5::Group& group, const std::string& name, h5::LinkKind want,
                 const std::string& where, const std::string& missing) {
  const h5::LinkKind kind = group.Kind(name);
  if (kind == want) return;
  Invalid(where, kind == h5::LinkKind::kMissing
                     ? missing
                     : h5::KindMismatch(kind, want == h5::LinkKind::kGroup ? "group" : "dataset"));
}

// The node values obey the limits of include/wrc/runtime.h: finite, strictly ascending, and
// spaced so that no step, span or reciprocal overflows or loses the position within a cell.
void CheckAxisValues(const std::vector<double>& values, const std::string& where) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::ostringstream problem;
    problem.precision(17);
    if (!std::isfinite(values[i])) {
      problem << "value " << i << " is not finite";
    } else if (std::abs(values[i]) > WRC_AXIS_MAX_MAGNITUDE) {
      problem << "value " << i << " (" << values[i] << ") is beyond ±" << WRC_AXIS_MAX_MAGNITUDE;
    } else if (i > 0 && !(values[i] > values[i - 1])) {
      problem << "values must be strictly ascending, but value " << i << " (" << values[i]
              << ") follows " << values[i - 1];
    } else if (i > 0) {
      const double step = values[i] - values[i - 1];
      const double magnitude = std::max(std::abs(values[i]), std::abs(values[i - 1]));
      if (step < WRC_AXIS_MIN_STEP || step < WRC_AXIS_MIN_RELATIVE_STEP * magnitude) {
        problem << "values " << i - 1 << " and " << i << " (" << values[i - 1] << ", " << values[i]
                << ") are too close: a step must be at least " << WRC_AXIS_MIN_STEP << " and "
                << WRC_AXIS_MIN_RELATIVE_STEP << " of the values' magnitude";
      }
    }
    if (!problem.str().empty()) Invalid(where, problem.str());
  }
}

Axis ReadAxis(const h5::Group& axes_group, const std::string& name) {
  const std::string where = axes_group.FileName() + ":/axes/" + name;
  if (name.empty() || name.find('/') != std::string::npos) {
    Invalid(axes_group.Where(), "axis name \"" + name + "\" in 'order' is not a valid name");
  }
  RequireKind(axes_group, name, h5::LinkKind::kDataset, where,
              "listed in /axes 'order' but there is no such dataset");
  const h5::Dataset dataset = axes_group.OpenDataset(name);
  const std::vector<h5::Size> shape = dataset.Shape();
  if (shape.size() != 1) Invalid(where, "must be 1-D, has shape " + ShapeText(shape));
  if (shape[0] < 1) Invalid(where, "is empty");
  if (shape[0] > kMaxAxisNodes) {
    Invalid(where, "has " + std::to_string(shape[0]) + " nodes, more than the " +
                       std::to_string(kMaxAxisNodes) + " a table axis may have");
  }
  RequireType(dataset, h5::ElementType::kFloat64, where);
  Axis axis;
  axis.name = name;
  axis.unit = OptionalStringAttribute(dataset, schema::kUnit);
  axis.values = dataset.Read<double>();
  CheckAxisValues(axis.values, where);
  const std::size_t n = axis.values.size();
  if (n >= 2) {
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
  }
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

Table Table::Load(const std::string& path) {
  std::error_code ignored;
  if (!std::filesystem::exists(path, ignored)) {
    throw TableError(WRC_ERR_FILE, path + ": no such file");
  }
  // HDF5 would block on a FIFO and read a device without end: regular files only.
  if (!std::filesystem::is_regular_file(path, ignored)) {
    throw TableError(WRC_ERR_FILE, path + ": not a regular file");
  }
  const auto lock = h5::LibraryLock();
  std::optional<h5::File> opened;
  try {
    opened.emplace(h5::File::Open(path));
  } catch (const h5::SealError& error) {
    throw TableError(WRC_ERR_FORMAT, std::string(error.what()));
  } catch (const h5::EarliestFormatError& error) {
    throw TableError(WRC_ERR_FORMAT, std::string(error.what()));
  } catch (const h5::Error& error) {
    throw TableError(WRC_ERR_FILE, std::string(error.what()));
  }
  const h5::File& file = *opened;
  const std::string where = path + ":";
  CheckRootAttributes(file);

  Table table;
  table.path_ = path;
  if (!file.Sealed()) {
    table.warning_ = path +
                     ": not sealed (written before tables carried a SHA-256 of their bytes), so "
                     "damage is found only as HDF5 reads it; seal it with `wrc upgrade " +
                     path + " -o NEW.h5`";
  }
  for (const std::string& name : file.AttributeNames()) {
    const h5::Attribute attribute = file.OpenAttribute(name);
    if (attribute.Type().Class() == h5::TypeClass::kString &&
        attribute.Space().NumElements() == 1) {
      table.attributes_[name] = attribute.ReadString();
    }
  }

  // Axes, in the order the /axes attribute 'order' gives.
  RequireKind(file, schema::kAxes, h5::LinkKind::kGroup, where + "/axes", "group is missing");
  const h5::Group axes_group = file.OpenGroup(schema::kAxes);
  if (!axes_group.HasAttribute(schema::kOrder))
    Invalid(where + "/axes", "attribute 'order' is missing");
  const std::vector<std::string> axis_names = axes_group.ReadStringArrayAttribute(schema::kOrder);
  if (axis_names.empty()) Invalid(where + "/axes", "attribute 'order' lists no axes");
  if (axis_names.size() > static_cast<std::size_t>(kMaxAxes)) {
    Invalid(where + "/axes", "attribute 'order' lists " + std::to_string(axis_names.size()) +
                                 " axes, at most " + std::to_string(kMaxAxes) + " are supported");
  }
  std::set<std::string> seen;
  for (const std::string& name : axis_names) {
    if (!seen.insert(name).second) {
      Invalid(where + "/axes", "attribute 'order' lists \"" + name + "\" twice");
    }
    table.axes_.push_back(ReadAxis(axes_group, name));
  }
  std::vector<h5::Size> grid_shape;
  h5::Size num_nodes = 1;
  for (const Axis& axis : table.axes_) {
    grid_shape.push_back(axis.values.size());
    // Multiplied without overflow: a product that wrapped would size the data wrongly.
    if (axis.values.size() > kMaxTableNodes / num_nodes) {
      Invalid(where + "/axes", "axes of lengths " + ShapeText(grid_shape) +
                                   " (and any after them) make more than " +
                                   std::to_string(kMaxTableNodes) + " nodes");
    }
    num_nodes *= axis.values.size();
  }

  table.IndexAxes();

  // Outputs: the /outputs attribute 'order' when present, else the group's member order.
  RequireKind(file, schema::kOutputs, h5::LinkKind::kGroup, where + "/outputs", "group is missing");
  const h5::Group outputs_group = file.OpenGroup(schema::kOutputs);
  std::vector<std::string> output_names = outputs_group.MemberNames();
  if (outputs_group.HasAttribute(schema::kOrder)) {
    std::vector<std::string> ordered = outputs_group.ReadStringArrayAttribute(schema::kOrder);
    std::vector<std::string> sorted_members = output_names;
    std::vector<std::string> sorted_order = ordered;
    std::sort(sorted_members.begin(), sorted_members.end());
    std::sort(sorted_order.begin(), sorted_order.end());
    if (sorted_members != sorted_order) {
      Invalid(where + "/outputs", "attribute 'order' does not list exactly the datasets present");
    }
    output_names = std::move(ordered);
  }
  if (output_names.empty()) Invalid(where + "/outputs", "holds no outputs");
  const std::size_t n_out = output_names.size();
  if (table.num_nodes_ > std::numeric_limits<std::size_t>::max() / 8 / n_out) {
    Invalid(where + "/outputs", "table too large for this machine");
  }
  table.values_.assign(table.num_nodes_ * n_out + kReadPadding, 0.0);
  table.CornerOffsets(n_out, table.linear_offset_);
  for (std::size_t k = 0; k < n_out; ++k) {
    const std::string& name = output_names[k];
    const std::string output_where = where + "/outputs/" + name;
    RequireKind(outputs_group, name, h5::LinkKind::kDataset, output_where, "missing");
    const h5::Dataset dataset = outputs_group.OpenDataset(name);
    const std::vector<h5::Size> shape = dataset.Shape();
    if (shape != grid_shape) {
      Invalid(output_where, "shape " + ShapeText(shape) +
                                " does not match the axis lengths in /axes 'order' " +
                                ShapeText(grid_shape));
    }
    RequireType(dataset, h5::ElementType::kFloat64, output_where);
    CheckDimensions(dataset, axis_names, output_where);
    const std::vector<double> values = dataset.Read<double>();
    for (std::size_t node = 0; node < table.num_nodes_; ++node) {
      table.values_[node * n_out + k] = values[node];
    }
    table.outputs_.push_back(Output{name, OptionalStringAttribute(dataset, schema::kUnit)});
  }

  // Status of every node.
  RequireKind(file, schema::kStatus, h5::LinkKind::kDataset, where + "/status",
              "dataset is missing");
  const h5::Dataset status = file.OpenDataset(schema::kStatus);
  if (status.Shape() != grid_shape) {
    Invalid(where + "/status", "shape " + ShapeText(status.Shape()) +
                                   " does not match the axis lengths " + ShapeText(grid_shape));
  }
  RequireType(status, h5::ElementType::kInt8, where + "/status");
  CheckDimensions(status, axis_names, where + "/status");
  table.status_ = status.Read<std::int8_t>();

  // A node that solved fine must carry finite numbers; failed nodes may hold NaN, which Eval
  // reports as WRC_ERR_NO_DATA rather than returning it.
  std::vector<std::uint8_t> node_flags(table.num_nodes_, 0);
  for (std::size_t node = 0; node < table.num_nodes_; ++node) {
    if (table.status_[node] != kOkStatus) node_flags[node] |= kCellStatus;
    for (std::size_t k = 0; k < n_out; ++k) {
      const double value = table.values_[node * n_out + k];
      if (std::abs(value) > WRC_VALUE_MAX_MAGNITUDE && std::isfinite(value)) {
        std::ostringstream text;
        text << "value " << value << " at node " << NodeText(node, table.axes_, table.node_stride_)
             << " is beyond ±" << WRC_VALUE_MAX_MAGNITUDE;
        Invalid(where + "/outputs/" + output_names[k], text.str());
      }
      if (std::isfinite(value)) continue;
      if (table.status_[node] == kOkStatus) {
        Invalid(where + "/outputs/" + output_names[k],
                "non-finite value at node " + NodeText(node, table.axes_, table.node_stride_) +
                    " whose /status is 0 (ok)");
      }
      node_flags[node] |= kCellNonFinite;
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
