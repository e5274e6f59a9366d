// ReadTableInfo(): what `wrc info` shows. The table is read as the runtime reads it
// (format::ReadTableContent, either format, every check a simulator's open makes); what only
// the HDF5 table holds (seal, solve times, profiles, failures) is read beside it with the
// checked HDF5 wrappers, lenient about extensions, strict about what
// docs/reference/table-layout.md requires.

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "runtime/format/flat_table.h"
#include "runtime/format/table_content.h"
#include "runtime/hdf5/hdf5.h"
#include "runtime/hdf5/table_schema.h"
#include "wrc/core/errors.h"
#include "wrc/generator/generator.h"
#include "wrc/runtime.hpp"

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

// What both formats hold: axes, outputs with their ranges over the ok points, status counts,
// root string attributes (all but `format`, which TableInfo holds apart).
TableInfo InfoOfContent(const format::TableContent& content) {
  TableInfo info;
  for (const auto& [name, value] : content.attributes) {
    if (name != schema::kFormat) info.attributes.emplace_back(name, value);
  }
  for (const auto& [name, value] : content.numbers) info.numbers.emplace_back(name, value);
  for (const format::AxisContent& axis : content.axes) {
    info.axes.push_back({axis.name, axis.unit, axis.values});
  }
  info.points = content.num_nodes();
  const std::size_t n_out = content.outputs.size();
  for (std::size_t k = 0; k < n_out; ++k) {
    TableInfo::Output output{content.outputs[k].name, content.outputs[k].unit};
    for (std::size_t node = 0; node < info.points; ++node) {
      if (content.status[node] != static_cast<std::int8_t>(schema::StoredStatus::kOk)) continue;
      const double v = content.values[node * n_out + k];  // finite: CheckContent
      output.min = std::isnan(output.min) ? v : std::min(output.min, v);
      output.max = std::isnan(output.max) ? v : std::max(output.max, v);
    }
    info.outputs.push_back(output);
  }
  for (const std::int8_t status : content.status) {
    if (status >= 0 && status < schema::kStoredStatusCount) {
      ++info.status_counts[status];
    } else {
      ++info.other_status;
    }
  }
  return info;
}

void ReadSolveTimes(const h5::File& file, TableInfo& info) {
  if (!HasOptional(file, schema::kSolveTime, h5::LinkKind::kDataset)) return;
  for (const float t : file.OpenDataset(schema::kSolveTime).Read<float>()) {
    info.solve_time_total_s += t;
    info.solve_time_max_s = std::max(info.solve_time_max_s, static_cast<double>(t));
  }
}

// The stored profile `name` (schema::kRailProfile or kWheelProfile), checked against the digest
// the table records for it; nothing when the table holds none.
std::optional<std::string> StoredProfile(const h5::File& file, const std::string& name,
                                         std::string* file_name) {
  if (!HasOptional(file, schema::kProfiles, h5::LinkKind::kGroup)) return std::nullopt;
  const h5::Group profiles = file.OpenGroup(schema::kProfiles);
  if (!HasOptional(profiles, name, h5::LinkKind::kDataset)) return std::nullopt;
  const h5::Dataset dataset = profiles.OpenDataset(name);
  if (file_name != nullptr) *file_name = OptionalString(dataset, schema::kProfileName);
  const std::vector<std::uint8_t> bytes = dataset.Read<std::uint8_t>();
  std::string text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  const std::string digest =
      name == schema::kRailProfile ? schema::kRailProfileSha256 : schema::kWheelProfileSha256;
  CheckStoredProfileDigest(file.FileName(), name, text, OptionalString(file, digest));
  return text;
}

void ReadProfiles(const h5::File& file, TableInfo& info) {
  if (const auto rail = StoredProfile(file, schema::kRailProfile, &info.rail_profile_name)) {
    info.rail_profile_bytes = rail->size();
  }
  if (const auto wheel = StoredProfile(file, schema::kWheelProfile, &info.wheel_profile_name)) {
    info.wheel_profile_bytes = wheel->size();
  }
}

// The grid indices of flat row-major point `index`.
std::vector<std::size_t> GridIndices(std::uint64_t index, const TableInfo& info) {
  std::vector<std::size_t> indices(info.axes.size());
  for (std::size_t a = info.axes.size(); a-- > 0;) {
    const std::size_t n = info.axes[a].values.size();
    indices[a] = static_cast<std::size_t>(index % n);
    index /= n;
  }
  return indices;
}

// /errors: why points failed. An entry must name a failed node of the grid: anywhere else it
// would be shown against another node (wrapped) or against one that solved.
void ReadFailures(const h5::File& file, const std::vector<std::int8_t>& status, TableInfo& info) {
  if (!HasOptional(file, schema::kErrors, h5::LinkKind::kGroup)) return;
  const h5::Group errors = file.OpenGroup(schema::kErrors);
  const std::vector<std::int64_t> points =
      errors.OpenDataset(schema::kErrorPoint).Read<std::int64_t>();
  const std::vector<std::string> messages = errors.OpenDataset(schema::kErrorMessage).ReadStrings();
  const std::string where = file.FileName() + ":/" + schema::kErrors + "/";
  if (points.size() != messages.size()) {
    throw InputError(where + schema::kErrorPoint + " holds " + std::to_string(points.size()) +
                     " entries but " + schema::kErrorMessage + " " +
                     std::to_string(messages.size()) + ": the table is damaged");
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
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
    const auto index = static_cast<std::uint64_t>(points[i]);
    info.failures.push_back({index, GridIndices(index, info), messages[i]});
  }
}

// The runtime reads the root attributes that are one string and passes over the rest; info shows
// them all, so a text attribute of another shape is damage it names.
void CheckTextAttributes(const h5::File& file) {
  for (const std::string& name : file.AttributeNames()) {
    const h5::Attribute attribute = file.OpenAttribute(name);
    if (attribute.Type().Class() != h5::TypeClass::kString) continue;
    const auto count = attribute.Space().NumElements();
    if (count != 1) {
      throw InputError(file.FileName() + ": the attribute '" + name + "' holds " +
                       std::to_string(count) +
                       " strings where a table has one: the table is "
                       "damaged");
    }
  }
}

// What only the HDF5 table holds: its seal, format version and warnings count, the solve
// times, the profiles and why points failed.
void ReadHdf5Extras(const std::filesystem::path& path, const std::vector<std::int8_t>& status,
                    TableInfo& info) {
  const auto lock = h5::LibraryLock();
  const h5::File file = h5::File::Open(path.string());
  info.sealed = file.Sealed();
  CheckTextAttributes(file);
  info.format = file.ReadStringAttribute(schema::kFormat);
  info.format_version = file.ReadIntAttribute(schema::kFormatVersionAttribute);
  if (file.HasAttribute(schema::kWarningsCount)) {
    info.warnings_count = file.ReadIntAttribute(schema::kWarningsCount);
  }
  ReadSolveTimes(file, info);
  ReadProfiles(file, info);
  ReadFailures(file, status, info);
}

}  // namespace

TableInfo ReadTableInfo(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) throw InputError(path.string() + ": no such file");
  try {
    // The runtime's reader and checks first: what info shows has passed every check a
    // simulator's open makes.
    const format::TableContent content = format::ReadTableContent(path.string());
    TableInfo info = InfoOfContent(content);
    if (format::IsFlatTableFile(path.string())) {
      info.format = kFlatTableFormat;
      info.format_version = format::kFlatVersion;
      info.sealed = true;  // a flat table's digest is checked before anything is read
    } else {
      ReadHdf5Extras(path, content.status, info);
    }
    return info;
  } catch (const TableError& error) {
    throw InputError(error.what());  // a damaged or foreign file: the user's input
  } catch (const h5::Error& error) {
    throw InputError(std::string("not a readable wrc table: ") + error.what());
  }
}

std::string ReadStoredProfile(const std::filesystem::path& table, const std::string& name) {
  try {
    const auto lock = h5::LibraryLock();
    const h5::File file = h5::File::Open(table.string());
    std::optional<std::string> bytes = StoredProfile(file, name, nullptr);
    if (!bytes) throw InputError(table.string() + ": the table holds no " + name + " profile");
    return std::move(*bytes);
  } catch (const h5::Error& error) {
    throw InputError(std::string("not a readable wrc table: ") + error.what());
  }
}

}  // namespace wrc
