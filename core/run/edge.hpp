// The real edges of a case in fixed dt, found by a log-spaced scan around the speed-of-sound
// limit h / c followed by bisection (docs/studies.md, "The stability edge"):
// - the survival edge dt_edge: the largest dt probed with which the case survives to T;
// - the accuracy edge dt_accurate: the largest dt probed up to which every probed dt from the
//   reference (the smallest dt that survives) survives with an error over time within
//   accuracy_factor times the reference's, and whose run is not meaningless (none when the
//   reference's run is meaningless: its error is no yardstick).
// Survival that is not monotone in dt (a dt below the edge fails) is reported as the dts where
// it flips.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "base/params.hpp"
#include "base/result.hpp"

namespace mpmstab {

struct EdgeOptions {
  double tolerance = 0.02;  // stop when (smallest failing dt) / (largest surviving dt) <= 1 + tol
  // The scan: dt = (h / c) * 2^(k / per_octave) for dt between scan_low and scan_high times h/c.
  double scan_low = 1.0 / 16;
  double scan_high = 4;
  int per_octave = 2;
  // A dt is accurate when its error over time (max over steps and particles) is at most this many
  // times the reference's.
  double accuracy_factor = 2;
  // When set, a probe survives only when it also stays bounded: its error over time ends at
  // most bound x A. A mode that grows but has not yet failed by T then counts as failing (the
  // edge of a tiny amplitude, where growth does not reach a failure within T).
  std::optional<double> bound;
};

// One run of the search. The probes run without observers: whether a surviving run is
// meaningless is known only for the scan's probes up to the first that survives (the
// reference, which observe their error over time) and for the measured runs at dt_edge and
// dt_accurate, whose outcome is copied to the probe at their dt.
struct EdgeProbe {
  double dt = 0;
  bool survived = false;
  std::optional<FailureReason> reason;  // a failed run
  std::int64_t steps = 0;
  std::optional<double> max_error;  // the error over time of a run that survived
  std::optional<Outcome> outcome;   // unstable when failed; a survivor's only when measured
};

// Survival changes between two probed dts next to each other (in increasing dt) below the
// survival edge: from `below` to `dt`, the run survives from dt on (`survives`) or fails.
struct SurvivalFlip {
  double below = 0;
  double dt = 0;
  bool survives = false;
};

struct EdgeResult {
  double dt_cfl = 0;              // h / c
  std::optional<double> dt_edge;  // largest dt found to survive; none in the scan: nullopt
  std::optional<double> dt_fail;  // smallest dt above it found to fail
  bool above_scan = false;        // every dt up to T survived
  // Stability is not monotone in dt: smaller steps that failed although dt_edge survived, and
  // the dts where survival flips below dt_fail (empty when monotone).
  std::vector<double> failed_below_edge;
  std::vector<SurvivalFlip> flips;

  // The accuracy edge. The reference is the smallest dt probed that survived.
  double accuracy_factor = 2;
  std::optional<double> dt_reference;
  std::optional<double> max_error_reference;
  std::optional<double> dt_accurate;    // none when the reference's run is meaningless
  std::optional<double> dt_inaccurate;  // the next dt probed above it (not accurate)

  std::vector<EdgeProbe> probes;     // every run without observers, in the order made
  std::optional<RunResult> at_edge;  // the run at dt_edge, with the observers of the params
  // The deterministic cost of the search: particles x steps over every run it made.
  std::int64_t particle_steps = 0;
  double wall_seconds = 0;
  bool interrupted = false;
};

// `base` must be valid apart from its dt, which the search sets (the fixed policy is used).
// The probes run with every observer off (those of the scan up to the first that survives, the
// candidates for the reference, observe the error over time); the run at dt_edge uses base's
// observers with
// dt_stable and error_over_time on, for dt_edge / (eq. 108 minimum) and its outcome; the run at
// dt_accurate observes the error over time (a meaningless run there is not accurate, and the
// search goes on below it).
// With `cancel` set during the search, it stops promptly and returns with interrupted = true.
EdgeResult find_edge(const RunParams& base, const EdgeOptions& options = {},
                     const std::atomic<bool>* cancel = nullptr);

// The same search on a given function of dt, for tests: `survey(dt, outcome)` stands for the
// probe at dt (`outcome`: the search needs its outcome, and find_edge observes the run's error
// over time). No run is measured: at_edge stays empty and a survivor's outcome is the one
// `survey` gives (unknown counts as not meaningless).
using EdgeSurvey = std::function<EdgeProbe(double dt, bool outcome)>;
EdgeResult find_edge(double dt_cfl, double T, const EdgeSurvey& survey,
                     const EdgeOptions& options = {});

}  // namespace mpmstab
