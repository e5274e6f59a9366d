#pragma once
/// @file table_layout.h
/// Names of the table layout (docs/reference/table-layout.md) that more than one reader needs.

#include <string>
#include <vector>

namespace wrc::runtime {

/// The root attributes a table may carry. Readers of tables in HDF5's earliest format read
/// these by name only (h5::RootAttributeNamesToRead).
inline const std::vector<std::string>& TableRootAttributeNames() {
  static const std::vector<std::string> names = {"format",
                                                 "format_version",
                                                 "wrc_version",
                                                 "created",
                                                 "scene",
                                                 "rail_profile_sha256",
                                                 "wheel_profile_sha256",
                                                 "z_warm_start",
                                                 "warnings_count",
                                                 "refine_target",
                                                 "refine_passes",
                                                 "refine_stop",
                                                 "refine_estimated_error"};
  return names;
}

}  // namespace wrc::runtime
