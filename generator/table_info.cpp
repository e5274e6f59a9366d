// ReadTableInfo(): what `wrc info` shows, read with the checked HDF5 wrappers. Deliberately
// lenient about extensions and strict about what docs/reference/table-layout.md requires.

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "runtime/hdf5/hdf5.h"
#include "runtime/hdf5/table_schema.h"
#include "wrc/core/errors.h"
#include "wrc/generator/generator.h"

namespace wrc {
namespace {

std::string OptionalString(const h5::Object& object, const std::string& name) {
  if (!object.HasAttribute(name)) return {};
  const h5::Attribute attribute = object.OpenAttribute(name);
  if (attribute.Type().Class() != h5::TypeClass::kString) return {};
  return attribute.ReadString();
}

// Whether the optional child `name` is present as `kind`. Present as something else (a damaged
// object header opens as neither group nor dataset) is an error, not an absence: info would
// otherwise show zeros for what the file holds.
bool HasOptional(const h5::Group& group, const std::string& name, h5::LinkKind kind) {
  const h5::LinkKind found = group.Kind(name);
  if (found == h5::LinkKind::kMissing) return false;
  if (found != kind) {
    throw InputError(group.Where() + (group.Path() == "/" ? "" : "/") + name +
                     ": cannot be opened (damaged or not what a table holds there)");
  }
  return true;
}

TableInfo ReadInfo(const std::filesystem::path& path) {
  const auto lock = h5::LibraryLock();
  const h5::File file = h5::File::Open(path.string());
  TableInfo info;
  info.sealed = file.Sealed();
  if (!file.HasAttribute(schema::kFormat)) {
    throw InputError(path.string() + ": not a wrc table (no 'format' attribute)");
  }
  info.format = file.ReadStringAttribute(schema::kFormat);
  if (info.format != schema::kFormatName) {
    throw InputError(path.string() + ": not a wrc table (format is \"" + info.format + "\")");
  }
  info.format_version = file.HasAttribute(schema::kFormatVersionAttribute)
                            ? file.ReadIntAttribute(schema::kFormatVersionAttribute)
                            : 0;
  if (file.HasAttribute(schema::kWarningsCount)) {
    info.warnings_count = file.ReadIntAttribute(schema::kWarningsCount);
  }
  for (const std::string& name : file.AttributeNames()) {
    if (name == schema::kFormat) continue;
    const h5::Attribute attribute = file.OpenAttribute(name);
    if (attribute.Type().Class() == h5::TypeClass::kString) {
      info.attributes.emplace_back(name, attribute.ReadString());
    }
  }

  const h5::Group axes = file.OpenGroup(schema::kAxes);
  std::vector<h5::Size> shape;
  for (const std::string& name : axes.ReadStringArrayAttribute(schema::kOrder)) {
    const h5::Dataset dataset = axes.OpenDataset(name);
    info.axes.push_back({name, OptionalString(dataset, schema::kUnit), dataset.Read<double>()});
    if (info.axes.back().values.empty()) {
      throw InputError(path.string() + ":/axes/" + name + ": the axis is empty");
    }
    shape.push_back(info.axes.back().values.size());
  }
  info.points = 1;
  for (const h5::Size n : shape) info.points *= static_cast<std::size_t>(n);

  const h5::Dataset status_dataset = file.OpenDataset(schema::kStatus);
  if (status_dataset.Shape() != shape) {
    throw InputError(path.string() + ":/status: its shape does not match the axes");
  }
  const std::vector<std::int8_t> status = status_dataset.Read<std::int8_t>();
  for (const std::int8_t s : status) {
    if (s >= 0 && s < schema::kStoredStatusCount) {
      ++info.status_counts[s];
    } else {
      ++info.other_status;
    }
  }

  const h5::Group outputs = file.OpenGroup(schema::kOutputs);
  const std::vector<std::string> output_names =
      outputs.HasAttribute(schema::kOrder) ? outputs.ReadStringArrayAttribute(schema::kOrder)
                                           : outputs.MemberNames();
  for (const std::string& name : output_names) {
    const h5::Dataset dataset = outputs.OpenDataset(name);
    if (dataset.Shape() != shape) {
      throw InputError(path.string() + ":/outputs/" + name + ": its shape does not match the axes");
    }
    TableInfo::Output output{name, OptionalString(dataset, schema::kUnit)};
    const std::vector<double> values = dataset.Read<double>();
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (status[i] != static_cast<std::int8_t>(schema::StoredStatus::kOk) ||
          !std::isfinite(values[i])) {
        continue;
      }
      low = std::min(low, values[i]);
      high = std::max(high, values[i]);
    }
    if (low <= high) {
      output.min = low;
      output.max = high;
    }
    info.outputs.push_back(output);
  }

  if (HasOptional(file, schema::kSolveTime, h5::LinkKind::kDataset)) {
    for (const float t : file.OpenDataset(schema::kSolveTime).Read<float>()) {
      info.solve_time_total_s += t;
      info.solve_time_max_s = std::max(info.solve_time_max_s, static_cast<double>(t));
    }
  }

  if (HasOptional(file, schema::kProfiles, h5::LinkKind::kGroup)) {
    const h5::Group profiles = file.OpenGroup(schema::kProfiles);
    for (auto [name, digest, out_name, out_bytes] :
         {std::tuple{schema::kRailProfile, schema::kRailProfileSha256, &info.rail_profile_name,
                     &info.rail_profile_bytes},
          std::tuple{schema::kWheelProfile, schema::kWheelProfileSha256, &info.wheel_profile_name,
                     &info.wheel_profile_bytes}}) {
      if (!HasOptional(profiles, name, h5::LinkKind::kDataset)) continue;
      const h5::Dataset dataset = profiles.OpenDataset(name);
      *out_name = OptionalString(dataset, schema::kProfileName);
      *out_bytes = static_cast<std::size_t>(dataset.NumElements());
      const std::vector<std::uint8_t> bytes = dataset.Read<std::uint8_t>();
      CheckStoredProfileDigest(
          path.string(), name,
          std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
          OptionalString(file, digest));
    }
  }

  if (HasOptional(file, schema::kErrors, h5::LinkKind::kGroup)) {
    const h5::Group errors = file.OpenGroup(schema::kErrors);
    const std::vector<std::int64_t> points =
        errors.OpenDataset(schema::kErrorPoint).Read<std::int64_t>();
    const std::vector<std::string> messages =
        errors.OpenDataset(schema::kErrorMessage).ReadStrings();
    const std::string where = path.string() + ":/" + schema::kErrors + "/";
    if (points.size() != messages.size()) {
      throw InputError(where + schema::kErrorPoint + " holds " + std::to_string(points.size()) +
                       " entries but " + schema::kErrorMessage + " " +
                       std::to_string(messages.size()) + ": the table is damaged");
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
      // An entry names a failed node of the grid: anywhere else it would be shown against
      // another node (wrapped) or against one that solved.
      const bool on_grid = points[i] >= 0 && static_cast<std::uint64_t>(points[i]) < info.points;
      if (!on_grid || status[static_cast<std::size_t>(points[i])] ==
                          static_cast<std::int8_t>(schema::StoredStatus::kOk)) {
        throw InputError(
            where + schema::kErrorPoint + "[" + std::to_string(i) +
            "] = " + std::to_string(points[i]) +
            (on_grid ? " is a node that solved (status 0)"
                     : " lies outside the grid of " + std::to_string(info.points) + " points") +
            ": the table is damaged");
      }
      TableInfo::Failure failure;
      failure.index = static_cast<std::uint64_t>(points[i]);
      std::uint64_t rest = failure.index;
      failure.indices.resize(shape.size());
      for (std::size_t a = shape.size(); a-- > 0;) {
        failure.indices[a] = static_cast<std::size_t>(rest % shape[a]);
        rest /= shape[a];
      }
      failure.message = messages[i];
      info.failures.push_back(std::move(failure));
    }
  }
  return info;
}

}  // namespace

TableInfo ReadTableInfo(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) throw InputError(path.string() + ": no such file");
  try {
    return ReadInfo(path);
  } catch (const h5::Error& error) {
    // An HDF5 failure here means a damaged or foreign file: the user's input, not a bug.
    throw InputError(std::string("not a readable wrc table: ") + error.what());
  }
}

}  // namespace wrc
