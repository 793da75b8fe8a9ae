// The real edges of a case in fixed dt, and every edge and margin the project prints (the edge,
// spectral_edge, scene_edges and courant studies, `mpmstab edge`, `mpmstab advise`'s margins):
// one rule and one search (docs/studies.md, "The stability edges").
// - The rule (edge_line): over the runs tried, in increasing step, the edge is the largest step
//   up to which every run tried holds (survives; or is accurate), and the run above it that does
//   not hold is the *lowest* failure found. A run that holds above that failure makes the edge
//   not monotone: the highest such run is reported beside the edge. A run too short for a verdict
//   (fewer than kMinStepsToJudge steps) neither holds nor fails.
// - The search: a log-spaced scan from scan_low to scan_high times the unit (h / c), doubling
//   while every step tried holds, bisection to `tolerance`, then a dense scan below the edge
//   (below_points steps from below_span x the edge up to it, and as many from below_from when
//   set); a failure found there moves the edge below it, and the search bisects and scans below
//   the new edge again, erratic_factor times as densely.
// - the survival edge dt_edge; the accuracy edge dt_accurate: by the same rule from the
//   reference (the smallest dt that survives), a run being accurate when it survives with an
//   error over time within accuracy_factor times the reference's (or, with accuracy_bound, at
//   most that bound) and is not meaningless; none when the reference's run is meaningless.
// - Every edge holds for the run length (wave passes c T / L) and the amplitude A it was
//   searched at; a search over runs of fewer than kMinWavePasses wave passes finds none.
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
  // When set, a run is accurate when it ends stable with an error over time at most this (the
  // target of `mpmstab advise`), instead of within accuracy_factor x the reference's.
  std::optional<double> accuracy_bound;
  // The dense scan below an edge: below_points steps from below_span x the edge up to it, and
  // when below_from is set, as many from below_from up to it. Once a scan below an edge has
  // found a failure (survival is erratic there), each scan below the next edge tries
  // erratic_factor times as many.
  double below_span = 0.9;
  int below_points = 8;
  int erratic_factor = 4;
  std::optional<double> below_from;
};

// The verdict of one run on one property: it holds (survives, or is accurate), it fails, or it
// is too short for a verdict.
enum class EdgeVerdict { holds, fails, none };

// The rule, on the runs tried (step, verdict), in any order: the edge is the largest step up to
// which every judged run holds; `fail` the lowest judged run that fails (none below it holds:
// no edge); `holds_above` the highest judged run above `fail` that holds (not monotone).
struct EdgeLine {
  std::optional<double> edge;
  std::optional<double> fail;
  std::optional<double> holds_above;
  bool monotone() const { return !holds_above; }
};
EdgeLine edge_line(std::vector<std::pair<double, EdgeVerdict>> runs);

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
  double dt_cfl = 0;  // h / c
  // What every run of the search holds for: its wave passes c T / L and its amplitude A. Under
  // kMinWavePasses the runs are too short for a verdict and the search makes none (too_short).
  double wave_passes = 0;
  double A = 0;
  bool too_short = false;
  std::optional<double> dt_edge;  // every dt tried up to it survives; none: nullopt
  std::optional<double> dt_fail;  // the lowest dt tried that fails (above dt_edge)
  bool above_scan = false;        // every dt up to the largest with a verdict survived
  // Survival is not monotone in dt: the highest dt above dt_fail that survives, and the dts
  // where survival flips, in increasing dt, over every dt tried (empty when monotone).
  std::optional<double> survives_above;
  std::vector<SurvivalFlip> flips;
  bool monotone() const { return !survives_above; }

  // The accuracy edge. The reference is the smallest dt probed that survived.
  double accuracy_factor = 2;
  std::optional<double> dt_reference;
  std::optional<double> max_error_reference;
  std::optional<double> dt_accurate;     // none when the reference's run is meaningless
  std::optional<double> dt_inaccurate;   // the lowest dt above it that is not accurate
  std::optional<double> accurate_above;  // the highest dt above dt_inaccurate that is accurate
  bool accuracy_monotone() const { return !accurate_above; }

  std::vector<EdgeProbe> probes;     // every run without observers, in the order made
  std::optional<RunResult> at_edge;  // the run at dt_edge, with the observers of the params
  // The deterministic cost of the search: particles x steps over every run it made.
  std::int64_t particle_steps = 0;
  double wall_seconds = 0;
  bool interrupted = false;
};

// `base` must be valid apart from its dt, which the search sets (the fixed policy is used); the
// largest dt tried takes kMinStepsToJudge steps to T.
// The probes run with every observer off (those of the scan up to the first that survives, the
// candidates for the reference, observe the error over time); the run at dt_edge uses base's
// observers with
// dt_stable and error_over_time on, for dt_edge / (eq. 108 minimum) and its outcome; the run at
// dt_accurate observes the error over time (a meaningless run there is not accurate, and the
// search goes on below it).
// With `cancel` set during the search, it stops promptly and returns with interrupted = true.
EdgeResult find_edge(const RunParams& base, const EdgeOptions& options = {},
                     const std::atomic<bool>* cancel = nullptr);

// The same search on a given function of the step, for tests and for searches in other units
// (`advise`'s margins in C): `survey(x, outcome)` stands for the run at x (`outcome`: the search
// needs its outcome). No run is measured: at_edge stays empty and a survivor's outcome is the
// one `survey` gives (unknown counts as not meaningless). `axis`: the unit of the scan (h / c),
// the largest step tried, and the wave passes and amplitude of every run.
using EdgeSurvey = std::function<EdgeProbe(double dt, bool outcome)>;
struct EdgeAxis {
  double unit = 0;
  double top = 0;
  double wave_passes = 0;
  double A = 0;
};
EdgeResult find_edge(const EdgeAxis& axis, const EdgeSurvey& survey,
                     const EdgeOptions& options = {});

}  // namespace mpmstab
