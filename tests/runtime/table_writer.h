#pragma once
/// @file table_writer.h
/// Test support (header-only, so benchmarks and the C test's support code can include it too):
/// writes a table file laid out as docs/reference/table-layout.md prescribes, from axes and a
/// function, with the wrc::h5 wrapper. Also a scratch file that deletes itself afterwards.

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <unistd.h>

#include "runtime/hdf5/hdf5.h"
#include "runtime/hdf5/seal.h"
#include "runtime/hdf5/table_schema.h"

namespace wrc::test {

struct TableAxis {
  std::string name;
  std::vector<double> values;
  std::string unit = "mm";
};

/// What to write. The function gives output k at the node with the given coordinates (one per
/// axis, in axis order); status likewise gives the node's /status (default: 0 everywhere).
struct TableContent {
  std::vector<TableAxis> axes;
  std::vector<std::string> outputs;
  std::function<double(int output, const std::vector<double>& coordinates)> function;
  std::function<std::int8_t(const std::vector<double>& coordinates)> status;
  /// Write the /outputs attribute 'order' (the runtime otherwise uses creation order).
  bool write_output_order = true;
  /// The root attribute `scene` (the wheelset API reads [state] and [wheelset] from it).
  std::string scene = "# written by tests/runtime/table_writer.h\n[table]\n";
  /// The HDF5 file format (kEarliest: as tables were written before metadata checksums).
  h5::FileFormat format = h5::FileFormat::kChecksummed;
  /// Storage of the axes (the generator checksums them too; default: contiguous, unfiltered).
  h5::DatasetOptions axis_storage = {};
  /// Name the axes of every grid dataset in its attribute 'dimensions', as the generator does
  /// (tables written before it did lack the attribute).
  bool write_dimensions = true;
  /// Seal the file as the generator does (runtime/hdf5/seal.h); unsealed: as tables were
  /// written before seals.
  bool sealed = false;
};

/// n values from first to last, equally spaced (last exactly).
inline std::vector<double> Linspace(double first, double last, int n) {
  std::vector<double> values(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    values[static_cast<std::size_t>(i)] =
        i == n - 1 ? last : first + (last - first) * i / static_cast<double>(n - 1);
  }
  return values;
}

/// The four axes of a typical wheelset table: y over [−10, 10] mm with y_nodes nodes, roll
/// ±0.002 (5 nodes), yaw ±0.01 (5) and spin ±0.01 (9).
inline std::vector<TableAxis> WheelsetAxes(int y_nodes) {
  return {{"y", Linspace(-10.0, 10.0, y_nodes)},
          {"roll", Linspace(-0.002, 0.002, 5)},
          {"yaw", Linspace(-0.01, 0.01, 5)},
          {"spin", Linspace(-0.01, 0.01, 9)}};
}

// The stored profiles' bytes (their digests are written as the generator writes them).
inline constexpr const char* kRailProfileText = "# rail profile\n0 0\n1 0\n";
inline constexpr const char* kWheelProfileText = "# wheel profile\n0 0\n1 1\n";

inline void WriteTableContents(const std::string& path, const TableContent& content);

/// Writes content to path (overwriting) as a complete, valid table.
inline void WriteTable(const std::string& path, const TableContent& content) {
  WriteTableContents(path, content);
  if (content.sealed) h5::SealFile(path);
}

inline void WriteTableContents(const std::string& path, const TableContent& content) {
  h5::File file = h5::File::Create(path, /*overwrite=*/true, content.format, content.sealed);
  file.WriteStringAttribute(schema::kFormat, schema::kFormatName);
  file.WriteIntAttribute(schema::kFormatVersionAttribute, schema::kFormatVersion);
  file.WriteStringAttribute(schema::kWrcVersion, "0.1.0-test");
  file.WriteStringAttribute(schema::kCreated, "2024-01-01T00:00:00Z");
  file.WriteStringAttribute(schema::kScene, content.scene);
  file.WriteStringAttribute(schema::kRailProfileSha256, h5::Sha256Hex(kRailProfileText));
  file.WriteStringAttribute(schema::kWheelProfileSha256, h5::Sha256Hex(kWheelProfileText));

  h5::Group axes = file.CreateGroup(schema::kAxes);
  std::vector<std::string> order;
  std::vector<h5::Size> shape;
  for (const TableAxis& axis : content.axes) {
    h5::Dataset dataset = axes.WriteDataset<double>(
        axis.name, {static_cast<h5::Size>(axis.values.size())}, axis.values, content.axis_storage);
    dataset.WriteStringAttribute(schema::kUnit, axis.unit);
    order.push_back(axis.name);
    shape.push_back(axis.values.size());
  }
  axes.WriteStringArrayAttribute(schema::kOrder, order);

  // Enumerate nodes in row-major order (last axis fastest), as the datasets store them.
  std::size_t n_nodes = 1;
  for (h5::Size n : shape) n_nodes *= n;
  std::vector<std::vector<double>> coordinates(n_nodes, std::vector<double>(shape.size()));
  for (std::size_t node = 0; node < n_nodes; ++node) {
    std::size_t rest = node;
    for (std::size_t a = shape.size(); a-- > 0;) {
      coordinates[node][a] = content.axes[a].values[rest % shape[a]];
      rest /= shape[a];
    }
  }

  h5::Group outputs = file.CreateGroup(schema::kOutputs);
  for (std::size_t k = 0; k < content.outputs.size(); ++k) {
    std::vector<double> values(n_nodes);
    for (std::size_t node = 0; node < n_nodes; ++node) {
      values[node] = content.function(static_cast<int>(k), coordinates[node]);
    }
    h5::Dataset dataset =
        outputs.WriteDataset(content.outputs[k], shape, values, h5::CompressedChecked());
    dataset.WriteStringAttribute(schema::kUnit, "N");
    if (content.write_dimensions) dataset.WriteStringArrayAttribute(schema::kDimensions, order);
  }
  if (content.write_output_order)
    outputs.WriteStringArrayAttribute(schema::kOrder, content.outputs);

  std::vector<std::int8_t> status(n_nodes, 0);
  if (content.status) {
    for (std::size_t node = 0; node < n_nodes; ++node)
      status[node] = content.status(coordinates[node]);
  }
  h5::Dataset status_dataset =
      file.WriteDataset(schema::kStatus, shape, status, h5::CompressedChecked());
  if (content.write_dimensions)
    status_dataset.WriteStringArrayAttribute(schema::kDimensions, order);
  file.WriteDataset(schema::kSolveTime, shape, std::vector<float>(n_nodes, 0.01f),
                    h5::CompressedChecked());

  h5::Group profiles = file.CreateGroup(schema::kProfiles);
  const std::string rail_text = kRailProfileText;
  const std::string wheel_text = kWheelProfileText;
  h5::Dataset rail =
      profiles.WriteDataset(schema::kRailProfile, {rail_text.size()},
                            std::vector<std::uint8_t>(rail_text.begin(), rail_text.end()));
  rail.WriteStringAttribute(schema::kProfileName, "rail.prr");
  h5::Dataset wheel =
      profiles.WriteDataset(schema::kWheelProfile, {wheel_text.size()},
                            std::vector<std::uint8_t>(wheel_text.begin(), wheel_text.end()));
  wheel.WriteStringAttribute(schema::kProfileName, "wheel.prw");
}

/// A unique file name in the temporary directory, removed when the object goes away.
class ScratchFile {
 public:
  explicit ScratchFile(const std::string& stem) {
    static std::atomic<int> counter{0};
    path_ =
        (std::filesystem::temp_directory_path() / ("wrc-test-" + std::to_string(::getpid()) + "-" +
                                                   std::to_string(counter++) + "-" + stem + ".h5"))
            .string();
  }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;
  ~ScratchFile() {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace wrc::test
