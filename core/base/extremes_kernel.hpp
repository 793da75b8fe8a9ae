// The extremes of a particle state (failure.hpp, StateExtremes) accumulated several particles at
// a time, over the lanes of lanes.hpp (AVX-512 or AVX2): shared by state_extremes's own pass
// (failure.cpp) and the pass of USL's g2p and stress update that takes them as it writes the
// state (phases.cpp). Minima and maxima are exact in any order, max_p |F_p| is
// max(|min_p F_p|, |max_p F_p|) exactly, and a value is not finite exactly when it is NaN or
// infinite however the lanes tell it: every pass gives the same values, and those of the portable
// pass (failure.cpp). Few accumulators, so that the fused pass keeps them all in registers.
// Internal to core/.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "base/failure.hpp"
#include "base/lanes.hpp"
#include "base/simd.hpp"

namespace mpmstab {

// One particle's values into running extremes, the arithmetic of a lane: the tail of every
// vector pass (Extremes below). The error is the caller's.
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

namespace {

MPMSTAB_LANES_BEGIN

// The running extremes over lanes L (lanes.hpp): add() takes L::n particles, add_one() one (a
// tail), result() the values. Inlined into its pass (MPMSTAB_LANES_BODY), so that the accumulators
// stay in registers through it (called out of line, result() takes the object's address and GCC
// keeps it in memory: every add() then stored and reloaded them, 0.98 ns per particle-step for
// USL's one pass, GIMP). With `with_error`, the error max_p |(x_p - X_p) - u_p f| of the
// ErrorTerms too.
template <class L, bool with_error>
struct Extremes {
  using V = typename L::V;
  V F_min, F_max, x_min, x_max, s_abs, sF_abs, err, f;
  typename L::NotFinite not_finite;
  const double* X = nullptr;
  const double* u = nullptr;
  double factor = 0;
  // The tail, one particle at a time.
  StateExtremes tail{
      true, std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), 0, 0,
      0,    std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), 0};

  MPMSTAB_LANES_BODY explicit Extremes(const ErrorTerms* error)
      : F_min(L::set1(std::numeric_limits<double>::infinity())),
        F_max(L::set1(-std::numeric_limits<double>::infinity())),
        x_min(F_min),
        x_max(F_max),
        s_abs(L::set1(0.0)),
        sF_abs(s_abs),
        err(s_abs),
        not_finite(L::none_seen()) {
    if constexpr (with_error) {
      X = error->X;
      u = error->u;
      factor = error->factor;
    }
    f = L::set1(factor);
  }

  // Particles p .. p + L::n - 1 with these x, v, F and sigma.
  MPMSTAB_LANES_BODY void add(std::size_t p, const V& xp, const V& vp, const V& Fp, const V& sp) {
    if constexpr (with_error) {
      const V d = L::sub(L::sub(xp, L::load(X + p)), L::mul(L::load(u + p), f));
      err = L::max(err, L::abs(d));
    }
    not_finite = L::see(not_finite, xp, vp, Fp, sp);
    F_min = L::min(F_min, Fp);
    F_max = L::max(F_max, Fp);
    s_abs = L::max(s_abs, L::abs(sp));
    sF_abs = L::max(sF_abs, L::abs(L::mul(sp, Fp)));
    x_min = L::min(x_min, xp);
    x_max = L::max(x_max, xp);
  }

  // One particle p (the arithmetic of a lane).
  MPMSTAB_INLINE void add_one(std::size_t p, double x, double v, double F, double s) {
    if constexpr (with_error) {
      tail.error_max = std::max(tail.error_max, std::abs((x - X[p]) - u[p] * factor));
    }
    add_particle(tail, x, v, F, s);
  }

  MPMSTAB_LANES_BODY StateExtremes result() const {
    StateExtremes e;
    e.F_min = std::min(L::lane_min(F_min), tail.F_min);
    e.F_max = std::max(L::lane_max(F_max), tail.F_max);
    e.F_abs_max = std::max(std::abs(e.F_min), std::abs(e.F_max));
    e.sigma_abs_max = std::max(L::lane_max(s_abs), tail.sigma_abs_max);
    e.sigmaF_abs_max = std::max(L::lane_max(sF_abs), tail.sigmaF_abs_max);
    e.x_min = std::min(L::lane_min(x_min), tail.x_min);
    e.x_max = std::max(L::lane_max(x_max), tail.x_max);
    if constexpr (with_error) e.error_max = std::max(L::lane_max(err), tail.error_max);
    e.finite = L::finite(not_finite) && tail.finite;
    return e;
  }
};

MPMSTAB_LANES_END

}  // namespace

}  // namespace mpmstab
