// The profile and scene hashes a table records: the runtime's SHA-256 (runtime/hdf5/seal.h).

#include <fstream>
#include <iterator>

#include "generator/sha256.h"
#include "runtime/hdf5/seal.h"
#include "wrc/core/errors.h"
#include "wrc/generator/generator.h"

namespace wrc {

std::string Sha256Hex(std::string_view bytes) { return h5::Sha256Hex(bytes); }

std::string Sha256FileHex(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open the file to hash it");
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError(path.string() + ": read error while hashing the file");
  return h5::Sha256Hex(bytes);
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
