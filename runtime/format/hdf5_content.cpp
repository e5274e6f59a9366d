// The HDF5 table's reader: the layout of docs/reference/table-layout.md through the checked
// wrappers of runtime/hdf5/, into a TableContent.

#include "runtime/format/hdf5_content.h"

#include <algorithm>
#include <limits>
#include <optional>
#include <set>
#include <sstream>

#include "runtime/hdf5/hdf5.h"
#include "runtime/hdf5/seal.h"
#include "runtime/hdf5/table_schema.h"
#include "wrc/runtime.hpp"

namespace wrc::format {
namespace {

using schema::kFormatName;
using schema::kFormatVersion;

std::string ShapeText(const std::vector<h5::Size>& shape) {
  std::ostringstream text;
  text << '[';
  for (std::size_t i = 0; i < shape.size(); ++i) text << (i ? "," : "") << shape[i];
  text << ']';
  return text.str();
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

h5::File OpenChecked(const std::string& path) {
  try {
    return h5::File::Open(path);
  } catch (const h5::SealError& error) {
    throw TableError(WRC_ERR_FORMAT, std::string(error.what()));
  } catch (const h5::EarliestFormatError& error) {
    throw TableError(WRC_ERR_FORMAT, std::string(error.what()));
  } catch (const h5::Error& error) {
    throw TableError(WRC_ERR_FILE, std::string(error.what()));
  }
}

void ReadRootAttributes(const h5::File& file, TableContent& content) {
  for (const std::string& name : file.AttributeNames()) {
    const h5::Attribute attribute = file.OpenAttribute(name);
    if (attribute.Space().NumElements() != 1) continue;
    if (attribute.Type().Class() == h5::TypeClass::kString) {
      content.attributes[name] = attribute.ReadString();
    } else if (attribute.Type().Class() == h5::TypeClass::kFloat) {
      content.numbers[name] = attribute.ReadDouble();
    }
  }
}

AxisContent ReadAxis(const h5::Group& axes_group, const std::string& name) {
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
  AxisContent axis{name, OptionalStringAttribute(dataset, schema::kUnit), dataset.Read<double>()};
  CheckAxisValues(axis.values, where);  // here too: the first problem a damaged axis shows
  return axis;
}

// The axes in the order the /axes attribute 'order' gives; returns their names.
std::vector<std::string> ReadAxes(const h5::File& file, TableContent& content) {
  const std::string where = file.FileName() + ":/axes";
  RequireKind(file, schema::kAxes, h5::LinkKind::kGroup, where, "group is missing");
  const h5::Group axes_group = file.OpenGroup(schema::kAxes);
  if (!axes_group.HasAttribute(schema::kOrder)) Invalid(where, "attribute 'order' is missing");
  const std::vector<std::string> names = axes_group.ReadStringArrayAttribute(schema::kOrder);
  if (names.empty()) Invalid(where, "attribute 'order' lists no axes");
  if (names.size() > static_cast<std::size_t>(WRC_MAX_AXES)) {
    Invalid(where, "attribute 'order' lists " + std::to_string(names.size()) + " axes, at most " +
                       std::to_string(WRC_MAX_AXES) + " are supported");
  }
  std::set<std::string> seen;
  for (const std::string& name : names) {
    if (!seen.insert(name).second) Invalid(where, "attribute 'order' lists \"" + name + "\" twice");
    content.axes.push_back(ReadAxis(axes_group, name));
  }
  return names;
}

// The outputs, in the /outputs attribute 'order' when present, else the group's member order,
// side by side per node.
void ReadOutputs(const h5::File& file, const std::vector<std::string>& axis_names,
                 const std::vector<h5::Size>& grid_shape, std::size_t num_nodes,
                 TableContent& content) {
  const std::string where = file.FileName() + ":/outputs";
  RequireKind(file, schema::kOutputs, h5::LinkKind::kGroup, where, "group is missing");
  const h5::Group outputs_group = file.OpenGroup(schema::kOutputs);
  std::vector<std::string> names = outputs_group.MemberNames();
  if (outputs_group.HasAttribute(schema::kOrder)) {
    std::vector<std::string> ordered = outputs_group.ReadStringArrayAttribute(schema::kOrder);
    std::vector<std::string> sorted_members = names;
    std::vector<std::string> sorted_order = ordered;
    std::sort(sorted_members.begin(), sorted_members.end());
    std::sort(sorted_order.begin(), sorted_order.end());
    if (sorted_members != sorted_order) {
      Invalid(where, "attribute 'order' does not list exactly the datasets present");
    }
    names = std::move(ordered);
  }
  if (names.empty()) Invalid(where, "holds no outputs");
  const std::size_t n_out = names.size();
  if (num_nodes > (std::numeric_limits<std::size_t>::max() / 8 - kValuePadding) / n_out) {
    Invalid(where, "table too large for this machine");
  }
  content.values.reserve(num_nodes * n_out + kValuePadding);
  content.values.assign(num_nodes * n_out, 0.0);
  for (std::size_t k = 0; k < n_out; ++k) {
    const std::string output_where = where + "/" + names[k];
    RequireKind(outputs_group, names[k], h5::LinkKind::kDataset, output_where, "missing");
    const h5::Dataset dataset = outputs_group.OpenDataset(names[k]);
    const std::vector<h5::Size> shape = dataset.Shape();
    if (shape != grid_shape) {
      Invalid(output_where, "shape " + ShapeText(shape) +
                                " does not match the axis lengths in /axes 'order' " +
                                ShapeText(grid_shape));
    }
    RequireType(dataset, h5::ElementType::kFloat64, output_where);
    CheckDimensions(dataset, axis_names, output_where);
    const std::vector<double> values = dataset.Read<double>();
    for (std::size_t node = 0; node < num_nodes; ++node)
      content.values[node * n_out + k] = values[node];
    content.outputs.push_back(
        OutputContent{names[k], OptionalStringAttribute(dataset, schema::kUnit)});
  }
}

void ReadStatus(const h5::File& file, const std::vector<std::string>& axis_names,
                const std::vector<h5::Size>& grid_shape, TableContent& content) {
  const std::string where = file.FileName() + ":/status";
  RequireKind(file, schema::kStatus, h5::LinkKind::kDataset, where, "dataset is missing");
  const h5::Dataset status = file.OpenDataset(schema::kStatus);
  if (status.Shape() != grid_shape) {
    Invalid(where, "shape " + ShapeText(status.Shape()) + " does not match the axis lengths " +
                       ShapeText(grid_shape));
  }
  RequireType(status, h5::ElementType::kInt8, where);
  CheckDimensions(status, axis_names, where);
  content.status = status.Read<std::int8_t>();
}

TableContent ReadOpened(const h5::File& file, const std::string& path) {
  CheckRootAttributes(file);
  TableContent content;
  content.path = path;
  if (!file.Sealed()) {
    content.warning = path +
                      ": not sealed (written before tables carried a SHA-256 of their bytes), so "
                      "damage is found only as HDF5 reads it; seal it with `wrc upgrade " +
                      path + " -o NEW.h5`";
  }
  ReadRootAttributes(file, content);
  const std::vector<std::string> axis_names = ReadAxes(file, content);
  std::vector<h5::Size> grid_shape;
  std::vector<std::uint64_t> lengths;
  for (const AxisContent& axis : content.axes) {
    grid_shape.push_back(axis.values.size());
    lengths.push_back(axis.values.size());
  }
  const auto num_nodes = static_cast<std::size_t>(CountNodes(lengths, path + ":/axes"));
  ReadOutputs(file, axis_names, grid_shape, num_nodes, content);
  ReadStatus(file, axis_names, grid_shape, content);
  CheckContent(content, path + ":");
  return content;
}

}  // namespace

TableContent ReadHdf5Content(const std::string& path) {
  const auto lock = h5::LibraryLock();
  const h5::File file = OpenChecked(path);
  try {
    return ReadOpened(file, path);
  } catch (const h5::Error& error) {  // An HDF5 failure while reading a valid-looking file.
    throw TableError(WRC_ERR_FORMAT, std::string(error.what()));
  }
}

}  // namespace wrc::format
