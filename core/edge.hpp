// The real stability edge: the largest fixed dt with which a case survives to T, found by a
// log-spaced scan around the speed-of-sound limit h / c followed by bisection.
#pragma once

#include <atomic>
#include <optional>
#include <vector>

#include "params.hpp"
#include "result.hpp"

namespace mpmstab {

struct EdgeOptions {
  double tolerance = 0.02;  // stop when (smallest failing dt) / (largest surviving dt) <= 1 + tol
  // The scan: dt = (h / c) * 2^(k / per_octave) for dt between scan_low and scan_high times h/c.
  double scan_low = 1.0 / 16;
  double scan_high = 4;
  int per_octave = 2;
};

struct EdgeProbe {
  double dt;
  bool stable;
  std::optional<FailureReason> reason;
  std::int64_t steps;
};

struct EdgeResult {
  double dt_cfl = 0;              // h / c
  std::optional<double> dt_edge;  // largest dt found to survive; none in the scan: nullopt
  std::optional<double> dt_fail;  // smallest dt above it found to fail
  bool above_scan = false;        // every dt up to T survived
  // Stability is not monotone in dt: smaller steps that failed although dt_edge survived.
  std::vector<double> failed_below_edge;
  std::vector<EdgeProbe> probes;     // every run, in the order made
  std::optional<RunResult> at_edge;  // the run at dt_edge, with the observers of the params
  double wall_seconds = 0;
  bool interrupted = false;
};

// `base` must be valid apart from its dt, which the search sets (the fixed policy is used).
// The probes run with every observer off; the final run at dt_edge uses base's observers with
// dt_stable on, for dt_edge / (eq. 108 minimum).
// With `cancel` set during the search, it stops promptly and returns with interrupted = true.
EdgeResult find_edge(const RunParams& base, const EdgeOptions& options = {},
                     const std::atomic<bool>* cancel = nullptr);

}  // namespace mpmstab
