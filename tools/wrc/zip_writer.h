#pragma once
// A checked RAII wrapper around libzip (Debian libzip-dev) for writing a new archive: the files
// go to PATH.tmp, which Close() renames to PATH once libzip has written it completely, so that an
// interrupted or failed write leaves no partial archive under the user's name.

#include <memory>
#include <string>
#include <vector>

struct zip;

namespace wrc::cli {

class ZipWriter {
 public:
  /// Throws InputError naming the file when it cannot be created.
  explicit ZipWriter(std::string path);
  ~ZipWriter();  ///< Discards the archive if Close() did not run.
  ZipWriter(const ZipWriter&) = delete;
  ZipWriter& operator=(const ZipWriter&) = delete;

  /// Adds a file (deflated) with Unix permissions mode; the bytes are copied.
  void Add(const std::string& name, std::string bytes, unsigned mode = 0644);
  /// Writes the archive and moves it to its path. Throws InputError naming the file on failure.
  void Close();

 private:
  [[noreturn]] void Fail(const std::string& what);

  std::string path_, temporary_;
  zip* archive_ = nullptr;
  // Kept alive until Close(): libzip reads the sources when it writes the archive.
  std::vector<std::unique_ptr<std::string>> contents_;
};

}  // namespace wrc::cli
