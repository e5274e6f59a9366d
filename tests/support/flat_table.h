#pragma once
/// @file flat_table.h
/// Test support: a flat table's bytes (runtime/format/flat_table.h) with the size and SHA-256 of
/// their header made to match again, so that damage behind the digest reaches the parser (the
/// runtime's tests forge bodies with it, the flat table fuzzer reseals its inputs).

#include <nettle/sha2.h>

#include <cstdint>
#include <string>

namespace wrc::test {

inline std::string ResealedFlatTable(std::string bytes) {
  constexpr std::size_t kSize = 16, kDigest = 24, kDigestEnd = 56;
  if (bytes.size() < kDigestEnd) return bytes;
  const std::uint64_t size = bytes.size();
  for (int i = 0; i < 8; ++i) bytes[kSize + i] = static_cast<char>((size >> (8 * i)) & 0xFF);
  sha256_ctx context;
  sha256_init(&context);
  sha256_update(&context, bytes.size() - kDigestEnd,
                reinterpret_cast<const std::uint8_t*>(&bytes[kDigestEnd]));
  sha256_digest(&context, SHA256_DIGEST_SIZE, reinterpret_cast<std::uint8_t*>(&bytes[kDigest]));
  return bytes;
}

}  // namespace wrc::test
