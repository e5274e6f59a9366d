#pragma once
// What `wrc solve` reports (docs/output-format.md): the JSON summary and the `--out` files.
// `wrc plot patch` writes the same files for the case it solves.

#include <filesystem>
#include <nlohmann/json.hpp>

#include "wrc/core/halfspace.h"
#include "wrc/core/wheelrail.h"

namespace wrc::cli {

/// The JSON object of a half-space solve that took `seconds`.
nlohmann::json HalfspaceJson(const HalfspaceResult& r, double seconds);
/// fields.csv and summary.json of a half-space solve into `dir` (created when missing).
void WriteHalfspaceFields(const std::filesystem::path& dir, const HalfspaceResult& r,
                          const nlohmann::json& summary);

/// The JSON object of a wheel–rail solve that took `seconds`.
nlohmann::json WheelRailJson(const WheelRailResult& r, double seconds);
/// summary.json and, per patch, patch<n>_fields.csv (and patch<n>_curve.csv for the curved
/// reference) of a wheel–rail solve solved with WheelRailOptions::keep_fields, into `dir`.
void WriteWheelRailFields(const std::filesystem::path& dir, const WheelRailResult& r,
                          const nlohmann::json& summary);

}  // namespace wrc::cli
