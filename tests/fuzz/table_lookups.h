#pragma once
// What the table fuzzers (fuzz_table, fuzz_flat_table) do with an input: write it to a scratch
// file, open it with the C API and, when it opens, look it up in both modes at the corners, the
// middle and outside of its axes. An accepted table must keep the runtime's promises (axes
// finite and ascending, finite values at ok cells); a broken one aborts the run.

#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "wrc/runtime.h"

namespace wrc::fuzz {

inline void Check(bool condition, const char* what) {
  if (condition) return;
  std::fprintf(stderr, "fuzz: accepted table breaks: %s\n", what);
  std::abort();
}

// One scratch file per fuzzing process (libFuzzer's -jobs run several).
inline const std::string& ScratchPath(const char* extension) {
  static const std::string path = "/tmp/wrc_fuzz_" + std::to_string(::getpid()) + "." + extension;
  return path;
}

inline bool WriteInput(const std::string& path, const std::string& bytes) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) return false;
  const bool written = std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
  return std::fclose(file) == 0 && written;
}

inline void EvaluateAFewPoints(wrc_table* table) {
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
        Check(std::isfinite(nodes[0]) && std::isfinite(nodes[n - 1]), "finite axis range");
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

// Writes `bytes` to the scratch file, opens it and looks it up where it opens.
inline void OpenAndEvaluate(const std::string& bytes, const char* extension) {
  const std::string& path = ScratchPath(extension);
  if (!WriteInput(path, bytes)) return;
  wrc_table* table = nullptr;
  if (wrc_table_open(path.c_str(), &table) == 0) {
    EvaluateAFewPoints(table);
    wrc_table_close(table);
  } else {
    Check(table == nullptr, "a failed open leaves no handle");
  }
}

}  // namespace wrc::fuzz
