#pragma once
/// @file case_parser.h
/// Private: the case part of case and scene parsing, shared by case_io.cpp and scene_io.cpp.

#include <filesystem>
#include <functional>
#include <set>
#include <string>
#include <string_view>

#include <toml++/toml.h>

#include "wrc/core/case.h"
#include "wrc/core/toml_reader.h"

namespace wrc::io {

/// How a document is read as a case.
struct CaseParseOptions {
  /// Check that the profile files exist and read as profiles (ReadProfile and ProfileSpline,
  /// errors reported at the [rail]/[wheel] profile key). Only when reading from disk: a scene
  /// stored in a table is re-read without its original files next to it.
  bool check_files_exist = false;
  /// Accept a [table] section (scenes); its contents are checked by the scene parser.
  bool allow_table_section = false;
  /// Quantities given by table axes instead of [state]: with a "z" or "fz" axis the state
  /// needs neither z nor fz, with "spin" or "omega" neither omega nor spin. The case then
  /// leaves those values unset (z/fz) or at their defaults (omega) for the caller to fill.
  std::set<std::string, std::less<>> axis_names;
};

/// Reads the case sections of a parsed document: checks section and key names, types and
/// values. Does not set source_text.
Case ReadCase(const toml::table& root, const SourceFile& file,
              const std::filesystem::path& base_dir, const CaseParseOptions& options);

/// Receives the [state] key whose value is out of range and what is wrong with it; throws.
using StateRangeFailure = std::function<void(std::string_view key, const std::string& message)>;

/// The range checks of a wheelset's state, the same wherever the state comes from (a case
/// file, the axes of a scene): velocity within WRC_VELOCITY_MIN..WRC_VELOCITY_MAX (or 0), the
/// creepages of spin, omega (when `omega_given`) and of the rates vy, vroll, vyaw within 100 %
/// slip, z within 1 m. Calls `fail` for the first value out of range.
void CheckWheelsetState(const WheelsetState& state, const Wheelset& wheelset, bool omega_given,
                        const StateRangeFailure& fail);

/// The problem type of a parsed document (`problem.type`, default wheel-rail).
CaseType ReadCaseType(const toml::table& root, const SourceFile& file);

/// Largest text input (case, scene, profile) read: 64 MiB, a thousand times the largest real
/// one; the limit makes `/dev/zero` or a runaway file an error instead of unbounded memory.
constexpr std::size_t kMaxTextFileBytes = std::size_t{64} << 20;

/// Reads a regular file of at most max_bytes into a string; throws InputError naming the file
/// when it is not a regular file (a FIFO is refused without blocking), too large or unreadable.
std::string ReadTextFile(const std::filesystem::path& path,
                         std::size_t max_bytes = kMaxTextFileBytes);

}  // namespace wrc::io
