#pragma once
// The start values of an FMU's parameters and inputs, which depend on its table (the table's
// speed, the rail origins of its scene). `wrc fmu` writes them into modelDescription.xml and,
// from the same map, into resources/start_values.txt, which the FMU's binary reads when it is
// instantiated: an FMI importer need not set a variable it leaves at its start value.
//
// The file is one "name = value" per line, in the order of the value references; a value runs
// to the end of its line (a table path may hold spaces). Lines starting with # are comments.

#include <cstdint>
#include <map>
#include <string>

namespace wrc::fmu {

inline constexpr const char* kStartValuesFile = "start_values.txt";

/// The text of each start value (a number as "%.17g" or "NaN", or a string), by value reference.
using StartValues = std::map<std::uint32_t, std::string>;

/// A number as start-value text: round-trips to the same double.
std::string StartNumber(double value);

std::string FormatStartValues(const StartValues& values);

/// Throws std::invalid_argument naming the line for an unknown name, a variable that takes no
/// start value (an output), a missing "=", a malformed number or a value given twice.
StartValues ParseStartValues(const std::string& text);

}  // namespace wrc::fmu
