#include "base/failure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/extremes_kernel.hpp"
#include "base/simd.hpp"

namespace mpmstab {

std::string_view to_string(FailureReason r) {
  switch (r) {
    case FailureReason::non_finite:
      return "non_finite";
    case FailureReason::nonpositive_F:
      return "nonpositive_F";
    case FailureReason::collapsed_F:
      return "collapsed_F";
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

MPMSTAB_LANES_BEGIN

// Every quantity in one pass, L::n particles at a time (and the error when `with_error`). The
// portable pass reads the arrays once per quantity through Eigen's SSE reductions (about 15% of a
// GIMP run on an AVX2 CPU); this reads them once.
template <class L, bool with_error>
MPMSTAB_LANES_BODY StateExtremes extremes_pass(const Particles& P, const ErrorTerms* error) {
  const auto n = static_cast<std::size_t>(P.size());
  const double *x = P.x.data(), *v = P.v.data(), *F = P.F.data(), *s = P.sigma.data();
  Extremes<L, with_error> e(error);
  std::size_t p = 0;
  for (; p + L::n <= n; p += L::n)
    e.add(p, L::load(x + p), L::load(v + p), L::load(F + p), L::load(s + p));
  for (; p < n; ++p)
    e.add_one(p, x[p], v[p], F[p], s[p]);
  const StateExtremes result = e.result();
  L::end();
  return result;
}

MPMSTAB_LANES_END

#if MPMSTAB_AVX512
template <bool with_error>
MPMSTAB_AVX512_TARGET MPMSTAB_LANES_ENTRY StateExtremes extremes_avx512(const Particles& P,
                                                                        const ErrorTerms* error) {
  return extremes_pass<Lanes8, with_error>(P, error);
}
#endif

#if MPMSTAB_AVX2
template <bool with_error>
MPMSTAB_AVX2_TARGET MPMSTAB_LANES_ENTRY StateExtremes extremes_avx2(const Particles& P,
                                                                    const ErrorTerms* error) {
  return extremes_pass<Lanes4, with_error>(P, error);
}
#endif

#if MPMSTAB_SSE2
template <bool with_error>
MPMSTAB_LANES_ENTRY StateExtremes extremes_sse2(const Particles& P, const ErrorTerms* error) {
  return extremes_pass<Lanes2, with_error>(P, error);
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
#if MPMSTAB_AVX2
  static const bool avx2 = __builtin_cpu_supports("x86-64-v3");
  if (avx2 && P.size() > 0) {
    return error ? extremes_avx2<true>(P, error) : extremes_avx2<false>(P, nullptr);
  }
#endif
#if MPMSTAB_SSE2
  if (P.size() > 0) {
    return error ? extremes_sse2<true>(P, error) : extremes_sse2<false>(P, nullptr);
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
  const bool ok = e.finite && e.F_min >= kSmallestNormalF && (!bounded_F || e.F_max <= max_F) &&
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
  if (auto p = first([&](Eigen::Index i) { return P.F[i] < kSmallestNormalF; })) {
    return Failure{FailureReason::collapsed_F, *p};
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
