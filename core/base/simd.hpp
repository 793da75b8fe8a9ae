// Instruction-set and inlining macros of the kernels (phases.cpp, p2g_bases.cpp, transfers.cpp)
// and of the shape functions they inline (shape.hpp). Used by core/ only.
#pragma once

// Instruction sets. MPMSTAB_SIMD_CLONES compiles a function for AVX-512 (x86-64-v4), AVX2
// (x86-64-v3) and the build's own target; the loader picks the best one the CPU has (GCC function
// multiversioning). g2p, the stress update and the state's extremes also have hand-written
// versions over vector lanes (lanes.hpp), the widest the CPU has chosen at run time. FMA
// contraction stays off in every version (-ffp-contract=off).
//
// MPMSTAB_KERNELS_PORTABLE (the build's own target only) and MPMSTAB_KERNELS_AVX2 (AVX2 and the
// build's own target, no AVX-512) build the same kernels without the versions above them: the
// reproducibility test (tests/test_kernel_versions.cpp) runs the same cases on every version
// this machine can run and compares the results byte for byte.
//
// MPMSTAB_AVX2 marks the hand-written AVX2 versions, chosen at run time on a CPU with AVX2 and
// without AVX-512; MPMSTAB_SSE2 the hand-written SSE2 ones (2 doubles, the x86-64 baseline), in
// every x86-64 build, for a CPU with neither.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && \
    defined(MPMSTAB_KERNELS_PORTABLE)
#include <immintrin.h>
#define MPMSTAB_SIMD_CLONES
#define MPMSTAB_AVX512 0
#define MPMSTAB_AVX2 0
#elif defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && \
    defined(MPMSTAB_KERNELS_AVX2)
#include <immintrin.h>
#define MPMSTAB_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#define MPMSTAB_AVX512 0
#define MPMSTAB_AVX2 1
#define MPMSTAB_AVX2_TARGET __attribute__((target("arch=x86-64-v3")))
#elif defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#include <immintrin.h>
#define MPMSTAB_SIMD_CLONES \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#define MPMSTAB_AVX512 1
#define MPMSTAB_AVX512_TARGET __attribute__((target("arch=x86-64-v4")))
#define MPMSTAB_AVX2 1
#define MPMSTAB_AVX2_TARGET __attribute__((target("arch=x86-64-v3")))
#else
#define MPMSTAB_SIMD_CLONES
#define MPMSTAB_AVX512 0
#define MPMSTAB_AVX2 0
#endif
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define MPMSTAB_SSE2 1
#else
#define MPMSTAB_SSE2 0
#endif
// A kernel's helper that must be inlined into each instruction set's version of its caller.
#define MPMSTAB_INLINE __attribute__((always_inline)) inline
#if defined(__GNUC__) && !defined(__clang__)
#define MPMSTAB_IVDEP _Pragma("GCC ivdep")  // the per-slot arrays of a stencil do not overlap
#else
#define MPMSTAB_IVDEP
#endif
