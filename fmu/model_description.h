#pragma once
// modelDescription.xml of the wheelset FMU (FMI 3.0 or 2.0 co-simulation), from the variables
// of fmu/variables.h and the start values of one table.

#include <string>

#include "fmu/start_values.h"

namespace wrc::fmu {

struct ModelDescriptionInfo {
  std::string description;      ///< What the FMU is: the table it was made from.
  std::string generation_tool;  ///< "wrc <version>".
  std::string generated_at;     ///< UTC, xs:dateTime ("2026-12-06T08:00:00Z").
  int fmi_version = 3;          ///< 3 or 2.
};

std::string ModelDescriptionXml(const StartValues& start, const ModelDescriptionInfo& info);

/// Text with &, <, >, " and ' written as XML entities; control characters other than tab and
/// line breaks, which XML 1.0 cannot hold, as spaces.
std::string XmlEscape(const std::string& text);

}  // namespace wrc::fmu
