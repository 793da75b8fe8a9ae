// Failure detection: the run stops as unstable ("*" in Table 1) when a particle leaves the
// domain (Dirichlet), any state value is not finite, some F_p <= 0, or some F_p is below the
// smallest normal double (collapsed_F: the particle's volume has collapsed, and F_p has lost
// significant bits; a machine that flushes subnormal numbers to zero holds F_p = 0 there and
// stops with nonpositive_F, so the verdict does not depend on the machine). With cpGIMP it also
// stops when a particle's half-width lp_p = F_p h / (2 m) exceeds h (F_p > 2 m): its support would
// then cover more nodes than the basis has (shape.hpp, CpGimpBasis). The run driver sets two
// more: step_limit when a run needs more steps than its cap, and dt_collapse when an adaptive or
// min policy asks for a step below kDtCollapseFraction of the CFL step h / c (params.hpp): the
// policy itself has failed, whatever the state.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>

#include "base/params.hpp"
#include "base/particles.hpp"

namespace mpmstab {

enum class FailureReason {
  non_finite,
  nonpositive_F,
  collapsed_F,
  support_too_wide,
  left_domain,
  step_limit,
  dt_collapse
};

std::string_view to_string(FailureReason r);

struct Failure {
  FailureReason reason;
  Eigen::Index particle = -1;  // first particle found in that state
  std::int64_t step = 0;       // the step after which the state was found
  double time = 0;             // the time reached by that step
};

// The smallest admissible F_p: the smallest normal double, 2.2e-308. Below it F_p is subnormal:
// it has fewer than 53 significant bits, so V_p = F_p V_p^0 and the stress are no longer computed
// to double precision, and every operation on it runs in the processor's slow microcode path.
inline constexpr double kSmallestNormalF = std::numeric_limits<double>::min();

// The largest admissible F_p of a method: 2 m for cpGIMP (lp_p <= h), unbounded otherwise.
double max_admissible_F(Method method, int ppc);

// The extremes of a particle state that the failure check and eq. (108) read, taken in one pass
// over the particles (vectorized): every run computes them once per step and hands them to both.
struct StateExtremes {
  bool finite = true;  // every x_p, v_p, F_p and sigma_p is finite
  double F_min = 0, F_max = 0;
  double F_abs_max = 0, sigma_abs_max = 0, sigmaF_abs_max = 0;  // max_p |F_p|, |s_p|, |s_p F_p|
  double x_min = 0, x_max = 0;
  double error_max = 0;  // max_p |x_p - X_p - u_p f| when ErrorTerms were given (else 0)
};
// The error of a manufactured solution u(X, t) = u_p f(t), taken in the same pass when given:
// the error-over-time observer's value, max_p |(x_p - X_p) - u_p f|, computed as
// Simulation::max_error computes it (the same rounding: the same result bit for bit).
struct ErrorTerms {
  const double* X = nullptr;  // reference positions, one per particle
  const double* u = nullptr;  // displacement profile u_p
  double factor = 0;          // f(t)
};
StateExtremes state_extremes(const Particles& P, const ErrorTerms* error = nullptr);
// max_p |(x_p - X_p) - u_p f| alone (the portable form of the fused pass's error).
double max_error(const Particles& P, const ErrorTerms& error);

// Checks every particle; nullopt if the state is admissible. When several particles fail, the
// reason reported is the first in the order non_finite, nonpositive_F, collapsed_F (some
// 0 < F_p < kSmallestNormalF), support_too_wide (some
// F_p > max_F), left_domain.
std::optional<Failure> detect_failure(const Particles& P, Boundary bc,
                                      double max_F = std::numeric_limits<double>::infinity());
// The same from the state's extremes, already taken (e = state_extremes(P)).
std::optional<Failure> detect_failure(const Particles& P, const StateExtremes& e, Boundary bc,
                                      double max_F = std::numeric_limits<double>::infinity());

}  // namespace mpmstab
