#pragma once
// Inputs of the studies that reproduce the paper (the cases and profiles of tables/), compiled
// into the program byte for byte so that the studies run from any directory.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace wrc::cli {

/// A file of tables/, by its path relative to tables/ ("profiles/site_b_hr.prr").
struct ShippedFile {
  std::string_view name;
  std::string_view bytes;
};

/// Every shipped file compiled in (tools/CMakeLists.txt lists them).
const std::vector<ShippedFile>& ShippedFiles();

/// Writes the shipped files whose names are given into `dir` under their names, and returns
/// the path of each; throws std::logic_error for a name that is not compiled in.
std::vector<std::filesystem::path> WriteShippedFiles(const std::filesystem::path& dir,
                                                     const std::vector<std::string>& names);

}  // namespace wrc::cli
