// The wheelset FMU's binary (fmu/, built as its own shared library) compiled into wrc-tables,
// so that `wrc fmu` packs the binary of its own build wherever wrc is installed or moved.

#include "tools/wrc/fmu_binary.h"

// The assembler includes the file's bytes verbatim (WRC_FMU_BINARY is its path).
__asm__(
    ".pushsection .rodata.wrc_fmu_binary,\"a\"\n"
    ".balign 16\n"
    ".hidden wrc_fmu_binary_begin\n"
    ".globl wrc_fmu_binary_begin\n"
    "wrc_fmu_binary_begin:\n"
    ".incbin \"" WRC_FMU_BINARY
    "\"\n"
    ".hidden wrc_fmu_binary_end\n"
    ".globl wrc_fmu_binary_end\n"
    "wrc_fmu_binary_end:\n"
    ".popsection\n");

extern "C" const char wrc_fmu_binary_begin[];
extern "C" const char wrc_fmu_binary_end[];

namespace wrc::cli {

std::string_view FmuBinary() {
  return {wrc_fmu_binary_begin,
          static_cast<std::size_t>(wrc_fmu_binary_end - wrc_fmu_binary_begin)};
}

const char* FmuPlatform() { return WRC_FMU_PLATFORM; }

}  // namespace wrc::cli
