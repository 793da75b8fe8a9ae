// The vector lanes of the hand-written kernels: Lanes8 (AVX-512, 8 doubles), Lanes4 (AVX2, 4
// doubles) and Lanes2 (SSE2, 2 doubles), each the same set of static functions on its own register
// type. A kernel is written once, as a template over its lanes L marked MPMSTAB_LANES_BODY, and
// instantiated for each instruction set by a function with that set's target and
// MPMSTAB_LANES_ENTRY. GCC cannot inline a function with a target into one without it, so the
// template calls L's functions and the entry point's `flatten` inlines the template and, once they
// are in the target's code, L's functions. Every lane does a scalar's operations in the same order:
// an instantiation for 8 lanes and one for 4 give the same bits. Internal to core/.
#pragma once

#include <algorithm>
#include <cstddef>

#include "base/simd.hpp"

// The body of a kernel over its lanes, inlined into each entry point (MPMSTAB_LANES_ENTRY).
#define MPMSTAB_LANES_BODY __attribute__((always_inline)) inline
// An instruction set's entry point into a MPMSTAB_LANES_BODY: everything it calls is inlined.
#define MPMSTAB_LANES_ENTRY __attribute__((flatten))

// The templates over lanes take and return vectors, about which GCC notes that the calling
// convention of a vector differs with and without the instruction set (-Wpsabi). Those templates
// are never called: they are inlined into their entry points. Files that define them turn the
// note off around their definitions with these two.
#define MPMSTAB_LANES_BEGIN \
  _Pragma("GCC diagnostic push") _Pragma("GCC diagnostic ignored \"-Wpsabi\"")
#define MPMSTAB_LANES_END _Pragma("GCC diagnostic pop")

namespace mpmstab {

#if MPMSTAB_AVX512
struct Lanes8 {
  using V = __m512d;
  static constexpr int n = 8;
  MPMSTAB_AVX512_TARGET static V load(const double* p) { return _mm512_loadu_pd(p); }
  MPMSTAB_AVX512_TARGET static void store(double* p, V a) { _mm512_storeu_pd(p, a); }
  MPMSTAB_AVX512_TARGET static V set1(double a) { return _mm512_set1_pd(a); }
  MPMSTAB_AVX512_TARGET static V add(V a, V b) { return _mm512_add_pd(a, b); }
  MPMSTAB_AVX512_TARGET static V sub(V a, V b) { return _mm512_sub_pd(a, b); }
  MPMSTAB_AVX512_TARGET static V mul(V a, V b) { return _mm512_mul_pd(a, b); }
  // The masked forms of min and max: no undefined source register, which GCC 12 warns about.
  MPMSTAB_AVX512_TARGET static V min(V a, V b) { return _mm512_mask_min_pd(a, 0xFF, a, b); }
  MPMSTAB_AVX512_TARGET static V max(V a, V b) { return _mm512_mask_max_pd(a, 0xFF, a, b); }
  MPMSTAB_AVX512_TARGET static V abs(V a) { return _mm512_andnot_pd(_mm512_set1_pd(-0.0), a); }
  MPMSTAB_AVX512_TARGET static double lane_min(V a) {
    alignas(64) double t[n];
    _mm512_store_pd(t, a);
    return *std::min_element(t, t + n);
  }
  MPMSTAB_AVX512_TARGET static double lane_max(V a) {
    alignas(64) double t[n];
    _mm512_store_pd(t, a);
    return *std::max_element(t, t + n);
  }
  // The lanes in which a value was NaN or infinite (fpclass), accumulated.
  using NotFinite = __mmask8;
  static constexpr int kNotFinite = 0x01 | 0x08 | 0x10 | 0x80;  // NaN, +inf, -inf
  static NotFinite none_seen() { return 0; }
  MPMSTAB_AVX512_TARGET static NotFinite see(NotFinite seen, V x, V v, V F, V s) {
    return seen | _mm512_fpclass_pd_mask(x, kNotFinite) | _mm512_fpclass_pd_mask(v, kNotFinite) |
           _mm512_fpclass_pd_mask(F, kNotFinite) | _mm512_fpclass_pd_mask(s, kNotFinite);
  }
  static bool finite(NotFinite seen) { return seen == 0; }
  // The end of a pass: no upper vector state left dirty for the SSE code that runs next (GCC 12
  // omits this vzeroupper; without it the next step's body force took 4x its time on an EPYC).
  MPMSTAB_AVX512_TARGET static void end() { _mm256_zeroupper(); }
};
#endif

#if MPMSTAB_AVX2
struct Lanes4 {
  using V = __m256d;
  static constexpr int n = 4;
  MPMSTAB_AVX2_TARGET static V load(const double* p) { return _mm256_loadu_pd(p); }
  MPMSTAB_AVX2_TARGET static void store(double* p, V a) { _mm256_storeu_pd(p, a); }
  MPMSTAB_AVX2_TARGET static V set1(double a) { return _mm256_set1_pd(a); }
  MPMSTAB_AVX2_TARGET static V add(V a, V b) { return _mm256_add_pd(a, b); }
  MPMSTAB_AVX2_TARGET static V sub(V a, V b) { return _mm256_sub_pd(a, b); }
  MPMSTAB_AVX2_TARGET static V mul(V a, V b) { return _mm256_mul_pd(a, b); }
  MPMSTAB_AVX2_TARGET static V min(V a, V b) { return _mm256_min_pd(a, b); }
  MPMSTAB_AVX2_TARGET static V max(V a, V b) { return _mm256_max_pd(a, b); }
  MPMSTAB_AVX2_TARGET static V abs(V a) { return _mm256_andnot_pd(_mm256_set1_pd(-0.0), a); }
  MPMSTAB_AVX2_TARGET static double lane_min(V a) {
    alignas(32) double t[n];
    _mm256_store_pd(t, a);
    return *std::min_element(t, t + n);
  }
  MPMSTAB_AVX2_TARGET static double lane_max(V a) {
    alignas(32) double t[n];
    _mm256_store_pd(t, a);
    return *std::max_element(t, t + n);
  }
  // As the portable pass: v * 0 is NaN exactly when v is NaN or infinite, so the sum of the
  // products stays 0 while every value seen is finite.
  using NotFinite = __m256d;
  MPMSTAB_AVX2_TARGET static NotFinite none_seen() { return _mm256_setzero_pd(); }
  MPMSTAB_AVX2_TARGET static NotFinite see(NotFinite seen, V x, V v, V F, V s) {
    const V zero = _mm256_setzero_pd();
    return _mm256_add_pd(
        seen, _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(x, zero), _mm256_mul_pd(v, zero)),
                            _mm256_add_pd(_mm256_mul_pd(F, zero), _mm256_mul_pd(s, zero))));
  }
  MPMSTAB_AVX2_TARGET static bool finite(NotFinite seen) {
    return _mm256_movemask_pd(_mm256_cmp_pd(seen, _mm256_setzero_pd(), _CMP_EQ_OQ)) == 0xF;
  }
  MPMSTAB_AVX2_TARGET static void end() { _mm256_zeroupper(); }
};
#endif

#if MPMSTAB_SSE2
// SSE2, the x86-64 baseline: every x86-64 CPU has it, so no target and no check at run time.
struct Lanes2 {
  using V = __m128d;
  static constexpr int n = 2;
  static V load(const double* p) { return _mm_loadu_pd(p); }
  static void store(double* p, V a) { _mm_storeu_pd(p, a); }
  static V set1(double a) { return _mm_set1_pd(a); }
  static V add(V a, V b) { return _mm_add_pd(a, b); }
  static V sub(V a, V b) { return _mm_sub_pd(a, b); }
  static V mul(V a, V b) { return _mm_mul_pd(a, b); }
  static V min(V a, V b) { return _mm_min_pd(a, b); }
  static V max(V a, V b) { return _mm_max_pd(a, b); }
  static V abs(V a) { return _mm_andnot_pd(_mm_set1_pd(-0.0), a); }
  static double lane_min(V a) {
    alignas(16) double t[n];
    _mm_store_pd(t, a);
    return *std::min_element(t, t + n);
  }
  static double lane_max(V a) {
    alignas(16) double t[n];
    _mm_store_pd(t, a);
    return *std::max_element(t, t + n);
  }
  // As Lanes4: the sum of v * 0 stays 0 while every value seen is finite.
  using NotFinite = __m128d;
  static NotFinite none_seen() { return _mm_setzero_pd(); }
  static NotFinite see(NotFinite seen, V x, V v, V F, V s) {
    const V zero = _mm_setzero_pd();
    return _mm_add_pd(seen, _mm_add_pd(_mm_add_pd(_mm_mul_pd(x, zero), _mm_mul_pd(v, zero)),
                                       _mm_add_pd(_mm_mul_pd(F, zero), _mm_mul_pd(s, zero))));
  }
  static bool finite(NotFinite seen) {
    return _mm_movemask_pd(_mm_cmpeq_pd(seen, _mm_setzero_pd())) == 0x3;
  }
  static void end() {}
};
#endif

}  // namespace mpmstab
