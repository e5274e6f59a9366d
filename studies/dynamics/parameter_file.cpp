// Schema and sign checks of the dynamics parameter files (parameter_file.h).

#include "studies/dynamics/parameter_file.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "wrc/core/errors.h"

namespace wrc::dynamics {

void CheckParameterNames(const toml::table& root, const io::SourceFile& file,
                         const ParameterSchema& schema) {
  std::vector<std::string_view> sections;
  std::string allowed;
  for (const auto& entry : schema) {
    sections.push_back(entry.first);
    allowed += (allowed.empty() ? "[" : ", [") + std::string(entry.first) + "]";
  }
  for (const auto& [key, node] : root) {
    const auto known = std::find_if(schema.begin(), schema.end(),
                                    [&](const auto& s) { return s.first == key.str(); });
    if (known == schema.end()) {
      const std::string suggestion = io::SuggestName(key.str(), sections);
      file.Fail(&node, key.str(),
                "unknown section" +
                    (suggestion.empty() ? "" : " (did you mean [" + suggestion + "]?)") +
                    "; allowed: " + allowed);
    }
    if (!node.is_table()) file.Fail(&node, key.str(), "must be a section");
    for (const auto& [inner, inner_node] : *node.as_table()) {
      const auto& keys = known->second;
      if (std::find(keys.begin(), keys.end(), inner.str()) != keys.end()) continue;
      const std::string suggestion = io::SuggestName(inner.str(), keys);
      file.Fail(&inner_node, std::string(key.str()) + "." + std::string(inner.str()),
                "unknown key" + (suggestion.empty() ? "" : " (did you mean " + suggestion + "?)"));
    }
  }
}

double CheckedNumber(const io::Section& s, std::string_view key, bool allow_zero, double fallback) {
  const double v =
      std::isnan(fallback) ? s.RequiredNumber(key, "the model needs it") : s.Number(key, fallback);
  if (v < 0.0 || (!allow_zero && v == 0.0)) {
    s.Fail(key, allow_zero ? "must not be negative" : "must be positive");
  }
  return v;
}

SimulationSettings ReadSimulation(const io::Section& sim, double default_duration,
                                  double default_initial_y) {
  SimulationSettings settings;
  settings.time_step = CheckedNumber(sim, "time_step", false, settings.time_step);
  settings.duration = CheckedNumber(sim, "duration", false, default_duration);
  settings.initial_y = sim.Number("initial_y", default_initial_y);
  if (settings.time_step > settings.duration) {
    sim.Fail("time_step", "must not exceed simulation.duration");
  }
  if (settings.duration / settings.time_step > 1e8) sim.Fail("duration", "more than 10^8 steps");
  return settings;
}

std::string ReadParameterFile(const std::filesystem::path& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot open the " + what + " file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace wrc::dynamics
