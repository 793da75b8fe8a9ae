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

// The verdict of a run on survival: one too short for a verdict (fewer than kMinStepsToJudge
// steps to T) neither survives nor fails.
EdgeVerdict survival_verdict(const EdgeProbe& p) {
  if (p.survived && p.steps < kMinStepsToJudge) return EdgeVerdict::none;
  return p.survived ? EdgeVerdict::holds : EdgeVerdict::fails;
}

class Search {
 public:
  Search(EdgeResult& e, double top, const EdgeOptions& o, const EdgeSurvey& survey,
         const Measure& measure_edge, const Measure& measure_accurate)
      : e_(e),
        top_(top),
        o_(o),
        survey_(survey),
        measure_edge_(measure_edge),
        measure_accurate_(measure_accurate) {}

  void run() {
    e_.accuracy_factor = o_.accuracy_factor;
    scan();
    survival();
    summarise();
    if (!e_.dt_edge) return;
    if (measure_edge_) probe_at(*e_.dt_edge).outcome = measure_edge_(*e_.dt_edge);
    accuracy();
  }

 private:
  // A run at dt (at most top); `outcome`: its outcome is needed.
  bool probe(double dt, bool outcome = false) {
    e_.probes.push_back(survey_(std::min(dt, top_), outcome));
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

  EdgeLine survival_line() const {
    std::vector<std::pair<double, EdgeVerdict>> runs;
    for (const auto& p : e_.probes)
      runs.emplace_back(p.dt, survival_verdict(p));
    return edge_line(std::move(runs));
  }

  EdgeVerdict accuracy_verdict(const EdgeProbe& p) const {
    const EdgeVerdict v = survival_verdict(p);
    if (v != EdgeVerdict::holds) return v;
    if (!p.max_error || p.outcome == Outcome::meaningless) return EdgeVerdict::fails;
    const double bound =
        o_.accuracy_bound ? *o_.accuracy_bound : o_.accuracy_factor * *e_.max_error_reference;
    const bool stable = !o_.accuracy_bound || p.outcome == Outcome::stable;
    return stable && *p.max_error <= bound ? EdgeVerdict::holds : EdgeVerdict::fails;
  }

  EdgeLine accuracy_line() const {
    std::vector<std::pair<double, EdgeVerdict>> runs;
    for (const auto& p : e_.probes)
      if (p.dt >= *e_.dt_reference) runs.emplace_back(p.dt, accuracy_verdict(p));
    return edge_line(std::move(runs));
  }

  // A log-spaced scan from small to large dt, up to the first that survives (the reference of
  // the accuracy edge) with the outcome of each measured.
  void scan() {
    const int k_low = static_cast<int>(std::floor(o_.per_octave * std::log2(o_.scan_low)));
    const int k_high = static_cast<int>(std::ceil(o_.per_octave * std::log2(o_.scan_high)));
    bool survivor = false;
    for (int k = k_low; k <= k_high; ++k) {
      const double dt = e_.dt_cfl * std::exp2(double(k) / o_.per_octave);
      if (dt > top_ * (1 + 1e-12)) break;
      if (probe(dt, !survivor) && survival_verdict(e_.probes.back()) == EdgeVerdict::holds)
        survivor = true;
    }
  }

  // The steps of the dense scan below `edge` not yet tried (none within a quarter of the scan's
  // spacing of a run made).
  std::vector<double> below(double edge, bool erratic) const {
    std::vector<double> want;
    const int n = std::max(o_.below_points, 1) * (erratic ? std::max(o_.erratic_factor, 1) : 1);
    const double ratio = std::pow(o_.below_span, 1.0 / n);
    for (int i = 1; i <= n; ++i)
      want.push_back(edge * std::pow(ratio, i));
    if (o_.below_from && *o_.below_from < edge) {
      const double r = std::pow(*o_.below_from / edge, 1.0 / n);
      for (int i = 1; i <= n; ++i)
        want.push_back(edge * std::pow(r, i));
    }
    std::vector<double> out;
    const double near = (1 - ratio) / 4;
    for (const double dt : want) {
      const bool tried = std::any_of(e_.probes.begin(), e_.probes.end(), [&](const EdgeProbe& p) {
        return std::abs(p.dt / dt - 1) < near;
      });
      if (!tried) out.push_back(dt);
    }
    return out;
  }

  // Doubling while every dt tried survives, bisection between the edge and the lowest failure,
  // then the dense scan below the edge: a failure there moves the edge below it, and the search
  // bisects and scans below the new edge again.
  void survival() {
    EdgeLine line = survival_line();
    double tried = 0;
    for (const auto& p : e_.probes)
      tried = std::max(tried, p.dt);
    while (line.edge && !line.fail) {
      const double dt = std::min(tried * 2, top_);
      // Every dt up to the top survives, or the runs above the edge are too short to judge.
      if (dt <= tried || survival_verdict(e_.probes.back()) == EdgeVerdict::none) {
        e_.above_scan = true;
        break;
      }
      probe(dt);
      tried = dt;
      line = survival_line();
    }
    bool erratic = false;
    for (;;) {
      while (line.edge && line.fail && *line.fail / *line.edge > 1 + o_.tolerance) {
        probe(std::sqrt(*line.edge * *line.fail));
        line = survival_line();
      }
      if (!line.edge) break;
      bool failed = false;
      for (const double dt : below(*line.edge, erratic)) {
        probe(dt);
        failed |= survival_verdict(e_.probes.back()) == EdgeVerdict::fails;
      }
      if (!failed) break;
      erratic = true;
      line = survival_line();
    }
    e_.dt_edge = line.edge;
    e_.dt_fail = line.fail;
    e_.survives_above = line.holds_above;
  }

  // The reference is the smallest surviving dt; when its run is meaningless its error is no
  // yardstick and there is no accuracy edge (unless accuracy_bound is the yardstick). Bisection
  // between the accuracy edge and the lowest dt above it that is not accurate, the dense scan
  // below it, then the measured run at the edge: a meaningless run there is not accurate, and
  // the search goes on below it.
  void accuracy() {
    const auto s = sorted();
    const EdgeProbe* reference = *std::find_if(s.begin(), s.end(), [](const EdgeProbe* p) {
      return survival_verdict(*p) == EdgeVerdict::holds;
    });
    e_.dt_reference = reference->dt;
    e_.max_error_reference = reference->max_error;
    if (!o_.accuracy_bound && (reference->outcome == Outcome::meaningless || !reference->max_error))
      return;
    bool erratic = false;
    for (;;) {
      EdgeLine line = accuracy_line();
      while (line.edge && line.fail && *line.fail / *line.edge > 1 + o_.tolerance) {
        probe(std::sqrt(*line.edge * *line.fail));
        line = accuracy_line();
      }
      e_.dt_accurate = line.edge;
      e_.dt_inaccurate = line.fail;
      e_.accurate_above = line.holds_above;
      if (!line.edge) return;
      bool failed = false;
      for (const double dt : below(*line.edge, erratic)) {
        probe(dt);
        failed |= accuracy_verdict(e_.probes.back()) == EdgeVerdict::fails;
      }
      if (failed) {
        erratic = true;
        continue;
      }
      EdgeProbe& p = probe_at(*line.edge);
      if (p.outcome || !measure_accurate_) return;
      p.outcome = measure_accurate_(p.dt);
      if (p.outcome != Outcome::meaningless) return;
    }
  }

  // The flips of survival over every dt tried (runs without a verdict left out).
  void summarise() {
    const EdgeProbe* previous = nullptr;
    for (const EdgeProbe* p : sorted()) {
      if (survival_verdict(*p) == EdgeVerdict::none) continue;
      if (previous && previous->survived != p->survived) {
        e_.flips.push_back({previous->dt, p->dt, p->survived});
      }
      previous = p;
    }
    if (e_.monotone()) e_.flips.clear();
  }

  EdgeResult& e_;
  const double top_;
  const EdgeOptions& o_;
  const EdgeSurvey& survey_;
  const Measure& measure_edge_;
  const Measure& measure_accurate_;
};

EdgeResult search(const RunParams& base, const EdgeOptions& o, const std::atomic<bool>* cancel) {
  const auto start = std::chrono::steady_clock::now();
  EdgeResult e;
  e.dt_cfl = (1.0 / base.cells) / std::sqrt(base.E);
  e.wave_passes = wave_passes(base);
  e.A = base.A;
  e.too_short = e.wave_passes < kMinWavePasses;
  if (e.too_short) return e;

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

  Search(e, base.T / double(kMinStepsToJudge), o, survey, measure_edge, measure_accurate).run();
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

EdgeResult find_edge(const EdgeAxis& axis, const EdgeSurvey& survey, const EdgeOptions& o) {
  EdgeResult e;
  e.dt_cfl = axis.unit;
  e.wave_passes = axis.wave_passes;
  e.A = axis.A;
  e.too_short = e.wave_passes < kMinWavePasses;
  if (e.too_short) return e;
  const Measure none;
  Search(e, axis.top, o, survey, none, none).run();
  return e;
}

EdgeLine edge_line(std::vector<std::pair<double, EdgeVerdict>> runs) {
  std::stable_sort(runs.begin(), runs.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  EdgeLine line;
  for (const auto& [x, v] : runs) {
    if (v == EdgeVerdict::none) continue;
    if (!line.fail && v == EdgeVerdict::holds) line.edge = x;
    if (!line.fail && v == EdgeVerdict::fails) line.fail = x;
    if (line.fail && x > *line.fail && v == EdgeVerdict::holds) line.holds_above = x;
  }
  return line;
}

}  // namespace mpmstab
