// libFuzzer target for the flat table reader (runtime/format/flat_table.h), through the C API
// as a simulator opens a table: each input is opened twice, as it is (the header's checks and
// the digest refuse almost every mutation) and with its header's size and digest made to match
// (so that the mutations reach the parser behind them). An input without the magic becomes the
// body of a flat file. An error code is the expected answer; a crash, a sanitizer report or an
// accepted table that breaks the runtime's promises aborts.

#include <nettle/sha2.h>
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "wrc/runtime.h"

namespace {

constexpr char kMagic[8] = {'\x89', 'W', 'R', 'C', 'T', '\r', '\n', '\x1a'};
constexpr std::size_t kHeader = 64;

void Check(bool condition, const char* what) {
  if (condition) return;
  std::fprintf(stderr, "fuzz_flat_table: accepted table breaks: %s\n", what);
  std::abort();
}

const std::string& ScratchPath() {
  static const std::string path = "/tmp/wrc_fuzz_flat_" + std::to_string(::getpid()) + ".wrct";
  return path;
}

// The input as a flat file whose size and digest match: the input itself when it starts with
// the magic, else a version-1 header before it.
std::string Resealed(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  if (size < kHeader || std::memcmp(data, kMagic, sizeof kMagic) != 0) {
    std::string header(kHeader, '\0');
    std::memcpy(header.data(), kMagic, sizeof kMagic);
    header[8] = 1;  // version
    bytes = header + bytes;
  }
  const std::uint64_t total = bytes.size();
  for (int i = 0; i < 8; ++i) bytes[16 + i] = static_cast<char>((total >> (8 * i)) & 0xFF);
  sha256_ctx context;
  sha256_init(&context);
  sha256_update(&context, bytes.size() - 56, reinterpret_cast<const std::uint8_t*>(&bytes[56]));
  sha256_digest(&context, 32, reinterpret_cast<std::uint8_t*>(&bytes[24]));
  return bytes;
}

bool WriteInput(const std::string& bytes) {
  std::FILE* file = std::fopen(ScratchPath().c_str(), "wb");
  if (file == nullptr) return false;
  const bool written = std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
  return std::fclose(file) == 0 && written;
}

// Both modes at the corners, the middle and outside: an accepted table keeps its promises.
void EvaluateAFewPoints(wrc_table* table) {
  const int n_axes = wrc_table_num_axes(table);
  const int n_outputs = wrc_table_num_outputs(table);
  Check(n_axes >= 1 && n_axes <= WRC_MAX_AXES, "axis count in 1..WRC_MAX_AXES");
  Check(n_outputs >= 1, "at least one output");
  double point[WRC_MAX_AXES];
  double* out =
      static_cast<double*>(std::malloc(sizeof(double) * static_cast<std::size_t>(n_outputs)));
  for (const int mode : {WRC_INTERP_LINEAR, WRC_INTERP_CUBIC}) {
    if (wrc_table_set_interpolation(table, mode) != 0) continue;  // cubic data: out of memory
    for (const double where : {0.0, 0.5, 1.0, -0.25}) {
      for (int a = 0; a < n_axes; ++a) {
        const int n = wrc_table_axis_size(table, a);
        const double* nodes = wrc_table_axis_values(table, a);
        Check(n >= 1 && nodes != nullptr, "a non-empty axis");
        for (int i = 1; i < n; ++i) Check(nodes[i] > nodes[i - 1], "strictly ascending nodes");
        point[a] = nodes[0] + where * (nodes[n - 1] - nodes[0]);
      }
      const int flags = wrc_table_eval(table, point, out);
      if (flags >= 0 && (flags & WRC_FLAG_STATUS) == 0) {
        for (int k = 0; k < n_outputs; ++k) Check(std::isfinite(out[k]), "finite value at ok cell");
      }
    }
  }
  std::free(out);
}

void OpenAndEvaluate(const std::string& bytes) {
  if (!WriteInput(bytes)) return;
  wrc_table* table = nullptr;
  if (wrc_table_open(ScratchPath().c_str(), &table) == 0) {
    EvaluateAFewPoints(table);
    wrc_table_close(table);
  } else {
    Check(table == nullptr, "a failed open leaves no handle");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  OpenAndEvaluate(std::string(reinterpret_cast<const char*>(data), size));
  OpenAndEvaluate(Resealed(data, size));
  return 0;
}
