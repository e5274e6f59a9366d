#pragma once
// SHA-256 digests of the profiles and scenes a table records (runtime/hdf5/seal.h).

#include <filesystem>
#include <string>
#include <string_view>

namespace wrc {

/// SHA-256 of bytes, as 64 lowercase hex digits.
std::string Sha256Hex(std::string_view bytes);

/// SHA-256 of a file's bytes; throws InputError when the file cannot be read.
std::string Sha256FileHex(const std::filesystem::path& path);

}  // namespace wrc
