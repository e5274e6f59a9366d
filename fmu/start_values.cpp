#include "fmu/start_values.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "fmu/variables.h"

namespace wrc::fmu {
namespace {

bool TakesStartValue(const Variable& v) {
  return v.causality == Causality::kParameter || v.causality == Causality::kInput;
}

const Variable& Named(const std::string& name, int line) {
  for (const Variable& v : Variables()) {
    if (v.name == name && TakesStartValue(v)) return v;
  }
  throw std::invalid_argument("line " + std::to_string(line) + ": \"" + name +
                              "\" is not a parameter or input of the FMU");
}

void CheckValue(const Variable& v, const std::string& value, int line) {
  if (v.type == Type::kString) return;
  char* end = nullptr;
  const double number = std::strtod(value.c_str(), &end);
  const bool integral = v.type != Type::kEnumeration || number == std::floor(number);
  if (value.empty() || *end != '\0' || !integral) {
    throw std::invalid_argument("line " + std::to_string(line) + ": \"" + value +
                                "\" is not a valid value of " + v.name);
  }
}

}  // namespace

std::string StartNumber(double value) {
  if (std::isnan(value)) return "NaN";
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

std::string FormatStartValues(const StartValues& values) {
  std::string text = "# Start values of the wheelset FMU's parameters and inputs (wrc fmu)\n";
  for (const auto& [vr, value] : values) text += Variables().at(vr).name + " = " + value + '\n';
  return text;
}

StartValues ParseStartValues(const std::string& text) {
  StartValues values;
  std::istringstream in(text);
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    if (line.empty() || line[0] == '#') continue;
    const auto eq = line.find(" = ");
    if (eq == std::string::npos) {
      throw std::invalid_argument("line " + std::to_string(number) + " has no \" = \"");
    }
    const Variable& v = Named(line.substr(0, eq), number);
    const std::string value = line.substr(eq + 3);
    CheckValue(v, value, number);
    if (!values.emplace(v.value_reference, value).second) {
      throw std::invalid_argument("line " + std::to_string(number) + ": " + v.name +
                                  " is given twice");
    }
  }
  return values;
}

}  // namespace wrc::fmu
