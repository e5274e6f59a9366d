// SHA-256 against the FIPS 180-2 / NIST test vectors, and file hashing against the same.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "generator/sha256.h"
#include "wrc/core/errors.h"
#include "wrc/generator/generator.h"

namespace wrc {
namespace {

TEST(Sha256, KnownVectors) {
  EXPECT_EQ(Sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(Sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(Sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(Sha256Hex(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, FileHashEqualsTheHashOfItsBytes) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("wrc_sha256_" + std::to_string(::getpid()));
  // Larger than the 64 KiB read buffer, so the streaming path is exercised across reads.
  std::string bytes;
  for (int i = 0; i < 200000; ++i) bytes += static_cast<char>(i * 7 % 251);
  std::ofstream(path, std::ios::binary) << bytes;
  EXPECT_EQ(Sha256FileHex(path), Sha256Hex(bytes));
  std::filesystem::remove(path);
  EXPECT_THROW(Sha256FileHex(path), InputError);
}

}  // namespace
}  // namespace wrc
