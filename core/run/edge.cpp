#include "run/edge.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "run/run.hpp"

namespace mpmstab {

namespace {

struct Interrupted {};

// A measured run at a dt: its outcome.
using Measure = std::function<std::optional<Outcome>(double dt)>;

class Search {
 public:
  Search(EdgeResult& e, double T, const EdgeOptions& o, const EdgeSurvey& survey,
         const Measure& measure_edge, const Measure& measure_accurate)
      : e_(e),
        T_(T),
        o_(o),
        survey_(survey),
        measure_edge_(measure_edge),
        measure_accurate_(measure_accurate) {}

  void run() {
    e_.accuracy_factor = o_.accuracy_factor;
    survival();
    if (!e_.dt_edge) return;
    if (measure_edge_) probe_at(*e_.dt_edge).outcome = measure_edge_(*e_.dt_edge);
    accuracy();
    summarise();
  }

 private:
  // A run at dt (at most T); `outcome`: its outcome is needed.
  bool probe(double dt, bool outcome = false) {
    e_.probes.push_back(survey_(std::min(dt, T_), outcome));
    return e_.probes.back().survived;
  }

  EdgeProbe& probe_at(double dt) {
    return *std::find_if(e_.probes.begin(), e_.probes.end(),
                         [&](const EdgeProbe& p) { return p.dt == dt; });
  }

  // The probes in increasing dt.
  std::vector<const EdgeProbe*> sorted() const {
    std::vector<const EdgeProbe*> s;
    for (const auto& p : e_.probes)
      s.push_back(&p);
    std::stable_sort(s.begin(), s.end(),
                     [](const EdgeProbe* a, const EdgeProbe* b) { return a->dt < b->dt; });
    return s;
  }

  // 1. A log-spaced scan from small to large dt; 2. doubling while every dt survives; 3.
  // geometric bisection between the largest survivor and the failure above it.
  void survival() {
    const int k_low = static_cast<int>(std::floor(o_.per_octave * std::log2(o_.scan_low)));
    const int k_high = static_cast<int>(std::ceil(o_.per_octave * std::log2(o_.scan_high)));
    std::optional<double> lo, hi;  // largest surviving, smallest failing above it
    for (int k = k_low; k <= k_high; ++k) {
      const double dt = e_.dt_cfl * std::exp2(double(k) / o_.per_octave);
      if (dt > T_) break;
      // Up to the first that survives (the reference of the accuracy edge), the outcome of
      // each probe is measured.
      if (probe(dt, !lo)) {
        lo = dt;
        hi.reset();
      } else if (lo && !hi) {
        hi = dt;
      }
    }
    if (!lo) return;  // nothing in the scan survives
    while (!hi) {
      const double dt = std::min(*lo * 2, T_);
      if (dt <= *lo) {
        e_.above_scan = true;
        break;
      }
      if (probe(dt)) {
        lo = dt;
      } else {
        hi = dt;
      }
    }
    while (hi && *hi / *lo > 1 + o_.tolerance) {
      const double mid = std::sqrt(*lo * *hi);
      if (probe(mid)) {
        lo = mid;
      } else {
        hi = mid;
      }
    }
    e_.dt_edge = lo;
    e_.dt_fail = hi;
  }

  bool accurate(const EdgeProbe& p) const {
    return p.survived && p.max_error &&
           *p.max_error <= o_.accuracy_factor * *e_.max_error_reference &&
           p.outcome != Outcome::meaningless;
  }

  // From the reference up, the last accurate dt before the first that is not.
  void accuracy_bracket() {
    e_.dt_accurate.reset();
    e_.dt_inaccurate.reset();
    for (const EdgeProbe* p : sorted()) {
      if (p->dt < *e_.dt_reference) continue;
      if (!accurate(*p)) {
        e_.dt_inaccurate = p->dt;
        return;
      }
      e_.dt_accurate = p->dt;
    }
  }

  // The reference is the smallest surviving dt; when its run is meaningless its error is no
  // yardstick and there is no accuracy edge. Bisection between the accuracy edge and the next
  // dt probed above it, then the measured run at the edge: a meaningless run there is not
  // accurate, and the search goes on below it.
  void accuracy() {
    const auto s = sorted();
    const EdgeProbe* reference =
        *std::find_if(s.begin(), s.end(), [](const EdgeProbe* p) { return p->survived; });
    e_.dt_reference = reference->dt;
    e_.max_error_reference = reference->max_error;
    if (reference->outcome == Outcome::meaningless) return;
    for (;;) {
      accuracy_bracket();
      while (e_.dt_accurate && e_.dt_inaccurate &&
             *e_.dt_inaccurate / *e_.dt_accurate > 1 + o_.tolerance) {
        probe(std::sqrt(*e_.dt_accurate * *e_.dt_inaccurate));
        accuracy_bracket();
      }
      if (!e_.dt_accurate) return;
      EdgeProbe& p = probe_at(*e_.dt_accurate);
      if (p.outcome || !measure_accurate_) return;
      p.outcome = measure_accurate_(p.dt);
      if (p.outcome != Outcome::meaningless) return;
    }
  }

  // The failures below the survival edge and the flips of survival up to it.
  void summarise() {
    const EdgeProbe* previous = nullptr;
    for (const EdgeProbe* p : sorted()) {
      if (p->dt > *e_.dt_edge) break;
      if (!p->survived) e_.failed_below_edge.push_back(p->dt);
      if (previous && previous->survived != p->survived) {
        e_.flips.push_back({previous->dt, p->dt, p->survived});
      }
      previous = p;
    }
  }

  EdgeResult& e_;
  const double T_;
  const EdgeOptions& o_;
  const EdgeSurvey& survey_;
  const Measure& measure_edge_;
  const Measure& measure_accurate_;
};

EdgeResult search(const RunParams& base, const EdgeOptions& o, const std::atomic<bool>* cancel) {
  const auto start = std::chrono::steady_clock::now();
  EdgeResult e;
  e.dt_cfl = (1.0 / base.cells) / std::sqrt(base.E);

  auto run_at = [&](RunParams p, double dt) {
    p.stepping.policy = TimeStepPolicy::fixed;
    p.dt = dt;
    RunResult r = run(p, cancel);
    if (r.interrupted) throw Interrupted{};
    e.particle_steps += r.steps * r.particles;
    return r;
  };
  // The probes: no observer, or only the error over time when their outcome is needed.
  // Every probe observes its error over time: the accuracy edge compares it (an error at one
  // instant T could be small where the exact solution vanishes).
  RunParams lean = base;
  lean.observe = Observe{};
  lean.observe.dt_stable = lean.observe.crossings = false;
  lean.observe.error_over_time = true;
  RunParams outcome_only = lean;
  const EdgeSurvey survey = [&](double dt, bool outcome) {
    const RunResult r = run_at(outcome ? outcome_only : lean, dt);
    const bool bounded =
        !o.bound || (r.max_error_over_time && *r.max_error_over_time <= *o.bound * base.A);
    return EdgeProbe{dt,
                     r.stable && bounded,
                     r.failure ? std::optional(r.failure->reason) : std::nullopt,
                     r.steps,
                     r.stable ? r.max_error_over_time : std::nullopt,
                     r.stable ? r.outcome : std::optional(Outcome::unstable)};
  };
  // The run at the survival edge, with the params' observers and its outcome.
  RunParams measured = base;
  measured.observe.dt_stable = measured.observe.error_over_time = true;
  const Measure measure_edge = [&](double dt) {
    e.at_edge = run_at(measured, dt);
    return e.at_edge->outcome;
  };
  const Measure measure_accurate = [&](double dt) { return run_at(outcome_only, dt).outcome; };

  Search(e, base.T, o, survey, measure_edge, measure_accurate).run();
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

EdgeResult find_edge(double dt_cfl, double T, const EdgeSurvey& survey, const EdgeOptions& o) {
  EdgeResult e;
  e.dt_cfl = dt_cfl;
  const Measure none;
  Search(e, T, o, survey, none, none).run();
  return e;
}

}  // namespace mpmstab
