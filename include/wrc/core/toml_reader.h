#pragma once
/// @file toml_reader.h
/// Typed access to TOML values that turns every problem into an InputError "file:line:
/// key.path = value: problem": what the case and scene parsers read with, and what the tools use
/// for their own input files (the dynamics model, the planar audit) so that their messages read
/// the same. Needs toml++ on the include path.

#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <toml++/toml.h>

#include "wrc/core/errors.h"

namespace wrc::io {

/// A value as written in the file, for messages: strings quoted, numbers in shortest form,
/// arrays element by element (abbreviated when long), tables as "{...}".
std::string DescribeValue(const toml::node& node);

/// A number in its shortest exact form ("0.1", "-20", "1e+12", "nan"); see wrc/core/errors.h.
using wrc::FormatNumber;

/// Edit distance (insertions, deletions, substitutions and swaps of neighbours), used to
/// suggest the intended name for a typo.
int EditDistance(std::string_view a, std::string_view b);

/// The closest of `candidates` to `name` when it is close enough to be a likely typo; empty
/// otherwise.
std::string SuggestName(std::string_view name, const std::vector<std::string_view>& candidates);

/// Names a source file in messages and throws the InputErrors.
class SourceFile {
 public:
  explicit SourceFile(std::string display_name) : name_(std::move(display_name)) {}
  const std::string& name() const { return name_; }

  /// Throws "name:line: path = value: problem". `node` may be null (no value, no line).
  [[noreturn]] void Fail(const toml::node* node, std::string_view path,
                         std::string_view problem) const;
  /// Throws "name:line: path: problem" at `where` (no line when `where` is unknown).
  [[noreturn]] void FailAt(const toml::source_position& where, std::string_view path,
                           std::string_view problem) const;

  /// Parses TOML text; syntax errors become "name:line:column: TOML syntax error: ...".
  toml::table Parse(std::string_view text) const;

 private:
  std::string name_;
};

/// A number read from the file together with where it came from, so that checks done later
/// (ordering, lengths) can still point at the right line.
struct NumberAt {
  double value = 0.0;
  const toml::node* node = nullptr;
  std::string path;
};

/// The finite number held by `node` (integers are accepted); throws for other types or
/// NaN / infinity.
double ReadNumber(const SourceFile& file, const toml::node& node, std::string_view path);

/// Read access to one `[section]` of a document. A missing section behaves like an empty one,
/// so that defaults apply.
class Section {
 public:
  Section(const SourceFile& file, const toml::table& root, std::string name);
  /// The sub-table `key` of another section, named "parent.key" in messages.
  Section(const Section& parent, std::string_view key);

  const SourceFile& file() const { return file_; }
  const std::string& name() const { return name_; }
  bool exists() const { return table_ != nullptr; }
  /// The section header's position (unknown when the section is absent).
  toml::source_position position() const;

  const toml::node* Find(std::string_view key) const;
  bool Has(std::string_view key) const { return Find(key) != nullptr; }
  /// "section.key".
  std::string Path(std::string_view key) const;

  /// Throws for the value at `key` (or for the section itself when the key is absent).
  [[noreturn]] void Fail(std::string_view key, std::string_view problem) const;
  /// Throws "section.key: missing (...)" pointing at the section header when there is one.
  [[noreturn]] void FailMissing(std::string_view key, std::string_view why) const;

  std::optional<double> OptionalNumber(std::string_view key) const;
  double Number(std::string_view key, double fallback) const;
  double RequiredNumber(std::string_view key, std::string_view why) const;
  bool Bool(std::string_view key, bool fallback) const;
  std::optional<std::string> OptionalString(std::string_view key) const;
  /// A number or an array of numbers; each element with its own path "section.key[i]".
  std::vector<NumberAt> NumberOrArray(std::string_view key) const;
  /// An array of numbers (a single number is a type error).
  std::vector<NumberAt> NumberArray(std::string_view key) const;

  /// One of a fixed set of strings, mapped to its enumerator; the message lists the allowed
  /// strings.
  template <typename Enum>
  Enum Choice(std::string_view key,
              std::initializer_list<std::pair<std::string_view, Enum>> options,
              Enum fallback) const {
    const std::optional<std::string> text = OptionalString(key);
    if (!text) return fallback;
    std::string allowed;
    for (const auto& [option_text, value] : options) {
      if (*text == option_text) return value;
      allowed += allowed.empty() ? "" : ", ";
      allowed += "\"" + std::string(option_text) + "\"";
    }
    Fail(key, "must be one of " + allowed);
  }

 private:
  const SourceFile& file_;
  std::string name_;
  const toml::table* table_ = nullptr;

 public:
  /// The section's table (null when absent), for iterating over its keys.
  const toml::table* table() const { return table_; }
};

}  // namespace wrc::io
