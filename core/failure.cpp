#include "failure.hpp"

#include <cmath>
#include <limits>

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

std::optional<Failure> detect_failure(const Particles& P, Boundary bc, double max_F) {
  // Fast path, vectorized reductions: v * 0 is NaN exactly when v is NaN or infinite, so the sum
  // below is zero for a finite state and NaN otherwise.
  const bool walls = bc == Boundary::dirichlet;
  const bool bounded_F = max_F < std::numeric_limits<double>::infinity();
  const double lo = walls ? 0.0 : -std::numeric_limits<double>::infinity();
  const double hi = walls ? 1.0 : std::numeric_limits<double>::infinity();
  const double poison = (P.x * 0.0 + P.v * 0.0 + P.F * 0.0 + P.sigma * 0.0).sum();
  const bool ok = poison == 0.0 && P.F.minCoeff() > 0.0 &&
                  (!bounded_F || P.F.maxCoeff() <= max_F) &&
                  (!walls || (P.x.minCoeff() >= lo && P.x.maxCoeff() <= hi));
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
