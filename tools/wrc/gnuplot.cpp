#include "tools/wrc/gnuplot.h"

#include <signal.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <system_error>
#include <vector>

#include "wrc/core/errors.h"
#include "wrc/core/output_file.h"

namespace wrc::cli {
namespace {

namespace fs = std::filesystem;

const std::regex kSetOutput(R"(set output '([^']+)')");

// The pictures a script draws: the names of its `set output '...'` lines.
std::vector<std::string> OutputNames(const std::string& text) {
  std::vector<std::string> names;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), kSetOutput);
       it != std::sregex_iterator(); ++it) {
    names.push_back((*it)[1].str());
  }
  return names;
}

// A PNG is whole when it starts with the PNG signature and ends with the IEND chunk, the last
// thing the encoder writes.
bool IsWholePng(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  static const std::string kSignature("\x89PNG\r\n\x1a\n", 8);
  static const std::string kEnd("\0\0\0\0IEND\xae\x42\x60\x82", 12);
  return bytes.size() >= kSignature.size() + kEnd.size() &&
         bytes.compare(0, kSignature.size(), kSignature) == 0 &&
         bytes.compare(bytes.size() - kEnd.size(), kEnd.size(), kEnd) == 0;
}

// gnuplot reading the script from a pipe, in `dir`; its exit status (127: not installed).
int Gnuplot(const fs::path& dir, const std::string& text) {
  const std::string command = "cd '" + dir.string() + "' && gnuplot";
  // A gnuplot that is missing or stops early closes the pipe: a write error, not SIGPIPE.
  struct sigaction ignore {
  }, previous{};
  ignore.sa_handler = SIG_IGN;
  ::sigaction(SIGPIPE, &ignore, &previous);
  std::FILE* pipe = ::popen(command.c_str(), "w");
  bool written = false;
  int status = -1;
  if (pipe != nullptr) {
    written = std::fwrite(text.data(), 1, text.size(), pipe) == text.size();
    status = ::pclose(pipe);
  }
  ::sigaction(SIGPIPE, &previous, nullptr);
  if (pipe == nullptr) return 127;
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return code == 0 && !written ? -1 : code;
}

void RemoveQuietly(const fs::path& path) {
  std::error_code ignored;
  fs::remove(path, ignored);
}

}  // namespace

bool RunGnuplot(const fs::path& dir, const std::string& script_name, const std::string& text) {
  const fs::path base = dir.empty() ? fs::path(".") : dir;
  WriteFileAtomically(base / script_name, text);
  const std::vector<std::string> names = OutputNames(text);
  for (const std::string& name : names) RequireRegularOutput(base / name);
  const std::string drawn = std::regex_replace(text, kSetOutput, "set output '$1.tmp'");
  const int status = Gnuplot(base, drawn);
  std::string incomplete;
  for (const std::string& name : names) {
    const fs::path tmp = base / (name + ".tmp");
    if (status == 0 && IsWholePng(tmp)) {
      fs::rename(tmp, base / name);
    } else {
      if (incomplete.empty()) incomplete = (base / name).string();
      RemoveQuietly(tmp);
    }
  }
  if (status == 127) return false;
  if (status != 0 || !incomplete.empty()) {
    throw InputError("gnuplot could not draw " + incomplete + " from " +
                     (base / script_name).string() + " (exit status " + std::to_string(status) +
                     "; is the disk full?)");
  }
  return true;
}

}  // namespace wrc::cli
