// libFuzzer target for the table reader (include/wrc/runtime.h): arbitrary bytes written to a
// file, opened with wrc_table_open and evaluated at a few points in both modes
// (tests/fuzz/table_lookups.h). An error code is the expected answer to a damaged file; a crash,
// a sanitizer report or an accepted table whose evaluation breaks the runtime's promises
// (finite values at ok nodes) aborts.

#include <cstddef>
#include <cstdint>
#include <string>

#include "tests/fuzz/table_lookups.h"

// HDF5 1.10 leaks a few hundred bytes on some error paths of damaged files (allocated and lost
// inside libhdf5, never reaching wrc's handles, which all close through RAII). Not ours to fix;
// without this every such input would stop the run as a leak.
extern "C" const char* __lsan_default_suppressions() { return "leak:libhdf5_serial.so\n"; }

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  wrc::fuzz::OpenAndEvaluate(std::string(reinterpret_cast<const char*>(data), size), "h5");
  return 0;
}
