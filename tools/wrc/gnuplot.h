#pragma once
// Pictures of the `wrc` subcommands: every PNG is drawn by gnuplot from a script written next to
// its data, so that a user can change the script and draw it again.

#include <filesystem>
#include <string>

namespace wrc::cli {

/// Writes `text` to dir/script_name (atomically) and runs it with gnuplot in `dir` (the script
/// names its data files relative to it). Each PNG of the script's `set output 'NAME'` lines is
/// drawn to NAME.tmp, checked to be a whole PNG and renamed into place, so that a picture is
/// either complete or absent. False when gnuplot is not installed (the caller says what is lost:
/// a picture, never the data); throws InputError naming the picture when gnuplot fails or a
/// picture comes out incomplete (a full disk).
bool RunGnuplot(const std::filesystem::path& dir, const std::string& script_name,
                const std::string& text);

}  // namespace wrc::cli
