#pragma once
// The table being assembled on rank 0: one slot per grid point, filled as points finish (from
// the journal or from the workers), written to HDF5 when all are filled.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "wrc/generator/generator.h"

namespace wrc::gen {

/// Values of all points, row-major, one array per output.
struct TableData {
  explicit TableData(std::size_t points = 0, std::size_t outputs = 0);

  /// Stores a point; false when it was already stored (the first result is kept).
  bool Store(std::uint64_t point, const PointResult& result);
  bool Has(std::uint64_t point) const { return status[point] >= 0; }

  std::vector<std::vector<double>> values;  ///< [output][point]
  std::vector<std::int8_t> status;          ///< PointStatus, or -1 while missing.
  std::vector<float> solve_time_s;
  std::vector<double> z;                          ///< Warm-start state of each finished point.
  std::map<std::uint64_t, std::string> messages;  ///< Failed points (status 2, 3).
  /// Solved points (status 0, 1) whose solution carries warnings (PointResult::message).
  std::uint64_t warning_points = 0;
  std::size_t finished = 0;
};

/// Provenance written as root attributes.
struct TableProvenance {
  std::string rail_sha256, wheel_sha256;
  std::string created;  ///< ISO 8601, UTC.
  /// How prescribed-fz solves were started (the z_warm_start attribute).
  std::string z_warm_start;
  /// Further root string attributes (a refined table's refine_* record), written in order.
  std::vector<std::pair<std::string, std::string>> attributes;
};

/// Writes the table file exactly per docs/reference/table-layout.md (plus /outputs 'order', /errors
/// and the warm_start attribute, documented in tables/README.md). Every point must be finished.
void WriteTableFile(const std::filesystem::path& path, const Scene& scene, const TableData& data,
                    const TableProvenance& provenance);

/// The current time as ISO 8601 UTC, e.g. 2025-03-01T12:34:56Z.
std::string IsoTimestampUtc();

}  // namespace wrc::gen
