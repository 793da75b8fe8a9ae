#include "failure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "simd.hpp"

namespace mpmstab {

std::string_view to_string(FailureReason r) {
  switch (r) {
    case FailureReason::non_finite:
      return "non_finite";
    case FailureReason::nonpositive_F:
      return "nonpositive_F";
    case FailureReason::support_too_wide:
      return "support_too_wide";
    case FailureReason::left_domain:
      return "left_domain";
    case FailureReason::step_limit:
      return "step_limit";
    case FailureReason::dt_collapse:
      return "dt_collapse";
  }
  return "?";
}

double max_admissible_F(Method method, int ppc) {
  return follows_F(method) ? 2.0 * ppc : std::numeric_limits<double>::infinity();
}

namespace {

// One pass with Eigen's vectorized reductions per quantity: the portable version.
StateExtremes extremes_by_array(const Particles& P, const ErrorTerms* error) {
  StateExtremes e;
  if (error) e.error_max = max_error(P, *error);
  // v * 0 is NaN exactly when v is NaN or infinite: the sum is zero for a finite state.
  e.finite = (P.x * 0.0 + P.v * 0.0 + P.F * 0.0 + P.sigma * 0.0).sum() == 0.0;
  e.F_min = P.F.minCoeff();
  e.F_max = P.F.maxCoeff();
  e.F_abs_max = P.F.abs().maxCoeff();
  e.sigma_abs_max = P.sigma.abs().maxCoeff();
  e.sigmaF_abs_max = (P.sigma * P.F).abs().maxCoeff();
  e.x_min = P.x.minCoeff();
  e.x_max = P.x.maxCoeff();
  return e;
}

#if MPMSTAB_AVX512
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

// Every quantity in one pass, 8 particles at a time (and the error when `with_error`). Minima and
// maxima are exact in any order; the values are read only when the state is finite (the poison
// sum is zero).
template <bool with_error>
MPMSTAB_AVX512_TARGET StateExtremes extremes_avx512(const Particles& P, const ErrorTerms* error) {
  const auto n = static_cast<std::size_t>(P.size());
  const double *x = P.x.data(), *v = P.v.data(), *F = P.F.data(), *s = P.sigma.data();
  const double inf = std::numeric_limits<double>::infinity();
  const __m512d zero = _mm512_setzero_pd();
  __m512d poison = zero, F_min = _mm512_set1_pd(inf), F_max = _mm512_set1_pd(-inf);
  __m512d F_abs = zero, s_abs = zero, sF_abs = zero;
  __m512d x_min = _mm512_set1_pd(inf), x_max = _mm512_set1_pd(-inf);
  __m512d err = zero;
  const double* X = with_error ? error->X : nullptr;
  const double* u = with_error ? error->u : nullptr;
  const double f = with_error ? error->factor : 0.0;
  const __m512d f8 = _mm512_set1_pd(f);
  std::size_t p = 0;
  for (; p + 8 <= n; p += 8) {
    const __m512d xp = _mm512_loadu_pd(x + p), vp = _mm512_loadu_pd(v + p);
    if constexpr (with_error) {
      const __m512d d = _mm512_sub_pd(_mm512_sub_pd(xp, _mm512_loadu_pd(X + p)),
                                      _mm512_mul_pd(_mm512_loadu_pd(u + p), f8));
      err = max8(err, abs8(d));
    }
    const __m512d Fp = _mm512_loadu_pd(F + p), sp = _mm512_loadu_pd(s + p);
    poison = _mm512_add_pd(
        poison, _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(xp, zero), _mm512_mul_pd(vp, zero)),
                              _mm512_add_pd(_mm512_mul_pd(Fp, zero), _mm512_mul_pd(sp, zero))));
    F_min = min8(F_min, Fp);
    F_max = max8(F_max, Fp);
    F_abs = max8(F_abs, abs8(Fp));
    s_abs = max8(s_abs, abs8(sp));
    sF_abs = max8(sF_abs, abs8(_mm512_mul_pd(sp, Fp)));
    x_min = min8(x_min, xp);
    x_max = max8(x_max, xp);
  }
  StateExtremes e;
  double poison_tail = 0;
  e.F_min = lane_min(F_min);
  e.F_max = lane_max(F_max);
  e.F_abs_max = lane_max(F_abs);
  e.sigma_abs_max = lane_max(s_abs);
  e.sigmaF_abs_max = lane_max(sF_abs);
  e.x_min = lane_min(x_min);
  e.x_max = lane_max(x_max);
  if constexpr (with_error) e.error_max = lane_max(err);
  for (; p < n; ++p) {
    if constexpr (with_error) {
      e.error_max = std::max(e.error_max, std::abs((x[p] - X[p]) - u[p] * f));
    }
    poison_tail += x[p] * 0.0 + v[p] * 0.0 + F[p] * 0.0 + s[p] * 0.0;
    e.F_min = std::min(e.F_min, F[p]);
    e.F_max = std::max(e.F_max, F[p]);
    e.F_abs_max = std::max(e.F_abs_max, std::abs(F[p]));
    e.sigma_abs_max = std::max(e.sigma_abs_max, std::abs(s[p]));
    e.sigmaF_abs_max = std::max(e.sigmaF_abs_max, std::abs(s[p] * F[p]));
    e.x_min = std::min(e.x_min, x[p]);
    e.x_max = std::max(e.x_max, x[p]);
  }
  e.finite = _mm512_cmp_pd_mask(poison, zero, _CMP_EQ_OQ) == 0xFF && poison_tail == 0.0;
  return e;
}
#endif

}  // namespace

double max_error(const Particles& P, const ErrorTerms& error) {
  const Eigen::Map<const Eigen::ArrayXd> X(error.X, P.size()), u(error.u, P.size());
  return ((P.x - X) - u * error.factor).abs().maxCoeff();
}

StateExtremes state_extremes(const Particles& P, const ErrorTerms* error) {
#if MPMSTAB_AVX512
  static const bool avx512 = __builtin_cpu_supports("x86-64-v4");
  if (avx512 && P.size() > 0) {
    return error ? extremes_avx512<true>(P, error) : extremes_avx512<false>(P, nullptr);
  }
#endif
  return extremes_by_array(P, error);
}

std::optional<Failure> detect_failure(const Particles& P, Boundary bc, double max_F) {
  return detect_failure(P, state_extremes(P), bc, max_F);
}

std::optional<Failure> detect_failure(const Particles& P, const StateExtremes& e, Boundary bc,
                                      double max_F) {
  // Fast path, from the extremes.
  const bool walls = bc == Boundary::dirichlet;
  const bool bounded_F = max_F < std::numeric_limits<double>::infinity();
  const double lo = walls ? 0.0 : -std::numeric_limits<double>::infinity();
  const double hi = walls ? 1.0 : std::numeric_limits<double>::infinity();
  const bool ok = e.finite && e.F_min > 0.0 && (!bounded_F || e.F_max <= max_F) &&
                  (!walls || (e.x_min >= lo && e.x_max <= hi));
  if (ok) return std::nullopt;
  const Eigen::Index n = P.size();

  // Slow path, once per failed run: name the reason and the particle.
  auto first = [&](auto&& is_bad) -> std::optional<Eigen::Index> {
    for (Eigen::Index p = 0; p < n; ++p)
      if (is_bad(p)) return p;
    return std::nullopt;
  };
  auto finite = [](double a) { return std::isfinite(a); };
  if (auto p = first([&](Eigen::Index i) {
        return !finite(P.x[i]) || !finite(P.v[i]) || !finite(P.F[i]) || !finite(P.sigma[i]);
      })) {
    return Failure{FailureReason::non_finite, *p};
  }
  if (auto p = first([&](Eigen::Index i) { return !(P.F[i] > 0.0); })) {
    return Failure{FailureReason::nonpositive_F, *p};
  }
  if (auto p = first([&](Eigen::Index i) { return P.F[i] > max_F; })) {
    return Failure{FailureReason::support_too_wide, *p};
  }
  if (auto p = first([&](Eigen::Index i) { return !(P.x[i] >= lo && P.x[i] <= hi); })) {
    return Failure{FailureReason::left_domain, *p};
  }
  return std::nullopt;  // unreachable: the fast path found a bad value
}

}  // namespace mpmstab
