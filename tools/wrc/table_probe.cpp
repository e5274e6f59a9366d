#include "tools/wrc/table_probe.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

#include "runtime/hdf5/hdf5.h"
#include "runtime/hdf5/table_schema.h"
#include "wrc/generator/generator.h"
#include "wrc/runtime.hpp"

namespace wrc::cli {
namespace {

// The superblock version, read without HDF5: the signature sits at byte 0, 512, 1024, 2048, …
// and the version byte follows it (HDF5 file format specification, "Superblock"). -1 when the
// path is not a regular file or no signature is found in the first 64 KiB (then HDF5's own open
// says what is wrong). Opened non-blocking and checked with fstat so that a FIFO at the path
// neither blocks the probe nor is read.
int SuperblockVersion(const std::string& path) {
  static constexpr std::array<unsigned char, 8> kSignature = {0x89, 'H',  'D',  'F',
                                                              '\r', '\n', 0x1a, '\n'};
  const int fd = open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return -1;
  struct stat info {};
  int version = -1;
  if (fstat(fd, &info) == 0 && S_ISREG(info.st_mode)) {
    for (off_t offset = 0; offset <= 65536; offset = offset == 0 ? 512 : 2 * offset) {
      std::array<unsigned char, 9> head{};
      if (pread(fd, head.data(), head.size(), offset) != static_cast<ssize_t>(head.size())) break;
      if (std::memcmp(head.data(), kSignature.data(), kSignature.size()) == 0) {
        version = head[8];
        break;
      }
    }
  }
  close(fd);
  return version;
}

// Everything the table commands read: the runtime's checks, `wrc info`'s view (axes, outputs,
// status, provenance) and the stored scene.
void ReadEverything(const std::string& path) {
  const Table validated(path);
  (void)ReadTableInfo(path);
  const h5::File file = h5::File::Open(path);
  if (file.HasAttribute(schema::kScene)) (void)file.ReadStringAttribute(schema::kScene);
}

}  // namespace

void ProbeUncheckedTable(const std::string& path) {
  const int version = SuperblockVersion(path);
  if (version < 0 || version >= 2) return;
  const pid_t child = fork();
  if (child < 0) return;  // no probe possible: the command's reads go ahead unguarded
  if (child == 0) {
    try {
      ReadEverything(path);
    } catch (...) {
      _exit(1);  // an error the parent's own reads report
    }
    _exit(0);  // _exit: neither the parent's buffered output nor its atexit handlers run twice
  }
  int status = 0;
  while (waitpid(child, &status, 0) < 0) {
    if (errno != EINTR) return;
  }
  if (WIFSIGNALED(status)) {
    throw std::runtime_error(
        path + ": damaged table: reading its HDF5 metadata crashed the HDF5 library (signal " +
        std::to_string(WTERMSIG(status)) +
        "); the file is in HDF5's earliest format, whose metadata has no checksums, so the damage "
        "is not detected otherwise. Regenerate the table (new tables carry checksums)");
  }
}

}  // namespace wrc::cli
