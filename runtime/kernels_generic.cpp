// Interpolation kernels for the baseline instruction set, and the choice between builds.

#define WRC_KERNEL_NAMESPACE generic
#include "runtime/kernels.inc"

#include <cstdlib>
#include <cstring>

namespace wrc::runtime {

const Kernels& SelectKernels() {
  // WRC_RUNTIME_ISA=baseline forces the baseline build (tests compare both; benchmarks too).
  const char* isa = std::getenv("WRC_RUNTIME_ISA");
  if (isa != nullptr && std::strcmp(isa, "baseline") == 0) return generic::kKernels;
#if defined(WRC_RUNTIME_X86_64_V3)
  // Checked once per table load. cpu_init makes the check valid even from static initialisers.
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return x86_64_v3::kKernels;
#endif
  return generic::kKernels;
}

}  // namespace wrc::runtime
