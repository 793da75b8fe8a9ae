#include "edge.hpp"

#include <chrono>
#include <cmath>

#include "run.hpp"

namespace mpmstab {

namespace {
struct Interrupted {};
}  // namespace

namespace {

EdgeResult search(const RunParams& base, const EdgeOptions& o, const std::atomic<bool>* cancel) {
  const auto start = std::chrono::steady_clock::now();
  EdgeResult e;
  e.dt_cfl = (1.0 / base.cells) / std::sqrt(base.E);

  RunParams lean = base;
  lean.stepping.policy = TimeStepPolicy::fixed;
  lean.observe = Observe{};
  lean.observe.error_over_time = lean.observe.dt_stable = lean.observe.crossings = false;
  auto probe = [&](double dt) {
    lean.dt = std::min(dt, base.T);
    const RunResult r = run(lean, cancel);
    if (r.interrupted) throw Interrupted{};
    e.probes.push_back(
        {lean.dt, r.stable, r.failure ? std::optional(r.failure->reason) : std::nullopt, r.steps});
    return r.stable;
  };

  // 1. Log-spaced scan, from small to large dt.
  const int k_low = static_cast<int>(std::floor(o.per_octave * std::log2(o.scan_low)));
  const int k_high = static_cast<int>(std::ceil(o.per_octave * std::log2(o.scan_high)));
  std::optional<double> lo, hi;  // largest surviving, smallest failing above it
  for (int k = k_low; k <= k_high; ++k) {
    const double dt = e.dt_cfl * std::exp2(double(k) / o.per_octave);
    if (dt > base.T) break;
    if (probe(dt)) {
      lo = dt;
      hi.reset();
    } else if (lo && !hi) {
      hi = dt;
    }
  }
  if (!lo) {
    e.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return e;  // nothing in the scan survives
  }
  // 2. Every scanned dt survived: double until a failure or T.
  while (!hi) {
    const double dt = std::min(*lo * 2, base.T);
    if (dt <= *lo) {
      e.above_scan = true;
      break;
    }
    if (probe(dt)) {
      lo = dt;
    } else {
      hi = dt;
    }
  }
  // 3. Geometric bisection between the largest survivor and the failure above it.
  while (hi && *hi / *lo > 1 + o.tolerance) {
    const double mid = std::sqrt(*lo * *hi);
    if (probe(mid)) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  e.dt_edge = lo;
  e.dt_fail = hi;
  for (const auto& p : e.probes) {
    if (!p.stable && p.dt < *lo) e.failed_below_edge.push_back(p.dt);
  }
  // 4. The run at the edge, measured.
  RunParams at = base;
  at.stepping.policy = TimeStepPolicy::fixed;
  at.dt = *lo;
  at.observe.dt_stable = true;
  e.at_edge = run(at, cancel);
  if (e.at_edge->interrupted) throw Interrupted{};
  e.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return e;
}

}  // namespace

EdgeResult find_edge(const RunParams& base, const EdgeOptions& o, const std::atomic<bool>* cancel) {
  try {
    return search(base, o, cancel);
  } catch (const Interrupted&) {
    EdgeResult e;
    e.interrupted = true;
    return e;
  }
}

}  // namespace mpmstab
