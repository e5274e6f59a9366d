// Safe output files (include/wrc/core/output_file.h), on POSIX descriptors: the standard streams
// cannot open exclusively, refuse symlinks or report a failed close.

#include "wrc/core/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>

#include "wrc/core/errors.h"

namespace wrc {
namespace {

[[noreturn]] void Fail(const std::filesystem::path& path, const std::string& what) {
  throw InputError(path.string() + ": " + what + ": " + std::strerror(errno));
}

// What lstat finds at path: false when nothing is there.
bool Inspect(const std::filesystem::path& path, struct stat* info) {
  if (::lstat(path.c_str(), info) == 0) return true;
  if (errno == ENOENT) return false;
  Fail(path, "cannot inspect the output path");
}

std::string KindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISLNK(mode)) return "a symbolic link";
  return "not a regular file";
}

void WriteAll(int fd, std::string_view text, const std::filesystem::path& path) {
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      Fail(path, "cannot write");
    }
    text.remove_prefix(static_cast<std::size_t>(n));
  }
}

}  // namespace

void RequireNotAnInput(const std::filesystem::path& output,
                       const std::vector<std::filesystem::path>& inputs) {
  std::error_code ignored;
  const std::filesystem::path normal = std::filesystem::weakly_canonical(output, ignored);
  for (const std::filesystem::path& input : inputs) {
    if (input.empty()) continue;
    const bool same =
        std::filesystem::equivalent(output, input, ignored) ||
        (!normal.empty() && normal == std::filesystem::weakly_canonical(input, ignored));
    if (same) {
      throw InputError(output.string() + ": is also an input of this command (" + input.string() +
                       "); writing there would overwrite it");
    }
  }
}

void RequireRegularOutput(const std::filesystem::path& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) {
    if (errno == ENOENT) {
      // Nothing there, or a dangling symlink: a dangling one would be followed on creation.
      struct stat link {};
      if (Inspect(path, &link) && S_ISLNK(link.st_mode)) {
        throw InputError(path.string() +
                         ": is a dangling symbolic link, refusing to write "
                         "through it");
      }
      return;
    }
    Fail(path, "cannot inspect the output path");
  }
  if (!S_ISREG(info.st_mode)) {
    throw InputError(path.string() + ": is " + KindOf(info.st_mode) +
                     ", refusing to replace it with an output file");
  }
}

void CreateExclusively(const std::filesystem::path& path) {
  struct stat info {};
  if (Inspect(path, &info)) {
    if (!S_ISREG(info.st_mode)) {
      throw InputError(path.string() + ": is " + KindOf(info.st_mode) +
                       ", refusing to use it as a temporary file");
    }
    if (::unlink(path.c_str()) != 0) Fail(path, "cannot remove the leftover temporary file");
  }
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) Fail(path, "cannot create the temporary file");
  if (::close(fd) != 0) Fail(path, "cannot close the temporary file");
}

void WriteFileAtomically(const std::filesystem::path& path, std::string_view text) {
  RequireRegularOutput(path);
  std::filesystem::path temporary = path;
  temporary += ".tmp";
  CreateExclusively(temporary);
  // Removes the temporary file unless it was renamed into place.
  struct Cleanup {
    const std::filesystem::path& file;
    bool done = false;
    ~Cleanup() {
      if (!done) ::unlink(file.c_str());
    }
  } cleanup{temporary};
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_TRUNC | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) Fail(temporary, "cannot open the temporary file");
  try {
    WriteAll(fd, text, temporary);
    if (::fsync(fd) != 0) Fail(temporary, "cannot sync");
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0) Fail(temporary, "cannot close");
  if (::rename(temporary.c_str(), path.c_str()) != 0) Fail(path, "cannot rename into place");
  cleanup.done = true;
}

void FinishStandardOutput() {
  std::cout.flush();
  const bool failed = !std::cout || std::fflush(stdout) != 0 || std::ferror(stdout) != 0;
  if (failed) throw InputError("standard output: cannot write (disk full or closed?)");
}

}  // namespace wrc
