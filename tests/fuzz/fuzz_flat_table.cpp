// libFuzzer target for the flat table reader (runtime/format/flat_table.h), through the C API
// as a simulator opens a table (tests/fuzz/table_lookups.h): each input is opened twice, as it
// is (the header's checks and the digest refuse almost every mutation) and with its header's
// size and digest made to match (so that the mutations reach the parser behind them). An input
// without the magic becomes the body of a flat file.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "tests/fuzz/table_lookups.h"
#include "tests/support/flat_table.h"

namespace {

constexpr char kMagic[8] = {'\x89', 'W', 'R', 'C', 'T', '\r', '\n', '\x1a'};
constexpr std::size_t kHeader = 64;

// The input as a flat file whose size and digest match: the input itself when it starts with
// the magic, else a version-1 header before it.
std::string Resealed(const std::string& input) {
  if (input.size() >= kHeader && std::memcmp(input.data(), kMagic, sizeof kMagic) == 0) {
    return wrc::test::ResealedFlatTable(input);
  }
  std::string header(kHeader, '\0');
  std::memcpy(header.data(), kMagic, sizeof kMagic);
  header[8] = 1;  // version
  return wrc::test::ResealedFlatTable(header + input);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  wrc::fuzz::OpenAndEvaluate(input, "wrct");
  wrc::fuzz::OpenAndEvaluate(Resealed(input), "wrct");
  return 0;
}
