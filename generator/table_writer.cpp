// The HDF5 table (docs/reference/table-layout.md), written through the checked wrc::h5 wrappers.

#include <ctime>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>

#include "generator/table_data.h"
#include "runtime/hdf5/hdf5.h"
#include "runtime/hdf5/seal.h"
#include "runtime/hdf5/table_schema.h"
#include "wrc/core/errors.h"

namespace wrc::gen {
namespace {

std::vector<std::uint8_t> FileBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot read the profile to store it in the table");
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in),
                                   std::istreambuf_iterator<char>());
}

void WriteProfile(h5::Group& group, const std::string& name, const std::filesystem::path& path) {
  std::vector<std::uint8_t> bytes = FileBytes(path);
  // HDF5 chunks need a non-empty dataset; an empty profile file could not be solved anyway.
  if (bytes.empty()) throw InputError(path.string() + ": the profile file is empty");
  h5::Dataset dataset =
      group.WriteDataset<std::uint8_t>(name, {bytes.size()}, bytes, h5::CompressedChecked());
  dataset.WriteStringAttribute(schema::kProfileName, path.filename().string());
}

}  // namespace

TableData::TableData(std::size_t points, std::size_t outputs)
    : values(outputs, std::vector<double>(points, std::numeric_limits<double>::quiet_NaN())),
      status(points, -1),
      solve_time_s(points, 0.0f),
      z(points, std::numeric_limits<double>::quiet_NaN()) {}

bool TableData::Store(std::uint64_t point, const PointResult& result) {
  if (point >= status.size()) throw std::out_of_range("TableData::Store: point index");
  if (status[point] >= 0) return false;
  if (result.values.size() != values.size()) {
    throw std::invalid_argument("TableData::Store: wrong number of output values");
  }
  for (std::size_t k = 0; k < values.size(); ++k) values[k][point] = result.values[k];
  status[point] = static_cast<std::int8_t>(result.status);
  solve_time_s[point] = result.solve_time_s;
  z[point] = result.z;
  if (result.status == PointStatus::kNotConverged || result.status == PointStatus::kError) {
    messages[point] = result.message;
  } else if (!result.message.empty()) {
    ++warning_points;
  }
  ++finished;
  return true;
}

std::string IsoTimestampUtc() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

// The generator's point outcomes are the codes the table stores.
static_assert(static_cast<int>(PointStatus::kOk) == static_cast<int>(schema::StoredStatus::kOk));
static_assert(static_cast<int>(PointStatus::kNoContact) ==
              static_cast<int>(schema::StoredStatus::kNoContact));
static_assert(static_cast<int>(PointStatus::kNotConverged) ==
              static_cast<int>(schema::StoredStatus::kNotConverged));
static_assert(static_cast<int>(PointStatus::kError) ==
              static_cast<int>(schema::StoredStatus::kError));
static_assert(kPointStatusCount == schema::kStoredStatusCount);

namespace {

void WriteTableContents(h5::File& file, const Scene& scene, const TableData& data,
                        const TableProvenance& provenance) {
  file.WriteStringAttribute(schema::kFormat, schema::kFormatName);
  file.WriteIntAttribute(schema::kFormatVersionAttribute, schema::kFormatVersion);
  file.WriteStringAttribute(schema::kWrcVersion, GeneratorVersion());
  file.WriteStringAttribute(schema::kCreated, provenance.created);
  file.WriteStringAttribute(schema::kScene, scene.base.source_text);
  file.WriteStringAttribute(schema::kRailProfileSha256, provenance.rail_sha256);
  file.WriteStringAttribute(schema::kWheelProfileSha256, provenance.wheel_sha256);
  // Extension: how z was started at each prescribed-fz point (results differ in the last bits).
  file.WriteStringAttribute(schema::kZWarmStart, provenance.z_warm_start);
  file.WriteIntAttribute(schema::kWarningsCount, static_cast<std::int64_t>(data.warning_points));
  for (const auto& [name, value] : provenance.attributes) file.WriteStringAttribute(name, value);
  WriteFixedStateAttributes(file, scene);

  const h5::DatasetOptions storage = h5::CompressedChecked();
  std::vector<h5::Size> shape;
  for (const std::size_t n : scene.Shape()) shape.push_back(n);

  h5::Group axes = file.CreateGroup(schema::kAxes);
  std::vector<std::string> axis_names;
  for (const SceneAxis& axis : scene.axes) {
    h5::Dataset dataset =
        axes.WriteDataset<double>(axis.name, {axis.values.size()}, axis.values, storage);
    dataset.WriteStringAttribute(schema::kUnit, std::string(QuantityUnit(axis.name)));
    axis_names.push_back(axis.name);
  }
  axes.WriteStringArrayAttribute(schema::kOrder, axis_names);

  h5::Group outputs = file.CreateGroup(schema::kOutputs);
  for (std::size_t k = 0; k < scene.outputs.size(); ++k) {
    const std::string& name = scene.outputs[k];
    h5::Dataset dataset = outputs.WriteDataset<double>(name, shape, data.values[k], storage);
    dataset.WriteStringAttribute(schema::kUnit, std::string(QuantityUnit(name)));
    dataset.WriteStringArrayAttribute(schema::kDimensions, axis_names);
  }
  outputs.WriteStringArrayAttribute(schema::kOrder, scene.outputs);

  h5::Dataset status = file.WriteDataset<std::int8_t>(schema::kStatus, shape, data.status, storage);
  status.WriteStringAttribute(schema::kMeaning, schema::kStatusMeaning);
  status.WriteStringArrayAttribute(schema::kDimensions, axis_names);
  file.WriteDataset<float>(schema::kSolveTime, shape, data.solve_time_s, storage)
      .WriteStringAttribute(schema::kUnit, "s");

  h5::Group profiles = file.CreateGroup(schema::kProfiles);
  WriteProfile(profiles, schema::kRailProfile, scene.base.rail.path);
  WriteProfile(profiles, schema::kWheelProfile, scene.base.wheel.path);

  // Extension: why points failed, so users need not re-run them to find out.
  if (!data.messages.empty()) {
    h5::Group errors = file.CreateGroup(schema::kErrors);
    std::vector<std::int64_t> points;
    std::vector<std::string> messages;
    for (const auto& [point, message] : data.messages) {
      points.push_back(static_cast<std::int64_t>(point));
      messages.push_back(message);
    }
    errors.WriteDataset<std::int64_t>(schema::kErrorPoint, {points.size()}, points, storage)
        .WriteStringAttribute(schema::kMeaning, "flat row-major index into the grid");
    errors.WriteStringDataset(schema::kErrorMessage, messages, storage);
  }
}

}  // namespace

void WriteTableFile(const std::filesystem::path& path, const Scene& scene, const TableData& data,
                    const TableProvenance& provenance) {
  if (data.finished != data.status.size()) {
    throw std::logic_error("WriteTableFile: the table has unfinished points");
  }
  const auto lock = h5::LibraryLock();
  {
    h5::File file = h5::File::Create(path.string(), /*overwrite=*/true,
                                     h5::FileFormat::kChecksummed, /*sealed=*/true);
    WriteTableContents(file, scene, data, provenance);
    file.Flush();  // a failed write is an error here; in the destructor it would be lost
  }                // closed: every byte is written before the seal is taken
  h5::SealFile(path.string());
}

}  // namespace wrc::gen

namespace wrc {

// The fixed state the runtime's wheelset API needs, typed, so that it reads no scene text.
void WriteFixedStateAttributes(h5::File& file, const Scene& scene) {
  const Case& c = scene.base;
  file.WriteDoubleAttribute(schema::kWheelsetVelocity, c.state.velocity);
  file.WriteDoubleAttribute(schema::kWheelsetNominalRadius, c.wheelset.nominal_radius);
  file.WriteDoubleAttribute(schema::kWheelProfileOffset, 0.5 * c.wheelset.flange_back_distance -
                                                             c.wheelset.flange_back_position);
  file.WriteStringAttribute(schema::kWheelsetSide,
                            c.wheelset.side == WheelSide::kLeft ? "left" : "right");
  for (const StateQuantity& q : kStateQuantities) {
    file.WriteDoubleAttribute(schema::kFixedPrefix + std::string(q.name),
                              FixedStateValue(scene, q.name));
  }
}

}  // namespace wrc
