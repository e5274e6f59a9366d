// SHA-256 through nettle (Debian's nettle-dev): a small, well-kept implementation, so tables
// carry profile hashes without wrc maintaining cryptographic code of its own.

#include <nettle/sha2.h>

#include <array>
#include <cstdint>
#include <fstream>
#include <vector>

#include "generator/sha256.h"
#include "wrc/core/errors.h"
#include "wrc/generator/generator.h"

namespace wrc {
namespace {

std::string HexDigest(sha256_ctx& context) {
  std::array<std::uint8_t, SHA256_DIGEST_SIZE> digest{};
  sha256_digest(&context, digest.size(), digest.data());
  static constexpr char kHex[] = "0123456789abcdef";
  std::string hex;
  hex.reserve(2 * digest.size());
  for (const std::uint8_t byte : digest) {
    hex += kHex[byte >> 4];
    hex += kHex[byte & 0xF];
  }
  return hex;
}

}  // namespace

std::string Sha256Hex(std::string_view bytes) {
  sha256_ctx context;
  sha256_init(&context);
  sha256_update(&context, bytes.size(), reinterpret_cast<const std::uint8_t*>(bytes.data()));
  return HexDigest(context);
}

std::string Sha256FileHex(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open the file to hash it");
  sha256_ctx context;
  sha256_init(&context);
  std::vector<char> buffer(1 << 16);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    const std::streamsize got = in.gcount();
    if (got > 0) {
      sha256_update(&context, static_cast<std::size_t>(got),
                    reinterpret_cast<const std::uint8_t*>(buffer.data()));
    }
  }
  if (in.bad()) throw InputError(path.string() + ": read error while hashing the file");
  return HexDigest(context);
}

void CheckStoredProfileDigest(const std::string& table, const std::string& name,
                              std::string_view bytes, const std::string& recorded) {
  if (recorded.empty()) return;
  const std::string actual = Sha256Hex(bytes);
  if (actual == recorded) return;
  throw InputError(table + ":/profiles/" + name + ": its SHA-256 " + actual + " differs from " +
                   name + "_profile_sha256 " + recorded + " (the profile was damaged or replaced)");
}

}  // namespace wrc
