// Readers for Simpack (.prr/.prw), MiniProf (.ban/.whl) and plain column profile files.

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "core/geometry/profile_internal.h"
#include "core/io/case_parser.h"
#include "wrc/core/errors.h"
#include "wrc/core/profile.h"

namespace wrc {
namespace profile_detail {

std::string At(const std::string& source, int line, const std::string& message) {
  return source + ":" + std::to_string(line) + ": " + message;
}

std::optional<double> ParseNumber(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return std::nullopt;
  double value = 0.0;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  // from_chars also reports out-of-range values (1e999); they are not usable numbers either.
  if (ec != std::errc() || ptr != end) return std::nullopt;
  return value;
}

}  // namespace profile_detail

namespace {

using profile_detail::At;
using profile_detail::ParseNumber;

std::string_view Trim(std::string_view text) {
  // The "C" locale's white space, without a library call per character.
  const auto is_space = [](char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r';
  };
  while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
  return text;
}

std::string Lower(std::string_view text) {
  std::string result(text);
  for (char& c : result) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return result;
}

bool StartsWith(std::string_view text, std::string_view prefix) {
  return text.substr(0, prefix.size()) == prefix;
}

std::string Extension(const std::string& path) {
  return Lower(std::filesystem::path(path).extension().string());
}

/// A line of text shortened for messages, so that a binary file does not flood the terminal.
std::string Quote(std::string_view text) {
  constexpr std::size_t kMaxShown = 60;
  std::string shown(Trim(text).substr(0, kMaxShown));
  if (Trim(text).size() > kMaxShown) shown += "...";
  return "'" + shown + "'";
}

/// Splits at any of `separators`, dropping empty pieces (runs of spaces).
void SplitInto(std::string_view text, std::string_view separators,
               std::vector<std::string_view>& tokens) {
  tokens.clear();
  // One pass over the characters against a table of the separators (find_first_of searched
  // the separators again at every character: a third of reading a profile's point lines).
  bool separator[256] = {};
  for (const char c : separators) separator[static_cast<unsigned char>(c)] = true;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= text.size(); ++i) {
    if (i < text.size() && !separator[static_cast<unsigned char>(text[i])]) continue;
    if (i > start) tokens.push_back(text.substr(start, i - start));
    start = i + 1;
  }
}

std::vector<std::string_view> Split(std::string_view text, std::string_view separators) {
  std::vector<std::string_view> tokens;
  SplitInto(text, separators, tokens);
  return tokens;
}

/// The file's lines without line terminators (LF or CRLF). Throws for a missing, unreadable or
/// empty file.
std::vector<std::string> ReadLines(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) {
    throw InputError(path + ": cannot open profile file: no such file");
  }
  if (std::filesystem::is_directory(path, error)) {
    throw InputError(path + ": cannot open profile file: it is a directory");
  }
  std::istringstream in(io::ReadTextFile(path));  // regular files only, bounded size
  std::vector<std::string> lines;
  std::string line;
  bool any_text = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!Trim(line).empty()) any_text = true;
    lines.push_back(line);
  }
  if (!any_text) throw InputError(At(path, 1, "the profile file is empty"));
  return lines;
}

/// Checks that every value is finite; the message names the offending token.
void RequireFinite(const std::string& source, int line, const std::vector<std::string_view>& tokens,
                   const std::vector<double>& values) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw InputError(
          At(source, line, "value '" + std::string(tokens[i]) + "' is not a finite number"));
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Simpack .prr / .prw

/// Cuts a Simpack comment ('!' or '%' up to the end of the line) unless it is inside quotes,
/// as in comment = 'wheel 1 ! worn'.
std::string_view StripSimpackComment(std::string_view line) {
  char quote = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quote != 0) {
      if (c == quote) quote = 0;
    } else if (c == '\'' || c == '"') {
      quote = c;
    } else if (c == '!' || c == '%') {
      return line.substr(0, i);
    }
  }
  return line;
}

struct SimpackSetting {
  std::string value;
  int line = 0;
};

// The settings of one Simpack block (header or spline), read by key.
class SimpackSettings {
 public:
  explicit SimpackSettings(const std::string& path) : path_(path) {}
  void Set(const std::string& key, SimpackSetting setting) { map_[key] = std::move(setting); }
  bool Has(const std::string& key) const { return map_.count(key) != 0; }
  const std::string& Text(const std::string& key) const { return map_.at(key).value; }
  /// The line of `key`, 0 when the file does not have it.
  int LineOf(const std::string& key) const {
    const auto it = map_.find(key);
    return it == map_.end() ? 0 : it->second.line;
  }
  /// The numeric value of `key`, or `fallback` when the file does not have it.
  double Number(const std::string& key, double fallback) const {
    const auto it = map_.find(key);
    if (it == map_.end()) return fallback;
    const std::optional<double> value = ParseNumber(it->second.value);
    if (!value || !std::isfinite(*value)) {
      throw InputError(
          At(path_, it->second.line, key + " = '" + it->second.value + "' is not a finite number"));
    }
    return *value;
  }

 private:
  const std::string& path_;
  std::map<std::string, SimpackSetting> map_;
};

// What the block reader collects from a Simpack file.
struct SimpackFile {
  ProfilePoints points;
  SimpackSettings header, settings;  // settings: the spline block's
  std::vector<double> weights;
  int point_block_line = 0;
  explicit SimpackFile(const std::string& path) : header(path), settings(path) {}
};

// One line of the point block: y z [weight].
class SimpackPointReader {
 public:
  void Read(const std::string& path, int line_number, std::string_view text, SimpackFile& file) {
    SplitInto(text, " \t\f\v,", tokens_);
    values_.clear();
    for (const std::string_view token : tokens_) {
      const std::optional<double> value = ParseNumber(token);
      if (!value) {
        throw InputError(At(path, line_number,
                            "'" + std::string(token) + "' is not a number (in " + Quote(text) +
                                ", expected 'y z [weight]')"));
      }
      values_.push_back(*value);
    }
    if (values_.size() < 2) {
      throw InputError(At(path, line_number, "expected 'y z [weight]' but found " + Quote(text)));
    }
    RequireFinite(path, line_number, tokens_, values_);
    if (values_.size() > 3 && !warned_extra_columns_) {
      file.points.warnings.push_back(
          At(path, line_number, "columns after 'y z weight' are ignored"));
      warned_extra_columns_ = true;
    }
    file.points.y.push_back(values_[0]);
    file.points.z.push_back(values_[1]);
    file.points.lines.push_back(line_number);
    file.weights.push_back(values_.size() >= 3 ? values_[2] : 1.0);
  }

 private:
  // Reused across the lines: a profile has hundreds of point lines, and allocating per line was
  // most of reading one.
  std::vector<std::string_view> tokens_;
  std::vector<double> values_;
  bool warned_extra_columns_ = false;
};

// The header, spline and point blocks of a Simpack file, as they are written.
void ReadSimpackBlocks(const std::string& path, const std::vector<std::string>& lines,
                       SimpackFile& file) {
  enum class Block { kNone, kHeader, kSpline, kPoints };
  Block block = Block::kNone;
  bool seen_point_block = false;
  SimpackPointReader point_reader;
  for (std::size_t index = 0; index < lines.size(); ++index) {
    const int line_number = static_cast<int>(index) + 1;
    const std::string_view text = Trim(StripSimpackComment(lines[index]));
    if (text.empty()) continue;
    // Block keywords start with a letter; point lines with a digit, sign or point.
    const bool may_be_keyword = std::isalpha(static_cast<unsigned char>(text.front())) != 0;
    const std::string keyword = may_be_keyword ? Lower(text) : std::string();
    if (keyword == "header.begin") {
      block = Block::kHeader;
    } else if (keyword == "spline.begin") {
      block = Block::kSpline;
    } else if (keyword == "point.begin") {
      block = Block::kPoints;
      file.point_block_line = line_number;
      seen_point_block = true;
    } else if (keyword == "point.end") {
      if (block != Block::kPoints) {
        throw InputError(At(path, line_number, "point.end without point.begin"));
      }
      block = Block::kSpline;
    } else if (keyword == "header.end" || keyword == "spline.end") {
      if (block == Block::kPoints) {
        throw InputError(
            At(path, line_number, Quote(text) + " inside the point block (missing point.end?)"));
      }
      block = Block::kNone;
    } else if (block == Block::kPoints) {
      point_reader.Read(path, line_number, text, file);
    } else if (block == Block::kHeader || block == Block::kSpline) {
      const std::size_t equals = text.find('=');
      if (equals == std::string_view::npos) {
        file.points.warnings.push_back(At(path, line_number, "ignored line " + Quote(text)));
        continue;
      }
      SimpackSetting setting{std::string(Trim(text.substr(equals + 1))), line_number};
      auto& target = block == Block::kHeader ? file.header : file.settings;
      target.Set(Lower(Trim(text.substr(0, equals))), setting);
    } else {
      file.points.warnings.push_back(
          At(path, line_number, "ignored line outside the Simpack blocks: " + Quote(text)));
    }
  }
  if (block == Block::kPoints) {
    throw InputError(At(path, static_cast<int>(lines.size()),
                        "file ends inside the point block opened at line " +
                            std::to_string(file.point_block_line) + " (missing point.end)"));
  }
  if (!seen_point_block) {
    throw InputError(At(path, static_cast<int>(lines.size()),
                        "no point.begin ... point.end block: not a Simpack profile"));
  }
}

// The header's profile type, and what wrc reads but does not apply.
void ReadSimpackDeclarations(const std::string& path, SimpackFile& file) {
  ProfilePoints& result = file.points;
  if (file.header.Has("type")) {
    const double type = file.header.Number("type", 0.0);
    if (type == 0.0) result.declared_kind = ProfileKind::kRail;
    if (type == 1.0) result.declared_kind = ProfileKind::kWheel;
  }
  if (file.settings.Number("approx.smooth", 0.0) != 0.0) {
    result.warnings.push_back(At(path, file.settings.LineOf("approx.smooth"),
                                 "Simpack approx.smooth is ignored (as in CONTACT); use the "
                                 "smoothing option instead"));
  }
  if (std::any_of(file.weights.begin(), file.weights.end(), [](double w) { return w != 1.0; })) {
    result.warnings.push_back(At(path, file.point_block_line, "point weights are ignored"));
  }
}

// Keeps the points (with their lines) for which predicate(i, kept) holds, in order; returns
// how many were dropped.
template <class Predicate>
std::size_t KeepIf(ProfilePoints& p, Predicate predicate) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < p.y.size(); ++i) {
    if (!predicate(i, kept)) continue;
    p.y[kept] = p.y[i];
    p.z[kept] = p.z[i];
    p.lines[kept] = p.lines[i];
    ++kept;
  }
  const std::size_t dropped = p.y.size() - kept;
  p.y.resize(kept);
  p.z.resize(kept);
  p.lines.resize(kept);
  return dropped;
}

// Steps 1 and 2 of Simpack's processing: point.dist.min drops points closer than that to the
// previously kept point; then the shift.
void ApplySimpackSpacingAndShift(const std::string& path, SimpackFile& file) {
  ProfilePoints& p = file.points;
  const SimpackSettings& settings = file.settings;
  const double min_distance = settings.Number("point.dist.min", 0.0);
  if (min_distance > 0.0) {
    const std::size_t dropped = KeepIf(p, [&](std::size_t i, std::size_t kept) {
      return kept == 0 ||
             std::hypot(p.y[i] - p.y[kept - 1], p.z[i] - p.z[kept - 1]) >= min_distance;
    });
    if (dropped > 0) {
      p.warnings.push_back(At(path, settings.LineOf("point.dist.min"),
                              std::to_string(dropped) + " points dropped by point.dist.min"));
    }
  }
  const double shift_y = settings.Number("shift.y", 0.0);
  const double shift_z = settings.Number("shift.z", 0.0);
  for (std::size_t i = 0; i < p.y.size(); ++i) {
    p.y[i] += shift_y;
    p.z[i] += shift_z;
  }
}

// Steps 3 and 4: rotation (refused: its sign convention is not documented well enough to apply
// it safely) and bounds (a pair with min >= max, as Simpack writes min = 1, max = 0, means no
// bound).
void ApplySimpackRotationAndBounds(const std::string& path, SimpackFile& file) {
  ProfilePoints& p = file.points;
  const SimpackSettings& settings = file.settings;
  if (settings.Number("rotate", 0.0) != 0.0) {
    throw InputError(At(path, settings.LineOf("rotate"),
                        "rotate = '" + settings.Text("rotate") +
                            "': a non-zero Simpack 'rotate' is not supported; rotate the points "
                            "in the file instead"));
  }
  const double y_min = settings.Number("bound.y.min", 1.0);
  const double y_max = settings.Number("bound.y.max", 0.0);
  const double z_min = settings.Number("bound.z.min", 1.0);
  const double z_max = settings.Number("bound.z.max", 0.0);
  if (y_min < y_max || z_min < z_max) {
    const std::size_t dropped = KeepIf(p, [&](std::size_t i, std::size_t) {
      return (y_min >= y_max || (p.y[i] >= y_min && p.y[i] <= y_max)) &&
             (z_min >= z_max || (p.z[i] >= z_min && p.z[i] <= z_max));
    });
    if (dropped > 0) {
      p.warnings.push_back(
          At(path, file.point_block_line,
             std::to_string(dropped) + " points outside the Simpack bounds dropped"));
    }
  }
}

// Steps 5 and 6: mirroring and inversion of the point order.
void ApplySimpackMirrorAndInversion(SimpackFile& file) {
  ProfilePoints& p = file.points;
  const SimpackSettings& settings = file.settings;
  if (settings.Number("mirror.y", 0.0) != 0.0) {
    for (double& value : p.y) value = -value;
    p.mirrored_y = true;
  }
  if (settings.Number("mirror.z", 0.0) != 0.0) {
    for (double& value : p.z) value = -value;
    p.mirrored_z = true;
  }
  if (settings.Number("inversion", 0.0) != 0.0) {
    std::reverse(p.y.begin(), p.y.end());
    std::reverse(p.z.begin(), p.z.end());
    std::reverse(p.lines.begin(), p.lines.end());
  }
}

// Step 7: units.len.f is "length unit per metre": 1000 means the numbers are in mm.
void ApplySimpackUnits(const std::string& path, SimpackFile& file) {
  ProfilePoints& p = file.points;
  const SimpackSettings& settings = file.settings;
  if (!settings.Has("units.len.f")) {
    p.warnings.push_back(At(path, file.point_block_line, "no units.len.f; assuming mm"));
    return;
  }
  const double unit_per_metre = settings.Number("units.len.f", 1000.0);
  if (unit_per_metre <= 0.0) {
    throw InputError(At(path, settings.LineOf("units.len.f"),
                        "units.len.f = '" + settings.Text("units.len.f") +
                            "' must be positive (length units per metre, 1000 for mm)"));
  }
  const double to_mm = 1000.0 / unit_per_metre;
  if (to_mm != 1.0) {
    for (std::size_t i = 0; i < p.y.size(); ++i) {
      p.y[i] *= to_mm;
      p.z[i] *= to_mm;
    }
  }
}

// The blocks as written, then Simpack's own processing steps in the order its numbered
// comments give (1 to 7).
ProfilePoints ParseSimpack(const std::string& path, const std::vector<std::string>& lines) {
  SimpackFile file(path);
  file.points.format = ProfileFormat::kSimpack;
  file.points.source = path;
  ReadSimpackBlocks(path, lines, file);
  ReadSimpackDeclarations(path, file);
  ApplySimpackSpacingAndShift(path, file);
  ApplySimpackRotationAndBounds(path, file);
  ApplySimpackMirrorAndInversion(file);
  ApplySimpackUnits(path, file);
  return std::move(file.points);
}

// ---------------------------------------------------------------------------------------------
// MiniProf .ban / .whl

enum class MiniProfLine {
  kSkip,             ///< Blank, or a comment starting with '%', '!' or '#'.
  kQuoted,           ///< Starts with '"': a switched-off header line or point.
  kKeyValue,         ///< key=value header line.
  kNumeric,          ///< Two or more numbers and nothing else (after a trailing comment).
  kNumericWithText,  ///< Two or more numbers followed by text.
  kText,             ///< Anything else.
};

struct ClassifiedLine {
  MiniProfLine kind = MiniProfLine::kSkip;
  std::vector<std::string_view> tokens;  ///< The numeric tokens.
  std::vector<double> values;
  std::string_view text;  ///< The trimmed line (comment removed).
};

ClassifiedLine ClassifyMiniProfLine(std::string_view raw) {
  ClassifiedLine line;
  std::string_view text = Trim(raw);
  line.text = text;
  if (text.empty() || text.front() == '%' || text.front() == '!' || text.front() == '#') {
    line.kind = MiniProfLine::kSkip;
    return line;
  }
  if (text.front() == '"') {
    line.kind = MiniProfLine::kQuoted;
    return line;
  }
  const std::size_t equals = text.find('=');
  if (equals != std::string_view::npos && !ParseNumber(Trim(text.substr(0, equals)))) {
    line.kind = MiniProfLine::kKeyValue;
    return line;
  }
  // After the numbers, '"' starts a note as well (avg_low2.ban line 74: `... " zig-zag pattern`).
  const std::size_t comment = text.find_first_of("%!\"");
  if (comment != std::string_view::npos) text = Trim(text.substr(0, comment));
  line.text = text;
  const std::vector<std::string_view> tokens = Split(text, " \t\f\v,;");
  std::size_t numeric = 0;
  while (numeric < tokens.size()) {
    const std::optional<double> value = ParseNumber(tokens[numeric]);
    if (!value) break;
    line.tokens.push_back(tokens[numeric]);
    line.values.push_back(*value);
    ++numeric;
  }
  if (numeric >= 2) {
    line.kind = numeric == tokens.size() ? MiniProfLine::kNumeric : MiniProfLine::kNumericWithText;
  } else {
    line.kind = MiniProfLine::kText;
  }
  return line;
}

ProfilePoints ParseMiniProf(const std::string& path, const std::vector<std::string>& lines) {
  ProfilePoints result;
  result.format = ProfileFormat::kMiniProf;
  result.source = path;
  std::vector<ClassifiedLine> classified;
  classified.reserve(lines.size());
  for (const std::string& line : lines) classified.push_back(ClassifyMiniProfLine(line));

  const auto is_numeric = [](const ClassifiedLine& line) {
    return line.kind == MiniProfLine::kNumeric || line.kind == MiniProfLine::kNumericWithText;
  };
  // The data section starts at the first clean numeric line followed by two more numeric
  // lines (blank, comment and quoted lines in between do not count). A lone numeric line
  // before it, like the "Sd Sh qR" line of old wheel files, belongs to the header.
  constexpr int kRunLength = 3;
  std::size_t data_start = classified.size();
  std::size_t first_clean = classified.size();
  for (std::size_t i = 0; i < classified.size(); ++i) {
    if (classified[i].kind != MiniProfLine::kNumeric) continue;
    if (first_clean == classified.size()) first_clean = i;
    int run = 1;
    for (std::size_t j = i + 1; j < classified.size() && run < kRunLength; ++j) {
      const MiniProfLine kind = classified[j].kind;
      if (kind == MiniProfLine::kSkip || kind == MiniProfLine::kQuoted) continue;
      if (!is_numeric(classified[j])) break;
      ++run;
    }
    if (run >= kRunLength) {
      data_start = i;
      break;
    }
  }
  // Files with fewer points than a run still get a data section, so that the error about too
  // few points can name the file and line.
  if (data_start == classified.size()) data_start = first_clean;
  if (data_start == classified.size()) {
    throw InputError(At(path, static_cast<int>(lines.size()),
                        "no numeric data lines found in the MiniProf file"));
  }

  for (std::size_t i = 0; i < data_start; ++i) {
    const ClassifiedLine& line = classified[i];
    const int line_number = static_cast<int>(i) + 1;
    if (is_numeric(line)) {
      result.warnings.push_back(
          At(path, line_number,
             "numeric header line " + Quote(lines[i]) + " ignored (not part of the profile data)"));
    } else if (line.kind == MiniProfLine::kKeyValue) {
      // Offsets other than 0 would move the profile; MiniProf's exact meaning is not known to
      // wrc, so they are reported rather than applied.
      const std::string_view text = line.text;
      const std::size_t equals = text.find('=');
      const std::string key = Lower(Trim(text.substr(0, equals)));
      if (key == "xoffset" || key == "yoffset") {
        const std::optional<double> value = ParseNumber(Trim(text.substr(equals + 1)));
        if (value && *value != 0.0) {
          result.warnings.push_back(
              At(path, line_number, Quote(text) + " is not applied to the points"));
        }
      }
    }
  }
  for (std::size_t i = data_start; i < classified.size(); ++i) {
    const ClassifiedLine& line = classified[i];
    const int line_number = static_cast<int>(i) + 1;
    switch (line.kind) {
      case MiniProfLine::kSkip:
        break;
      case MiniProfLine::kQuoted:
        result.warnings.push_back(
            At(path, line_number, "switched-off point " + Quote(lines[i]) + " skipped"));
        break;
      case MiniProfLine::kKeyValue:
      case MiniProfLine::kText: {
        const std::vector<std::string_view> tokens = Split(line.text, " \t\f\v,;");
        std::string bad = tokens.empty() ? std::string(line.text) : std::string(tokens.front());
        for (const std::string_view token : tokens) {
          if (!ParseNumber(token)) {
            bad = std::string(token);
            break;
          }
        }
        throw InputError(At(path, line_number,
                            "'" + bad + "' is not a number (line " + Quote(lines[i]) +
                                " in the data section, which started at line " +
                                std::to_string(data_start + 1) + ")"));
      }
      case MiniProfLine::kNumericWithText:
        result.warnings.push_back(
            At(path, line_number, "text after the numbers ignored: " + Quote(lines[i])));
        [[fallthrough]];
      case MiniProfLine::kNumeric:
        RequireFinite(path, line_number, line.tokens, line.values);
        result.y.push_back(line.values[0]);
        result.z.push_back(line.values[1]);
        result.lines.push_back(line_number);
        break;
    }
  }
  return result;
}

// ---------------------------------------------------------------------------------------------
// Plain columns (CSV and friends)

ProfilePoints ParseTable(const std::string& path, const std::vector<std::string>& lines) {
  ProfilePoints result;
  result.format = ProfileFormat::kTable;
  result.source = path;
  int first_data_line = 0;
  for (std::size_t index = 0; index < lines.size(); ++index) {
    const int line_number = static_cast<int>(index) + 1;
    std::string_view text = Trim(lines[index]);
    const std::size_t comment = text.find_first_of("#%!");
    if (comment != std::string_view::npos) text = Trim(text.substr(0, comment));
    if (text.empty()) continue;

    // With ';' as separator a ',' is a decimal comma (spreadsheets in many locales write that).
    const bool semicolons = text.find(';') != std::string_view::npos;
    std::vector<std::string_view> tokens = Split(text, semicolons ? " \t\f\v;" : " \t\f\v,");
    std::vector<std::string> owned;
    owned.reserve(tokens.size());
    for (const std::string_view token : tokens) {
      std::string copy(token);
      if (semicolons) std::replace(copy.begin(), copy.end(), ',', '.');
      owned.push_back(std::move(copy));
    }
    std::vector<double> values;
    std::size_t bad = owned.size();
    for (std::size_t i = 0; i < owned.size(); ++i) {
      const std::optional<double> value = ParseNumber(owned[i]);
      if (!value) {
        bad = i;
        break;
      }
      values.push_back(*value);
    }
    // An empty field between two separators ("1,,2") shows up as a missing column.
    const bool empty_field = !semicolons && text.find(",,") != std::string_view::npos;
    if (first_data_line == 0) {
      if (bad < owned.size() || values.size() < 2) continue;  // Header line.
      first_data_line = line_number;
    }
    if (bad < owned.size()) {
      throw InputError(
          At(path, line_number, "'" + owned[bad] + "' is not a number (in " + Quote(text) + ")"));
    }
    if (values.size() < 2 || empty_field) {
      throw InputError(
          At(path, line_number, "expected at least two columns y, z but found " + Quote(text)));
    }
    RequireFinite(path, line_number, tokens, values);
    result.y.push_back(values[0]);
    result.z.push_back(values[1]);
    result.lines.push_back(line_number);
  }
  if (first_data_line == 0) {
    throw InputError(At(path, static_cast<int>(lines.size()),
                        "no numeric data lines with two columns y, z found"));
  }
  return result;
}

ProfileFormat SniffFormat(const std::vector<std::string>& lines) {
  bool first_text_line = true;
  for (const std::string& raw : lines) {
    const std::string text = Lower(Trim(raw));
    if (text.empty()) continue;
    if (text == "header.begin" || text == "spline.begin" || text == "point.begin") {
      return ProfileFormat::kSimpack;
    }
    if (first_text_line && (StartsWith(text, "miniprof") || StartsWith(text, "#miniwheelprof"))) {
      return ProfileFormat::kMiniProf;
    }
    if (StartsWith(text, "columndef=") || StartsWith(text, "xypoints=") ||
        StartsWith(text, "mptypeno=")) {
      return ProfileFormat::kMiniProf;
    }
    first_text_line = false;
  }
  return ProfileFormat::kTable;
}

std::optional<ProfileFormat> FormatFromExtension(const std::string& path) {
  const std::string extension = Extension(path);
  if (extension == ".prr" || extension == ".prw") return ProfileFormat::kSimpack;
  if (extension == ".ban" || extension == ".whl") return ProfileFormat::kMiniProf;
  if (extension == ".csv") return ProfileFormat::kTable;
  return std::nullopt;
}

std::string KindName(ProfileKind kind) { return kind == ProfileKind::kRail ? "rail" : "wheel"; }

}  // namespace

std::optional<ProfileKind> ProfileKindFromExtension(const std::string& path) {
  const std::string extension = Extension(path);
  if (extension == ".prr" || extension == ".ban") return ProfileKind::kRail;
  if (extension == ".prw" || extension == ".whl") return ProfileKind::kWheel;
  return std::nullopt;
}

ProfileFormat DetectProfileFormat(const std::string& path) {
  const std::vector<std::string> lines = ReadLines(path);
  if (const std::optional<ProfileFormat> format = FormatFromExtension(path)) return *format;
  return SniffFormat(lines);
}

ProfilePoints ReadProfilePoints(const std::string& path) {
  const std::vector<std::string> lines = ReadLines(path);
  const ProfileFormat format = FormatFromExtension(path).value_or(SniffFormat(lines));
  switch (format) {
    case ProfileFormat::kSimpack:
      return ParseSimpack(path, lines);
    case ProfileFormat::kMiniProf:
      return ParseMiniProf(path, lines);
    case ProfileFormat::kTable:
      break;
  }
  return ParseTable(path, lines);
}

Profile ReadProfile(const std::string& path, ProfileKind kind, const ProfileOptions& options) {
  ProfilePoints points = ReadProfilePoints(path);
  if (points.declared_kind && *points.declared_kind != kind) {
    points.warnings.push_back(path + ": the file declares a " + KindName(*points.declared_kind) +
                              " profile but is used as a " + KindName(kind) + " profile");
  } else if (const std::optional<ProfileKind> by_extension = ProfileKindFromExtension(path);
             !points.declared_kind && by_extension && *by_extension != kind) {
    points.warnings.push_back(path + ": the extension suggests a " + KindName(*by_extension) +
                              " profile but it is used as a " + KindName(kind) + " profile");
  }
  return RepairProfile(std::move(points), kind, options);
}

}  // namespace wrc
