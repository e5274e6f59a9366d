// Interpolation kernels for x86-64-v3 (AVX2 + FMA). runtime/CMakeLists.txt compiles this file
// with -mavx2 -mfma -ffp-contract=fast and defines WRC_RUNTIME_X86_64_V3 only where that works
// (x86-64, GCC or Clang); SelectKernels() uses it only on CPUs that have both extensions. The
// fused multiply-adds round differently from the baseline build (in the last bit).

#if defined(WRC_RUNTIME_X86_64_V3)
#define WRC_KERNEL_NAMESPACE x86_64_v3
#include "runtime/kernels.inc"
#endif
