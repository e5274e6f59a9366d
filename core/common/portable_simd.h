#pragma once
/// @file portable_simd.h
/// WRC_CLONE_FOR_AVX2: built for AVX2 as well as the baseline x86-64 ISA, the variant chosen
/// when the program loads, so one binary runs everywhere and is fast where AVX2 exists. GCC on
/// x86-64 only (clang's target_clones differs); elsewhere the baseline build alone. No variant
/// uses FMA (not in the list), so both give the same results to the bit.

#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
#define WRC_CLONE_FOR_AVX2 __attribute__((target_clones("avx2", "default")))
#else
#define WRC_CLONE_FOR_AVX2
#endif
