// The seal through nettle's SHA-256 (Debian nettle-dev), the same well-kept implementation the
// generator hashes profiles with.

#include "runtime/hdf5/seal.h"

#include <fcntl.h>
#include <nettle/sha2.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <vector>

namespace wrc::h5 {
namespace {

constexpr char kMagic[] = "wrc-seal 1\n";
constexpr char kHdf5Signature[] = "\x89HDF\r\n\x1a\n";

// An open file descriptor, closed on scope exit.
class Fd {
 public:
  Fd(const std::string& path, int flags) : fd_(::open(path.c_str(), flags | O_CLOEXEC)) {
    if (fd_ < 0) throw Error(path + ":/", std::string("cannot open: ") + std::strerror(errno));
  }
  ~Fd() { ::close(fd_); }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

// Reads up to n bytes at offset; fewer only at the end of the file.
std::size_t ReadAt(const Fd& fd, const std::string& path, char* out, std::size_t n, off_t offset) {
  std::size_t done = 0;
  while (done < n) {
    const ssize_t got = ::pread(fd.get(), out + done, n - done, offset + static_cast<off_t>(done));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw Error(path + ":/", std::string("cannot read: ") + std::strerror(errno));
    if (got == 0) break;
    done += static_cast<std::size_t>(got);
  }
  return done;
}

// The seal's record for a file whose bytes after the user block have this digest and size,
// padded with NULs to the whole block: a reader compares all of the block, so a damaged byte
// in the padding counts as damage too.
std::array<char, kUserBlockSize> Record(const std::string& sha256_hex, std::uint64_t bytes) {
  std::array<char, kUserBlockSize> block{};
  const std::string text =
      std::string(kMagic) + "sha256 " + sha256_hex + "\nbytes " + std::to_string(bytes) + "\n";
  std::memcpy(block.data(), text.data(), text.size());
  return block;
}

// The digest of everything fed to `context`, as lowercase hex.
std::string HexDigest(sha256_ctx* context) {
  std::array<std::uint8_t, SHA256_DIGEST_SIZE> digest{};
  sha256_digest(context, digest.size(), digest.data());
  static constexpr char kHex[] = "0123456789abcdef";
  std::string hex;
  hex.reserve(2 * digest.size());
  for (const std::uint8_t b : digest) {
    hex += kHex[b >> 4];
    hex += kHex[b & 0xF];
  }
  return hex;
}

// SHA-256 (lowercase hex) and count of the bytes after the user block.
std::string DigestAfterUserBlock(const Fd& fd, const std::string& path, std::uint64_t* bytes) {
  sha256_ctx context;
  sha256_init(&context);
  std::vector<char> buffer(1 << 20);
  off_t offset = static_cast<off_t>(kUserBlockSize);
  *bytes = 0;
  for (;;) {
    const std::size_t got = ReadAt(fd, path, buffer.data(), buffer.size(), offset);
    if (got == 0) break;
    sha256_update(&context, got, reinterpret_cast<const std::uint8_t*>(buffer.data()));
    offset += static_cast<off_t>(got);
    *bytes += got;
  }
  return HexDigest(&context);
}

}  // namespace

std::string Sha256Hex(std::string_view bytes) {
  sha256_ctx context;
  sha256_init(&context);
  sha256_update(&context, bytes.size(), reinterpret_cast<const std::uint8_t*>(bytes.data()));
  return HexDigest(&context);
}

void SealFile(const std::string& path) {
  const Fd fd(path, O_RDWR);
  std::array<char, kUserBlockSize> block{};
  // An empty user block, or the seal of an earlier version of the file (sealed again after
  // an edit).
  if (ReadAt(fd, path, block.data(), block.size(), 0) != block.size() ||
      !(std::all_of(block.begin(), block.end(), [](char c) { return c == 0; }) ||
        std::memcmp(block.data(), kMagic, sizeof kMagic - 1) == 0)) {
    throw Error(path + ":/", "cannot seal: the file has no user block of " +
                                 std::to_string(kUserBlockSize) + " bytes");
  }
  std::uint64_t bytes = 0;
  const std::string digest = DigestAfterUserBlock(fd, path, &bytes);
  const std::array<char, kUserBlockSize> record = Record(digest, bytes);
  std::size_t done = 0;
  while (done < record.size()) {
    const ssize_t put =
        ::pwrite(fd.get(), record.data() + done, record.size() - done, static_cast<off_t>(done));
    if (put < 0 && errno == EINTR) continue;
    if (put <= 0) throw Error(path + ":/", std::string("cannot seal: ") + std::strerror(errno));
    done += static_cast<std::size_t>(put);
  }
  if (::fsync(fd.get()) != 0) {
    throw Error(path + ":/", std::string("cannot seal: ") + std::strerror(errno));
  }
}

SealStatus CheckSeal(const std::string& path) {
  const Fd fd(path, O_RDONLY);
  std::array<char, kUserBlockSize> block{};
  const std::size_t head = ReadAt(fd, path, block.data(), block.size(), 0);
  if (head >= sizeof kHdf5Signature - 1 &&
      std::memcmp(block.data(), kHdf5Signature, sizeof kHdf5Signature - 1) == 0) {
    // The superblock's version byte follows the signature (HDF5 file format specification,
    // "Superblock"); versions 0 and 1 carry no metadata checksums.
    const auto version = static_cast<unsigned char>(block[sizeof kHdf5Signature - 1]);
    return head > sizeof kHdf5Signature - 1 && version >= 2 ? SealStatus::kUnsealed
                                                            : SealStatus::kUnsealedEarliest;
  }
  if (head < block.size() || std::memcmp(block.data(), kMagic, sizeof kMagic - 1) != 0) {
    // HDF5's signature right after the user block: a sealed table whose seal is damaged.
    char after[sizeof kHdf5Signature - 1] = {};
    if (ReadAt(fd, path, after, sizeof after, static_cast<off_t>(kUserBlockSize)) == sizeof after &&
        std::memcmp(after, kHdf5Signature, sizeof after) == 0) {
      throw SealError(path + ":/", "damaged: the seal in its first " +
                                       std::to_string(kUserBlockSize) +
                                       " bytes is unreadable; regenerate it or copy it again");
    }
    throw Error(path + ":/",
                "not a wrc table: neither a seal (\"wrc-seal\") nor HDF5's "
                "signature at its start");
  }
  std::uint64_t bytes = 0;
  const std::string digest = DigestAfterUserBlock(fd, path, &bytes);
  if (Record(digest, bytes) != block) {
    throw SealError(path + ":/",
                    "damaged: its bytes do not match the SHA-256 sealed in its first " +
                        std::to_string(kUserBlockSize) +
                        " bytes when it was written (a changed, truncated or extended file); "
                        "regenerate it or copy it again");
  }
  return SealStatus::kIntact;
}

}  // namespace wrc::h5
