// libFuzzer target for the table reader (include/wrc/runtime.h): arbitrary bytes written to a
// file and opened with wrc_table_open, then evaluated at a few points. An error code is the
// expected answer to a damaged file; a crash, a sanitizer report or an accepted table whose
// evaluation breaks the runtime's promises (finite values at ok nodes) aborts.

#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "wrc/runtime.h"

namespace {

void Check(bool condition, const char* what) {
  if (condition) return;
  std::fprintf(stderr, "fuzz_table: accepted table breaks: %s\n", what);
  std::abort();
}

// One scratch file per fuzzing process (libFuzzer's -jobs run several).
const std::string& ScratchPath() {
  static const std::string path = "/tmp/wrc_fuzz_table_" + std::to_string(::getpid()) + ".h5";
  return path;
}

bool WriteInput(const std::uint8_t* data, std::size_t size) {
  std::FILE* file = std::fopen(ScratchPath().c_str(), "wb");
  if (file == nullptr) return false;
  const bool written = std::fwrite(data, 1, size, file) == size;
  return std::fclose(file) == 0 && written;
}

// Evaluates at the lower corner, the middle and the upper corner of the axis ranges, and outside.
void EvaluateAFewPoints(const wrc_table* table) {
  const int n_axes = wrc_table_num_axes(table);
  const int n_outputs = wrc_table_num_outputs(table);
  Check(n_axes >= 1 && n_axes <= WRC_MAX_AXES, "axis count in 1..WRC_MAX_AXES");
  Check(n_outputs >= 1, "at least one output");
  double point[WRC_MAX_AXES];
  double* out =
      static_cast<double*>(std::malloc(sizeof(double) * static_cast<std::size_t>(n_outputs)));
  for (const double where : {0.0, 0.5, 1.0, -0.25}) {
    for (int a = 0; a < n_axes; ++a) {
      const int n = wrc_table_axis_size(table, a);
      const double* nodes = wrc_table_axis_values(table, a);
      Check(n >= 1 && nodes != nullptr, "a non-empty axis");
      for (int i = 1; i < n; ++i) Check(nodes[i] > nodes[i - 1], "strictly ascending nodes");
      const double low = nodes[0], high = nodes[n - 1];
      Check(std::isfinite(low) && std::isfinite(high), "finite axis range");
      point[a] = low + where * (high - low);
    }
    const int flags = wrc_table_eval(table, point, out);
    if (flags >= 0 && (flags & WRC_FLAG_STATUS) == 0) {
      for (int k = 0; k < n_outputs; ++k) Check(std::isfinite(out[k]), "finite value at ok cell");
    }
  }
  std::free(out);
}

}  // namespace

// HDF5 1.10 leaks a few hundred bytes on some error paths of damaged files (allocated and lost
// inside libhdf5, never reaching wrc's handles, which all close through RAII). Not ours to fix;
// without this every such input would stop the run as a leak.
extern "C" const char* __lsan_default_suppressions() { return "leak:libhdf5_serial.so\n"; }

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (!WriteInput(data, size)) return 0;
  wrc_table* table = nullptr;
  if (wrc_table_open(ScratchPath().c_str(), &table) == 0) {
    EvaluateAFewPoints(table);
    wrc_table_close(table);
  } else {
    Check(table == nullptr, "a failed open leaves no handle");
  }
  return 0;
}
