#pragma once
/// @file scene_values.h
/// Reads single values from the scene text a table stores (its root attribute `scene`), for
/// tables written before the fixed state was stored typed (the wheel*_ and fixed_* attributes
/// of runtime/hdf5/table_schema.h): the wheelset API needs the fixed state (velocity, nominal
/// radius, side, quantities that are not axes). A line reader for `[section]` headers and `key =
/// number | "string"` lines, which is how scene files write these keys; it is not a TOML parser.
/// Internal to wrc_runtime.

#include <optional>
#include <string>
#include <string_view>

namespace wrc::runtime {

/// The text of `key = ...` in `[section]` with its comment and surrounding blanks removed, or
/// nothing when the section has no such key.
std::optional<std::string> SceneValueText(std::string_view scene, std::string_view section,
                                          std::string_view key);

/// The key's value as a number; nothing when absent or not a number.
std::optional<double> SceneNumber(std::string_view scene, std::string_view section,
                                  std::string_view key);

/// The key's value as a basic string ("..." without escapes); nothing when absent or not one.
std::optional<std::string> SceneString(std::string_view scene, std::string_view section,
                                       std::string_view key);

}  // namespace wrc::runtime
