#include "tools/wrc/gnuplot.h"

#include <cstdlib>
#include <fstream>

namespace wrc::cli {

bool RunGnuplotScript(const std::filesystem::path& script, const std::filesystem::path& dir) {
  std::string command = "gnuplot '" + script.string() + "'";
  if (!dir.empty()) command = "cd '" + dir.string() + "' && " + command;
  return std::system(command.c_str()) == 0;
}

bool RunGnuplot(const std::filesystem::path& dir, const std::string& script_name,
                const std::string& text) {
  std::ofstream(dir / script_name) << text;
  return RunGnuplotScript(script_name, dir);
}

}  // namespace wrc::cli
