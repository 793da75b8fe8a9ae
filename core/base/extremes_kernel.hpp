// The extremes of a particle state (failure.hpp, StateExtremes) accumulated 8 particles at a
// time with AVX-512: shared by state_extremes's own pass (failure.cpp) and the pass of USL's
// g2p and stress update that takes them as it writes the state (phases.cpp). Minima and maxima
// are exact in any order, max_p |F_p| is max(|min_p F_p|, |max_p F_p|) exactly, and a value is
// not finite exactly when its class is NaN or infinity: both passes give the same values, and
// the values of the portable pass (failure.cpp). Few accumulators, so that the fused pass keeps
// them all in registers. Internal to core/.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "base/failure.hpp"
#include "base/simd.hpp"

namespace mpmstab {

// One particle's values into running extremes, the arithmetic of a lane: the tail of every
// vector pass (Extremes8 below, the AVX2 pass of failure.cpp). The error is the caller's.
MPMSTAB_INLINE void add_particle(StateExtremes& e, double x, double v, double F, double s) {
  if (!std::isfinite(x) || !std::isfinite(v) || !std::isfinite(F) || !std::isfinite(s)) {
    e.finite = false;
  }
  e.F_min = std::min(e.F_min, F);
  e.F_max = std::max(e.F_max, F);
  e.sigma_abs_max = std::max(e.sigma_abs_max, std::abs(s));
  e.sigmaF_abs_max = std::max(e.sigmaF_abs_max, std::abs(s * F));
  e.x_min = std::min(e.x_min, x);
  e.x_max = std::max(e.x_max, x);
}

#if MPMSTAB_AVX512
namespace {

// The smallest and largest lane, lane-wise min, max and |a|: written without the intrinsics
// that start from an undefined register, which GCC 12 warns about.
MPMSTAB_AVX512_TARGET inline double lane_min(__m512d a) {
  alignas(64) double t[8];
  _mm512_store_pd(t, a);
  return *std::min_element(t, t + 8);
}
MPMSTAB_AVX512_TARGET inline double lane_max(__m512d a) {
  alignas(64) double t[8];
  _mm512_store_pd(t, a);
  return *std::max_element(t, t + 8);
}
MPMSTAB_AVX512_TARGET inline __m512d min8(__m512d a, __m512d b) {
  return _mm512_mask_min_pd(a, 0xFF, a, b);  // the masked form: no undefined source register
}
MPMSTAB_AVX512_TARGET inline __m512d max8(__m512d a, __m512d b) {
  return _mm512_mask_max_pd(a, 0xFF, a, b);
}
MPMSTAB_AVX512_TARGET inline __m512d abs8(__m512d a) {
  return _mm512_andnot_pd(_mm512_set1_pd(-0.0), a);
}

// The running extremes: add() takes 8 particles, add_one() one (a tail), result() the values.
// Every member function is inlined, so that the accumulators stay in registers through a pass
// (called out of line, result() takes the object's address and GCC keeps it in memory: every
// add() then stored and reloaded them, 0.98 ns per particle-step for USL's one pass, GIMP).
// With `with_error`, the error max_p |(x_p - X_p) - u_p f| of the ErrorTerms too.
template <bool with_error>
struct Extremes8 {
  static constexpr int kNotFinite = 0x01 | 0x08 | 0x10 | 0x80;  // NaN, +inf, -inf (fpclass)
  __m512d zero = _mm512_setzero_pd();
  __mmask8 not_finite = 0;
  __m512d F_min = _mm512_set1_pd(std::numeric_limits<double>::infinity());
  __m512d F_max = _mm512_set1_pd(-std::numeric_limits<double>::infinity());
  __m512d s_abs = zero, sF_abs = zero;
  __m512d x_min = F_min, x_max = F_max;
  __m512d err = zero;
  __m512d f8;
  const double* X = nullptr;
  const double* u = nullptr;
  double f = 0;
  // The tail, one particle at a time.
  StateExtremes tail{
      true, std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), 0, 0,
      0,    std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), 0};

  MPMSTAB_AVX512_TARGET explicit Extremes8(const ErrorTerms* error) {
    if constexpr (with_error) {
      X = error->X;
      u = error->u;
      f = error->factor;
    }
    f8 = _mm512_set1_pd(f);
  }

  // Particles p .. p + 7 with these x, v, F and sigma.
  MPMSTAB_AVX512_TARGET MPMSTAB_INLINE void add(std::size_t p, __m512d xp, __m512d vp, __m512d Fp,
                                                __m512d sp) {
    if constexpr (with_error) {
      const __m512d d = _mm512_sub_pd(_mm512_sub_pd(xp, _mm512_loadu_pd(X + p)),
                                      _mm512_mul_pd(_mm512_loadu_pd(u + p), f8));
      err = max8(err, abs8(d));
    }
    not_finite |= _mm512_fpclass_pd_mask(xp, kNotFinite) | _mm512_fpclass_pd_mask(vp, kNotFinite) |
                  _mm512_fpclass_pd_mask(Fp, kNotFinite) | _mm512_fpclass_pd_mask(sp, kNotFinite);
    F_min = min8(F_min, Fp);
    F_max = max8(F_max, Fp);
    s_abs = max8(s_abs, abs8(sp));
    sF_abs = max8(sF_abs, abs8(_mm512_mul_pd(sp, Fp)));
    x_min = min8(x_min, xp);
    x_max = max8(x_max, xp);
  }

  // One particle p (the arithmetic of a lane).
  MPMSTAB_INLINE void add_one(std::size_t p, double x, double v, double F, double s) {
    if constexpr (with_error) {
      tail.error_max = std::max(tail.error_max, std::abs((x - X[p]) - u[p] * f));
    }
    add_particle(tail, x, v, F, s);
  }

  MPMSTAB_AVX512_TARGET MPMSTAB_INLINE StateExtremes result() const {
    StateExtremes e;
    e.F_min = std::min(lane_min(F_min), tail.F_min);
    e.F_max = std::max(lane_max(F_max), tail.F_max);
    e.F_abs_max = std::max(std::abs(e.F_min), std::abs(e.F_max));
    e.sigma_abs_max = std::max(lane_max(s_abs), tail.sigma_abs_max);
    e.sigmaF_abs_max = std::max(lane_max(sF_abs), tail.sigmaF_abs_max);
    e.x_min = std::min(lane_min(x_min), tail.x_min);
    e.x_max = std::max(lane_max(x_max), tail.x_max);
    if constexpr (with_error) e.error_max = std::max(lane_max(err), tail.error_max);
    e.finite = not_finite == 0 && tail.finite;
    return e;
  }
};

}  // namespace
#endif

#if MPMSTAB_AVX2
namespace {

// The running extremes 4 particles at a time with AVX2, for a CPU without AVX-512: the lane-wise
// operations of Extremes8 in the same operand order, finiteness as in the portable pass (v * 0
// is NaN exactly when v is NaN or infinite), and the tail one particle at a time (add_particle).
// Shared by state_extremes's AVX2 pass (failure.cpp) and the AVX2 pass of USL's g2p and stress
// update (phases.cpp); inlined, so that the accumulators stay in registers.
template <bool with_error>
struct Extremes4 {
  __m256d zero = _mm256_setzero_pd(), sign = _mm256_set1_pd(-0.0);
  __m256d F_min = _mm256_set1_pd(std::numeric_limits<double>::infinity());
  __m256d F_max = _mm256_set1_pd(-std::numeric_limits<double>::infinity());
  __m256d x_min = F_min, x_max = F_max;
  __m256d s_abs = zero, sF_abs = zero, err = zero, not_finite = zero;
  __m256d f4;
  const double* X = nullptr;
  const double* u = nullptr;
  double f = 0;
  StateExtremes tail{
      true, std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), 0, 0,
      0,    std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), 0};

  MPMSTAB_AVX2_TARGET explicit Extremes4(const ErrorTerms* error) {
    if constexpr (with_error) {
      X = error->X;
      u = error->u;
      f = error->factor;
    }
    f4 = _mm256_set1_pd(f);
  }

  // Particles p .. p + 3 with these x, v, F and sigma.
  MPMSTAB_AVX2_TARGET MPMSTAB_INLINE void add(std::size_t p, __m256d xp, __m256d vp, __m256d Fp,
                                              __m256d sp) {
    if constexpr (with_error) {
      const __m256d d = _mm256_sub_pd(_mm256_sub_pd(xp, _mm256_loadu_pd(X + p)),
                                      _mm256_mul_pd(_mm256_loadu_pd(u + p), f4));
      err = _mm256_max_pd(err, _mm256_andnot_pd(sign, d));
    }
    not_finite = _mm256_add_pd(
        not_finite, _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(xp, zero), _mm256_mul_pd(vp, zero)),
                                  _mm256_add_pd(_mm256_mul_pd(Fp, zero), _mm256_mul_pd(sp, zero))));
    F_min = _mm256_min_pd(F_min, Fp);
    F_max = _mm256_max_pd(F_max, Fp);
    s_abs = _mm256_max_pd(s_abs, _mm256_andnot_pd(sign, sp));
    sF_abs = _mm256_max_pd(sF_abs, _mm256_andnot_pd(sign, _mm256_mul_pd(sp, Fp)));
    x_min = _mm256_min_pd(x_min, xp);
    x_max = _mm256_max_pd(x_max, xp);
  }

  // One particle p (the arithmetic of a lane).
  MPMSTAB_INLINE void add_one(std::size_t p, double x, double v, double F, double s) {
    if constexpr (with_error) {
      tail.error_max = std::max(tail.error_max, std::abs((x - X[p]) - u[p] * f));
    }
    add_particle(tail, x, v, F, s);
  }

  MPMSTAB_AVX2_TARGET MPMSTAB_INLINE StateExtremes result() const {
    alignas(32) double lanes[8][4];
    _mm256_store_pd(lanes[0], F_min);
    _mm256_store_pd(lanes[1], F_max);
    _mm256_store_pd(lanes[2], s_abs);
    _mm256_store_pd(lanes[3], sF_abs);
    _mm256_store_pd(lanes[4], x_min);
    _mm256_store_pd(lanes[5], x_max);
    _mm256_store_pd(lanes[6], err);
    _mm256_store_pd(lanes[7], not_finite);
    StateExtremes e;
    e.F_min = std::min(*std::min_element(lanes[0], lanes[0] + 4), tail.F_min);
    e.F_max = std::max(*std::max_element(lanes[1], lanes[1] + 4), tail.F_max);
    e.F_abs_max = std::max(std::abs(e.F_min), std::abs(e.F_max));
    e.sigma_abs_max = std::max(*std::max_element(lanes[2], lanes[2] + 4), tail.sigma_abs_max);
    e.sigmaF_abs_max = std::max(*std::max_element(lanes[3], lanes[3] + 4), tail.sigmaF_abs_max);
    e.x_min = std::min(*std::min_element(lanes[4], lanes[4] + 4), tail.x_min);
    e.x_max = std::max(*std::max_element(lanes[5], lanes[5] + 4), tail.x_max);
    if constexpr (with_error) {
      e.error_max = std::max(*std::max_element(lanes[6], lanes[6] + 4), tail.error_max);
    }
    e.finite = tail.finite;
    for (int k = 0; k < 4; ++k)
      e.finite = e.finite && lanes[7][k] == 0.0;
    return e;
  }
};

}  // namespace
#endif

}  // namespace mpmstab
