#pragma once
// Case and scene files for tests: a starting text (a shipped case, or any TOML) with keys set,
// replaced or removed section by section, written where the test wants it. Line-based: one
// `key = value` per line, as the shipped files and the docs write them.

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/files.h"

namespace wrc::test_support {

class CaseBuilder {
 public:
  explicit CaseBuilder(const std::string& text) {
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines_.push_back(line);
  }

  /// A case file of tables/ (e.g. "mbench_case.toml"), its profile paths made absolute so that
  /// the case can be written anywhere.
  static CaseBuilder Shipped(const std::string& name) {
    const std::filesystem::path tables = std::filesystem::path(WRC_SOURCE_DIR) / "tables";
    std::string text = ReadFile(tables / name);
    const std::string relative = "\"profiles/";
    const std::string absolute = "\"" + (tables / "profiles").string() + "/";
    for (std::size_t at = text.find(relative); at != std::string::npos;
         at = text.find(relative, at + absolute.size())) {
      text.replace(at, relative.size(), absolute);
    }
    return CaseBuilder(text);
  }

  /// `key = value` in [section] (value as TOML writes it: "0.5", "\"curved\"", "[1, 2]"),
  /// replacing the key's line if the section has one; the section is added if missing.
  CaseBuilder& Set(const std::string& section, const std::string& key, const std::string& value) {
    const std::string line = key + " = " + value;
    const std::size_t header = FindSection(section);
    if (header == lines_.size()) {
      lines_.push_back("[" + section + "]");
      lines_.push_back(line);
      return *this;
    }
    const std::size_t at = FindKey(header, key);
    if (at < lines_.size()) {
      lines_[at] = line;
    } else {
      lines_.insert(lines_.begin() + static_cast<std::ptrdiff_t>(header) + 1, line);
    }
    return *this;
  }

  /// Removes `key` from [section]; nothing when it is not there.
  CaseBuilder& Remove(const std::string& section, const std::string& key) {
    const std::size_t header = FindSection(section);
    if (header == lines_.size()) return *this;
    const std::size_t at = FindKey(header, key);
    if (at < lines_.size()) lines_.erase(lines_.begin() + static_cast<std::ptrdiff_t>(at));
    return *this;
  }

  std::string Text() const {
    std::string text;
    for (const std::string& line : lines_) text += line + "\n";
    return text;
  }

  std::filesystem::path Write(const std::filesystem::path& path) const {
    return WriteFile(path, Text());
  }

 private:
  static std::string Trimmed(const std::string& s) {
    const std::size_t first = s.find_first_not_of(" \t");
    if (first == std::string::npos) return {};
    return s.substr(first, s.find_last_not_of(" \t") + 1 - first);
  }
  // The line of "[section]", or lines_.size().
  std::size_t FindSection(const std::string& section) const {
    for (std::size_t i = 0; i < lines_.size(); ++i) {
      if (Trimmed(lines_[i]) == "[" + section + "]") return i;
    }
    return lines_.size();
  }
  // The line of `key = ...` after the header and before the next section, or lines_.size().
  std::size_t FindKey(std::size_t header, const std::string& key) const {
    for (std::size_t i = header + 1; i < lines_.size(); ++i) {
      const std::string line = Trimmed(lines_[i]);
      if (!line.empty() && line[0] == '[') break;
      if (line.compare(0, key.size(), key) != 0) continue;
      const std::string rest = Trimmed(line.substr(key.size()));
      if (!rest.empty() && rest[0] == '=') return i;
    }
    return lines_.size();
  }

  std::vector<std::string> lines_;
};

}  // namespace wrc::test_support
