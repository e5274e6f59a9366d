#pragma once
/// @file parameter_file.h
/// Reading the dynamics models' parameter files: sections and keys checked against a schema
/// (a misspelling is an error with a suggestion), numbers checked for sign.

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "wrc/core/toml_reader.h"

namespace wrc::dynamics {

/// Each section's name with its allowed keys.
using ParameterSchema = std::vector<std::pair<std::string_view, std::vector<std::string_view>>>;

/// Throws InputError for a section or key the schema does not have, or a section that is not a
/// table, naming the file and line and suggesting the nearest name.
void CheckParameterNames(const toml::table& root, const io::SourceFile& file,
                         const ParameterSchema& schema);

/// A number that must be positive or, with allow_zero, not negative; required when `fallback`
/// is NaN.
double CheckedNumber(const io::Section& s, std::string_view key, bool allow_zero, double fallback);

/// `[simulation]`: the integrator's step and duration (s) and the initial lateral disturbance
/// (mm), with the model's defaults for the last two; the step at most the duration and at
/// most 10^8 steps.
struct SimulationSettings {
  double time_step = 1e-3;
  double duration = 0.0;
  double initial_y = 0.0;
};
SimulationSettings ReadSimulation(const io::Section& sim, double default_duration,
                                  double default_initial_y);

/// The text of a parameter file; InputError "PATH: cannot open the WHAT file" when unreadable.
std::string ReadParameterFile(const std::filesystem::path& path, const std::string& what);

}  // namespace wrc::dynamics
