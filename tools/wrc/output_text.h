#pragma once
// Text outputs of the `wrc` subcommands (CSV, data, scripts, summaries): built in memory and
// written in one go through WriteFileAtomically, so that a full disk or a file that cannot be
// replaced is an error naming the file, never a short file left under its name.

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <sstream>
#include <string>
#include <utility>

#include "wrc/core/output_file.h"

namespace wrc::cli {

/// An output file's text: stream into it, then Commit() writes it (throws InputError on failure).
/// Leaving scope without Commit() other than by an exception is a programming error and aborts,
/// so that no output can be dropped unnoticed.
class OutputText : public std::ostringstream {
 public:
  explicit OutputText(std::filesystem::path path) : path_(std::move(path)) {}
  OutputText(const OutputText&) = delete;
  OutputText& operator=(const OutputText&) = delete;
  ~OutputText() override {
    if (committed_ || std::uncaught_exceptions() > exceptions_) return;
    std::fprintf(stderr, "wrc: internal error: %s was never written\n", path_.c_str());
    std::abort();
  }

  void Commit() {
    committed_ = true;  // also when writing throws: the error is the report
    WriteFileAtomically(path_, str());
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  int exceptions_ = std::uncaught_exceptions();
  bool committed_ = false;
};

}  // namespace wrc::cli
