#pragma once
// Pictures of the `wrc` subcommands: every PNG is drawn by gnuplot from a script written next to
// its data, so that a user can change the script and draw it again.

#include <filesystem>
#include <string>

namespace wrc::cli {

/// Runs gnuplot on `script`; with `dir` given, in that directory (the script then names its data
/// files relative to it). gnuplot's own messages go to stderr. False when gnuplot is missing or
/// fails: the caller says what is lost (a picture, never the data).
bool RunGnuplotScript(const std::filesystem::path& script, const std::filesystem::path& dir = {});

/// Writes `text` to dir/script_name and runs it in `dir` (RunGnuplotScript).
bool RunGnuplot(const std::filesystem::path& dir, const std::string& script_name,
                const std::string& text);

}  // namespace wrc::cli
