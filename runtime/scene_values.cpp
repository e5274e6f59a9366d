// Single values from a table's scene text (scene_values.h).

#include "runtime/scene_values.h"

#include <cerrno>
#include <cstdlib>

namespace wrc::runtime {
namespace {

std::string_view Trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

// The line without its comment: a '#' outside a double-quoted string starts one.
std::string_view StripComment(std::string_view line) {
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] == '"') quoted = !quoted;
    if (line[i] == '#' && !quoted) return line.substr(0, i);
  }
  return line;
}

// "[name]" → name; nothing for other lines (array-of-tables headers included).
std::optional<std::string_view> SectionHeader(std::string_view line) {
  if (line.size() < 3 || line.front() != '[' || line.back() != ']' || line[1] == '[') return {};
  return Trim(line.substr(1, line.size() - 2));
}

}  // namespace

std::optional<std::string> SceneValueText(std::string_view scene, std::string_view section,
                                          std::string_view key) {
  std::string_view current;
  while (!scene.empty()) {
    const auto end = scene.find('\n');
    const std::string_view line = Trim(StripComment(scene.substr(0, end)));
    scene = end == std::string_view::npos ? std::string_view{} : scene.substr(end + 1);
    if (const auto header = SectionHeader(line)) {
      current = *header;
      continue;
    }
    const auto equals = line.find('=');
    if (current != section || equals == std::string_view::npos) continue;
    if (Trim(line.substr(0, equals)) == key) return std::string(Trim(line.substr(equals + 1)));
  }
  return {};
}

std::optional<double> SceneNumber(std::string_view scene, std::string_view section,
                                  std::string_view key) {
  const auto text = SceneValueText(scene, section, key);
  if (!text || text->empty()) return {};
  std::string digits;  // TOML allows 1_000.0; strtod does not
  for (const char c : *text) {
    if (c != '_') digits += c;
  }
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(digits.c_str(), &end);
  if (errno != 0 || end != digits.c_str() + digits.size()) return {};
  return value;
}

std::optional<std::string> SceneString(std::string_view scene, std::string_view section,
                                       std::string_view key) {
  const auto text = SceneValueText(scene, section, key);
  if (!text || text->size() < 2 || text->front() != '"' || text->back() != '"') return {};
  return text->substr(1, text->size() - 2);
}

}  // namespace wrc::runtime
