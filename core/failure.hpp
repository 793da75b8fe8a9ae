// Failure detection: the run stops as unstable ("*" in Table 1) when a particle leaves the
// domain (Dirichlet), any state value is not finite, or some F_p <= 0. A run whose time-step
// policy needs more steps than the cap stops with step_limit (set by the run driver).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "params.hpp"
#include "particles.hpp"

namespace mpmstab {

enum class FailureReason { non_finite, nonpositive_F, left_domain, step_limit };

std::string_view to_string(FailureReason r);

struct Failure {
  FailureReason reason;
  Eigen::Index particle = -1;  // first particle found in that state
  std::int64_t step = 0;       // the step after which the state was found
  double time = 0;             // the time reached by that step
};

// Checks every particle; nullopt if the state is admissible. When several particles fail, the
// reason reported is the first in the order non_finite, nonpositive_F, left_domain.
std::optional<Failure> detect_failure(const Particles& P, Boundary bc);

}  // namespace mpmstab
