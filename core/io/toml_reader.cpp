#include "wrc/core/toml_reader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "wrc/core/errors.h"

namespace wrc::io {
namespace {

// Long arrays are shortened in messages; the line number says where to look.
constexpr std::size_t kMaxDescribedLength = 60;

std::string PositionPrefix(const std::string& file, const toml::source_position& where) {
  std::string prefix = file;
  if (where.line > 0) prefix += ":" + std::to_string(where.line);
  return prefix + ": ";
}

// A string as TOML writes it, control characters escaped: a message is one line of text, and a
// NUL in it would end it for every C reader of what().
std::string QuotedString(const std::string& text) {
  std::string quoted = "\"";
  for (const char c : text) {
    const auto code = static_cast<unsigned char>(c);
    if (code < 0x20 || code == 0x7f) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", code);
      quoted += escaped;
    } else {
      quoted += c;
    }
  }
  return quoted + "\"";
}

}  // namespace

std::string DescribeValue(const toml::node& node) {
  if (const auto* text = node.as_string()) return QuotedString(text->get());
  if (const auto* integer = node.as_integer()) return std::to_string(integer->get());
  if (const auto* floating = node.as_floating_point()) return FormatNumber(floating->get());
  if (const auto* boolean = node.as_boolean()) return boolean->get() ? "true" : "false";
  if (node.is_table()) return "{...}";
  if (const auto* array = node.as_array()) {
    std::string described = "[";
    for (std::size_t i = 0; i < array->size(); ++i) {
      if (i > 0) described += ", ";
      described += DescribeValue(*array->get(i));
      if (described.size() > kMaxDescribedLength) return described + ", ...]";
    }
    return described + "]";
  }
  // Dates and times: only ever wrong here, print them as TOML does.
  std::ostringstream stream;
  node.visit([&stream](const auto& value) { stream << value; });
  return stream.str();
}

int EditDistance(std::string_view a, std::string_view b) {
  // Optimal string alignment distance: a swap of two neighbours ("grdi") costs 1, like a
  // single wrong letter.
  const std::size_t rows = a.size() + 1;
  const std::size_t cols = b.size() + 1;
  std::vector<int> d(rows * cols);
  auto at = [cols, &d](std::size_t i, std::size_t j) -> int& { return d[i * cols + j]; };
  for (std::size_t i = 0; i < rows; ++i) at(i, 0) = static_cast<int>(i);
  for (std::size_t j = 0; j < cols; ++j) at(0, j) = static_cast<int>(j);
  for (std::size_t i = 1; i < rows; ++i) {
    for (std::size_t j = 1; j < cols; ++j) {
      const int substitution = a[i - 1] == b[j - 1] ? 0 : 1;
      int best = std::min({at(i - 1, j) + 1, at(i, j - 1) + 1, at(i - 1, j - 1) + substitution});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        best = std::min(best, at(i - 2, j - 2) + 1);
      }
      at(i, j) = best;
    }
  }
  return at(rows - 1, cols - 1);
}

namespace {
std::string Lowercase(std::string_view text) {
  std::string lower(text);
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower;
}
}  // namespace

std::string SuggestName(std::string_view name, const std::vector<std::string_view>& candidates) {
  // Keys are lowercase, and a capital is how users write quantities (Fz): case costs nothing.
  // Short names tolerate one edit, longer ones two; more would suggest unrelated names.
  const int limit = name.size() <= 3 ? 1 : 2;
  const std::string lower = Lowercase(name);
  std::string_view best;
  int best_distance = limit + 1;
  for (std::string_view candidate : candidates) {
    const int distance = EditDistance(lower, Lowercase(candidate));
    if (distance < best_distance) {
      best_distance = distance;
      best = candidate;
    }
  }
  return std::string(best);
}

void SourceFile::Fail(const toml::node* node, std::string_view path,
                      std::string_view problem) const {
  std::string message = name_;
  if (node != nullptr && node->source().begin.line > 0) {
    message += ":" + std::to_string(node->source().begin.line);
  }
  message += ": ";
  message += path;
  if (node != nullptr) message += " = " + DescribeValue(*node);
  message += ": ";
  message += problem;
  throw InputError(message);
}

void SourceFile::FailAt(const toml::source_position& where, std::string_view path,
                        std::string_view problem) const {
  std::string message = PositionPrefix(name_, where);
  message += path;
  message += ": ";
  message += problem;
  throw InputError(message);
}

namespace {
// HDF5's format signature, at offset 0 or after a user block of 512 · 2^k bytes.
bool LooksLikeHdf5(std::string_view text) {
  constexpr std::string_view kSignature("\x89HDF\r\n\x1a\n", 8);
  for (std::size_t offset = 0; offset + kSignature.size() <= text.size();
       offset = offset == 0 ? 512 : 2 * offset) {
    if (text.substr(offset, kSignature.size()) == kSignature) return true;
  }
  return false;
}
}  // namespace

toml::table SourceFile::Parse(std::string_view text) const {
  // A table or another binary file given where a TOML file belongs: say so, not "invalid utf-8".
  if (LooksLikeHdf5(text)) {
    throw InputError(name_ + ": an HDF5 file (a wrc table?), not a TOML case or scene file; " +
                     "'wrc info " + name_ + "' describes a table");
  }
  if (text.find('\0') != std::string_view::npos) {
    throw InputError(name_ + ": a binary file (it holds NUL bytes), not a TOML case or scene file");
  }
  try {
    return toml::parse(text, name_);
  } catch (const toml::parse_error& error) {
    const toml::source_position where = error.source().begin;
    std::string message = name_;
    if (where.line > 0) {
      message += ":" + std::to_string(where.line) + ":" + std::to_string(where.column);
    }
    message += ": TOML syntax error: ";
    message += error.description();
    throw InputError(message);
  }
}

double ReadNumber(const SourceFile& file, const toml::node& node, std::string_view path) {
  double value = 0.0;
  if (const auto* floating = node.as_floating_point()) {
    value = floating->get();
  } else if (const auto* integer = node.as_integer()) {
    value = static_cast<double>(integer->get());
  } else {
    file.Fail(&node, path, "must be a number");
  }
  if (!std::isfinite(value)) file.Fail(&node, path, "must be a finite number");
  return value;
}

Section::Section(const SourceFile& file, const toml::table& root, std::string name)
    : file_(file), name_(std::move(name)) {
  if (const toml::node* node = root.get(name_)) {
    table_ = node->as_table();
    if (table_ == nullptr) file_.Fail(node, name_, "must be a section [" + name_ + "]");
  }
}

Section::Section(const Section& parent, std::string_view key)
    : file_(parent.file_), name_(parent.name_ + "." + std::string(key)) {
  if (const toml::node* node = parent.Find(key)) {
    table_ = node->as_table();
    if (table_ == nullptr) file_.Fail(node, name_, "must be a table [" + name_ + "]");
  }
}

toml::source_position Section::position() const {
  return table_ != nullptr ? table_->source().begin : toml::source_position{0, 0};
}

const toml::node* Section::Find(std::string_view key) const {
  return table_ != nullptr ? table_->get(key) : nullptr;
}

std::string Section::Path(std::string_view key) const { return name_ + "." + std::string(key); }

void Section::Fail(std::string_view key, std::string_view problem) const {
  if (const toml::node* node = Find(key)) file_.Fail(node, Path(key), problem);
  file_.FailAt(position(), Path(key), problem);
}

void Section::FailMissing(std::string_view key, std::string_view why) const {
  std::string problem = "missing";
  if (!why.empty()) problem += " (" + std::string(why) + ")";
  file_.FailAt(position(), Path(key), problem);
}

std::optional<double> Section::OptionalNumber(std::string_view key) const {
  const toml::node* node = Find(key);
  if (node == nullptr) return std::nullopt;
  return ReadNumber(file_, *node, Path(key));
}

double Section::Number(std::string_view key, double fallback) const {
  return OptionalNumber(key).value_or(fallback);
}

double Section::RequiredNumber(std::string_view key, std::string_view why) const {
  const std::optional<double> value = OptionalNumber(key);
  if (!value) FailMissing(key, why);
  return *value;
}

bool Section::Bool(std::string_view key, bool fallback) const {
  const toml::node* node = Find(key);
  if (node == nullptr) return fallback;
  const auto* boolean = node->as_boolean();
  if (boolean == nullptr) file_.Fail(node, Path(key), "must be true or false");
  return boolean->get();
}

std::optional<std::string> Section::OptionalString(std::string_view key) const {
  const toml::node* node = Find(key);
  if (node == nullptr) return std::nullopt;
  const auto* text = node->as_string();
  if (text == nullptr) file_.Fail(node, Path(key), "must be a string");
  // No key of ours holds a NUL, and a path holding one would be cut there by the C library and
  // name another file.
  if (text->get().find('\0') != std::string::npos) {
    file_.Fail(node, Path(key), "contains a NUL character (\\u0000)");
  }
  return text->get();
}

std::vector<NumberAt> Section::NumberOrArray(std::string_view key) const {
  const toml::node* node = Find(key);
  if (node == nullptr) return {};
  if (node->is_array()) return NumberArray(key);
  return {NumberAt{ReadNumber(file_, *node, Path(key)), node, Path(key)}};
}

std::vector<NumberAt> Section::NumberArray(std::string_view key) const {
  const toml::node* node = Find(key);
  if (node == nullptr) return {};
  const toml::array* array = node->as_array();
  if (array == nullptr) file_.Fail(node, Path(key), "must be an array of numbers");
  if (array->empty()) file_.Fail(node, Path(key), "must not be empty");
  std::vector<NumberAt> numbers;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::node* element = array->get(i);
    std::string element_path = Path(key) + "[" + std::to_string(i) + "]";
    const double value = ReadNumber(file_, *element, element_path);
    numbers.push_back(NumberAt{value, element, std::move(element_path)});
  }
  return numbers;
}

}  // namespace wrc::io
