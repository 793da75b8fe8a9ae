#include "run/run.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include "analysis/bloch.hpp"
#include "analysis/spectral.hpp"
#include "analysis/stable_dt.hpp"
#include "base/failure.hpp"
#include "observers/crossings.hpp"
#include "observers/energy.hpp"
#include "observers/error_l2.hpp"
#include "step/simulation.hpp"

namespace mpmstab {

namespace {

// The step about to be taken: the time it reaches, and whether it is the last one (it lands
// on T).
struct NextStep {
  double t_next;
  bool last;
};

// One run, from its set-up to its result, as the phases run() calls in order. The state lives
// in the members so that each phase is a method; each is called once per step or once per run,
// and nothing is allocated per step but the history rows kept.
class Driver {
 public:
  // 1. Set up the scene and the quantities that do not depend on the run; 2. the observers.
  Driver(const RunParams& p, const HistorySink& sink);

  // A scene's initial state can already be inadmissible (a steffen amplitude with F_p(0) <= 0,
  // or a cpGIMP support wider than 2 h): the run then fails at step 0, before any step reads it.
  void check_initial_state();

  // 3. Step to T, checking the state after every step.
  bool running() const { return !r_.failure && sim_.time() < p_.T; }
  NextStep next_step() const;
  bool stops_before_step(const NextStep& next, const std::atomic<bool>* cancel);
  void advance(const NextStep& next);
  bool fails_after_step();
  void observe_step(bool last);

  // 4. The verdict and the measured quantities; `wall` is the time spent stepping.
  RunResult result(std::chrono::steady_clock::duration wall);

 private:
  double bound_now() const;
  void observe_every_option();
  FinalState final_state() const;
  void keep(const HistoryRow& row);

  const RunParams& p_;
  const Observe& obs_;
  const HistorySink& sink_;
  const bool history_;  // rows are made: kept (observe.history) or handed to the sink
  // eq. (108) is observed: asked for, and derived for the basis (params.hpp, has_eq108); with
  // a B-spline dt_stable stays unmeasured (null), never a number of another basis's formula.
  const bool dt_stable_;
  const double h_;
  const TimeStepPolicy policy_;
  const bool uses_bound_;       // the policy reads eq. (108) of the current state
  const bool spectral_policy_;  // the policy reads the spectral limit of a recent layout
  RunResult r_;
  Simulation sim_;
  const std::optional<double> fixed_dt_;  // fixed and cfl policies
  std::optional<CrossingCounter> crossing_counter_;
  std::optional<EnergyObserver> energy_;   // observe.energy
  std::optional<ErrorL2InTime> error_l2_;  // observe.error_l2
  const StableDtGeometry geometry_;
  const StableDtConstants eq108_constants_;  // of geometry_
  const double max_F_;
  double max_error_over_time_ = 0;
  double dt_stable_min_ = std::numeric_limits<double>::infinity();
  std::array<double, kStableDtOptionCount> dt_stable_min_of_option_;  // every_option_ only
  const bool every_option_;  // eq. (108) under every StableDtOptions
  std::int64_t crossings_ = 0;
  std::optional<HistoryRow> pending_row_;  // last row not kept by the stride
  double bound_ = 0;                       // eq. (108) of the current state, when read
  StateExtremes extremes_;                 // of the state after the last check
  Eigen::ArrayXd initial_x_;               // spectral policy: the initial positions,
  double next_excursion_ = 0;              // the excursion from them that recomputes the limit,
  double limit_dt_ = 0;                    // and the limit last computed, as dt
  double dt_min_ = std::numeric_limits<double>::infinity();
  double dt_max_ = 0;
};

Driver::Driver(const RunParams& p, const HistorySink& sink)
    : p_(p),
      obs_(p.observe),
      sink_(sink),
      history_(p.observe.history || static_cast<bool>(sink)),
      dt_stable_(p.observe.dt_stable && has_eq108(p.method)),
      h_(1.0 / p.cells),
      policy_(p.stepping.policy),
      uses_bound_(policy_ == TimeStepPolicy::adaptive || policy_ == TimeStepPolicy::min),
      spectral_policy_(policy_ == TimeStepPolicy::spectral),
      sim_(p),
      fixed_dt_(fixed_step(p)),
      geometry_{p.method, p.E, h_, p.ppc, h_ / p.ppc},
      eq108_constants_(stable_dt_constants(geometry_)),
      max_F_(max_admissible_F(p.method, p.ppc)),
      every_option_(dt_stable_ && p.observe.dt_stable_every_option) {
  dt_stable_min_of_option_.fill(std::numeric_limits<double>::infinity());
  r_.params = p;
  r_.particles = sim_.particles().size();
  r_.c = sim_.scene().c;
  r_.dt_cfl = h_ / r_.c;
  r_.dt_sound = 1.0 / r_.c;
  if (fixed_dt_) r_.steps_planned = *step_count(p.T, std::min(*fixed_dt_, p.T));

  if (obs_.crossings) crossing_counter_.emplace(sim_.particles(), h_);
  if (obs_.energy) energy_.emplace(sim_.particles(), sim_.scene().law(), sim_.scene());
  if (obs_.error_l2) error_l2_.emplace(sim_.particles(), sim_.scene());
  if (obs_.history && !sink_ && r_.steps_planned > 0) {
    const auto rows = r_.steps_planned / obs_.history_stride + 1;
    r_.history.reserve(static_cast<std::size_t>(std::min<std::int64_t>(rows, 10'000'000)));
  }
  extremes_ = state_extremes(sim_.particles());
  if (uses_bound_) bound_ = bound_now();
  // The spectral limit of the initial layout, on every record: Bloch where the layout is
  // uniform, the dense map where it is not and the spec records `spectral`. The spectral policy
  // takes its first step from it (the dense limit where none is recorded) and its later ones
  // from the dense limit of the layout it has reached.
  if (bloch_applies(p)) {
    r_.courant_spectral = spectral_courant(p, SpectralAnalysis::bloch);
    r_.spectral_analysis = SpectralAnalysis::bloch;
  } else if (obs_.spectral && spectral_state_size(p) <= kMaxSpectralState) {
    r_.courant_spectral = spectral_courant(p, SpectralAnalysis::dense);
    r_.spectral_analysis = SpectralAnalysis::dense;
  }
  if (r_.courant_spectral) r_.dt_spectral = *r_.courant_spectral * h_ / r_.c;
  if (spectral_policy_) {
    initial_x_ = sim_.particles().x;
    next_excursion_ = h_;
    const auto c =
        r_.spectral_analysis ? r_.courant_spectral : spectral_courant(p, SpectralAnalysis::dense);
    limit_dt_ = c.value_or(kMaxSpectralCourant) * r_.dt_cfl;
  }
}

// Eq. (108) from the state after the last step (before the first, with ||v|| = 0).
double Driver::bound_now() const {
  return stable_dt(
      stable_dt_inputs(sim_.particles(), extremes_, sim_.grid(), p_.stable.vnorm, p_.method),
      geometry_, eq108_constants_, p_.stable.sigma);
}

// eq. (108) of the state after the last step under each StableDtOptions, into their minima;
// bound_ is the run's own option's, computed as bound_now() computes it.
void Driver::observe_every_option() {
  for (const VelocityNorm vnorm : {VelocityNorm::l2, VelocityNorm::max}) {
    const StableDtInputs in =
        stable_dt_inputs(sim_.particles(), extremes_, sim_.grid(), vnorm, p_.method);
    for (const StressScaling sigma : {StressScaling::scaled, StressScaling::raw}) {
      const StableDtOptions option{sigma, vnorm};
      const double dt = stable_dt(in, geometry_, eq108_constants_, sigma);
      double& low = dt_stable_min_of_option_[option_index(option)];
      low = std::min(low, dt);
      if (option_index(option) == option_index(p_.stable)) bound_ = dt;
    }
  }
}

void Driver::check_initial_state() {
  // extremes_: of the initial state, taken in the constructor.
  if (auto failure = detect_failure(sim_.particles(), extremes_, p_.bc, max_F_)) {
    r_.failure = failure;
  }
}

// The next time: fixed steps are counted (t = n dt, no drift); adaptive ones accumulate.
NextStep Driver::next_step() const {
  if (fixed_dt_) {
    const bool last = sim_.steps() + 1 >= r_.steps_planned;
    return {last ? p_.T : static_cast<double>(sim_.steps() + 1) * *fixed_dt_, last};
  }
  double dt = p_.stepping.safety * (spectral_policy_ ? limit_dt_ : bound_);
  if (policy_ == TimeStepPolicy::min) dt = std::min(dt, p_.stepping.cfl_factor * r_.dt_cfl);
  // Land on T exactly, without leaving a sliver of a step.
  const bool last = sim_.time() + dt >= p_.T - 1e-9 * dt;
  return {last ? p_.T : sim_.time() + dt, last};
}

// The counter of count_work_on_this_thread (run.hpp).
thread_local std::atomic<double>* t_work_counter = nullptr;

// Cancellation, the step cap and a collapsed adaptive step, before the step is taken.
bool Driver::stops_before_step(const NextStep& next, const std::atomic<bool>* cancel) {
  // Cancellation is polled every 1024 steps: cheap, and prompt (well under a second); the work
  // done so far is counted then too.
  if ((sim_.steps() & 1023) == 0) {
    if (t_work_counter && sim_.steps() > 0)
      t_work_counter->fetch_add(1024.0 * double(sim_.particles().size()),
                                std::memory_order_relaxed);
    if (cancel && cancel->load(std::memory_order_relaxed)) {
      r_.interrupted = true;
      return true;
    }
  }
  if (sim_.steps() >= p_.max_steps) {
    r_.failure = Failure{FailureReason::step_limit, -1, sim_.steps(), sim_.time()};
    return true;
  }
  if (uses_bound_ && !next.last && next.t_next - sim_.time() < kDtCollapseFraction * r_.dt_cfl) {
    r_.failure = Failure{FailureReason::dt_collapse, -1, sim_.steps(), sim_.time()};
    return true;
  }
  return false;
}

void Driver::advance(const NextStep& next) {
  // The nominal step for fixed policies (t_next - t differs from it by rounding).
  const double dt = fixed_dt_ && !next.last ? *fixed_dt_ : next.t_next - sim_.time();
  if (!next.last || sim_.steps() == 0) {
    dt_min_ = std::min(dt_min_, dt);
    dt_max_ = std::max(dt_max_, dt);
  }
  if (energy_) energy_->before_step(sim_.particles());
  // The state's extremes come with the step, read by the check, eq. (108) and the error over
  // time (taken in the same pass).
  sim_.advance_to(next.t_next, &extremes_, obs_.error_over_time);
}

// The failure check after a step ("*" in Table 1); true when the run stops here.
bool Driver::fails_after_step() {
  auto failure = detect_failure(sim_.particles(), extremes_, p_.bc, max_F_);
  if (!failure) return false;
  failure->step = sim_.steps();
  failure->time = sim_.time();
  r_.failure = failure;
  // Keep the last admissible step in the history even when the stride skipped it.
  if (pending_row_) keep(*pending_row_);
  return true;
}

// The observers of the state after an admissible step, and its history row.
void Driver::observe_step(bool last) {
  HistoryRow row;
  row.step = sim_.steps();
  row.time = sim_.time();
  if (obs_.error_over_time) {
    const double e = extremes_.error_max;  // sim_.max_error(), from the pass after the step
    max_error_over_time_ = std::max(max_error_over_time_, e);
    row.error = e;
  }
  if (obs_.crossings) {
    crossings_ += crossing_counter_->update(sim_.particles());
    row.crossings = crossings_;
  }
  if (obs_.tip && history_) {
    const Particles& P = sim_.particles();
    const Eigen::Index tip = P.size() - 1;
    row.tip_u = P.x[tip] - P.X[tip];
    row.tip_u_exact = sim_.scene().displacement(P.X[tip], sim_.time());
  }
  if (error_l2_) error_l2_->after_step(sim_.particles(), sim_.time());
  if (energy_) {
    const Eigen::ArrayXd none;
    const EnergySample e = energy_->after_step(
        sim_.particles(), sim_.scene().has_body_force() ? sim_.body_acceleration() : none,
        sim_.time(), sim_.steps());
    if (history_) {
      row.kinetic = e.kinetic;
      row.strain = e.strain;
      row.work = e.work;
      row.energy_balance = e.balance;
      row.kinetic_exact = e.exact.kinetic;
      row.strain_exact = e.exact.strain;
      row.work_exact = e.exact.work;
    }
  }
  if (dt_stable_ || uses_bound_) {
    if (every_option_) {
      observe_every_option();
    } else {
      bound_ = bound_now();
    }
    if (dt_stable_) {
      dt_stable_min_ = std::min(dt_stable_min_, bound_);
      row.dt_stable = bound_;
    }
  }
  // The spectral policy's limit again, at the current layout, each time the largest
  // displacement any particle has reached from its initial position grows by another h: at most
  // max|u| / h + 1 computations in a run (params.hpp).
  if (spectral_policy_ && !last) {
    const double excursion = (sim_.particles().x - initial_x_).abs().maxCoeff();
    if (excursion > next_excursion_) {
      const auto c = spectral_courant_at(p_, sim_.particles().x, limit_dt_ / r_.dt_cfl);
      limit_dt_ = c.value_or(kMaxSpectralCourant) * r_.dt_cfl;
      next_excursion_ = (std::floor(excursion / h_) + 1) * h_;
    }
  }
  if (history_) {
    if (sim_.steps() % obs_.history_stride == 0 || last) {
      keep(row);
      pending_row_.reset();
    } else {
      pending_row_ = row;
    }
  }
}

void Driver::keep(const HistoryRow& row) {
  if (sink_) {
    sink_(row);
  } else {
    r_.history.push_back(row);
  }
}

// The particles where the run ended, with the exact solution there.
FinalState Driver::final_state() const {
  const Particles& P = sim_.particles();
  const Scene& scene = sim_.scene();
  const double t = sim_.time();
  FinalState f{t, P.X, P.x, P.v, P.F, P.sigma, {}, {}, {}};
  f.u_exact = P.X.unaryExpr([&](double X) { return scene.displacement(X, t); });
  f.v_exact = P.X.unaryExpr([&](double X) { return scene.velocity(X, t); });
  f.sigma_exact = P.X.unaryExpr([&](double X) { return scene.stress(X, t); });
  return f;
}

RunResult Driver::result(std::chrono::steady_clock::duration wall) {
  r_.steps = sim_.steps();
  r_.dt_min = std::isfinite(dt_min_) ? dt_min_ : 0;
  r_.dt_max = dt_max_;
  if (r_.steps > 0) r_.dt_mean = sim_.time() / static_cast<double>(r_.steps);
  // Fixed and cfl policies: the Courant number of their step, even for a run that failed before
  // its first step; adaptive ones: of the largest step taken.
  r_.courant = r_.c * (fixed_dt_ ? std::min(*fixed_dt_, p_.T) : dt_max_) / h_;
  r_.stable = !r_.failure.has_value() && !r_.interrupted;
  if (r_.stable) r_.max_error = sim_.max_error();  // Table 1's "Max Error"
  if (obs_.error_over_time) {
    r_.max_error_over_time = max_error_over_time_;
    if (r_.stable) r_.meaningless = max_error_over_time_ > 0 && max_error_over_time_ >= p_.A;
  }
  if (!r_.stable && !r_.interrupted) {
    r_.outcome = Outcome::unstable;
  } else if (r_.meaningless) {
    r_.outcome = *r_.meaningless ? Outcome::meaningless : Outcome::stable;
  }
  if (r_.outcome && r_.stable && r_.steps < kMinStepsToJudge) r_.outcome = Outcome::too_short;
  if (obs_.crossings) r_.crossings = crossings_;
  if (error_l2_) r_.error_l2_time = error_l2_->value();
  if (energy_) {
    const EnergySummary e = energy_->summary();
    r_.energy_error_max = e.error_max;
    r_.energy_exact_error_max = e.exact_error_max;
    r_.energy_drift = e.drift;
    r_.energy_warning_step = e.warning_step;
  }
  // step_limit and dt_collapse stop before a step; the other failures are found after one.
  const bool failed_in_a_step = r_.failure && r_.failure->reason != FailureReason::step_limit &&
                                r_.failure->reason != FailureReason::dt_collapse;
  if (dt_stable_ && r_.steps > (failed_in_a_step ? 1 : 0)) {
    r_.dt_stable_min = dt_stable_min_;
    if (every_option_) {
      for (int k = 0; k < kStableDtOptionCount; ++k)
        r_.dt_stable_min_of_option[k] = dt_stable_min_of_option_[k];
    }
  }
  if (obs_.final_state) r_.final_state = final_state();
  r_.wall_seconds = std::chrono::duration<double>(wall).count();
  if (r_.steps > 0) {
    r_.ns_per_particle_step = r_.wall_seconds * 1e9 / (double(r_.steps) * double(r_.particles));
  }
  return std::move(r_);
}

}  // namespace

std::string_view to_string(Outcome o) {
  switch (o) {
    case Outcome::unstable:
      return "unstable";
    case Outcome::meaningless:
      return "meaningless";
    case Outcome::stable:
      return "stable";
    case Outcome::too_short:
      return "too_short";
  }
  return "?";
}

void count_work_on_this_thread(std::atomic<double>* counter) {
  t_work_counter = counter;
}

RunResult run(const RunParams& p, const std::atomic<bool>* cancel, const HistorySink& history) {
  Driver driver(p, history);
  driver.check_initial_state();
  const auto start = std::chrono::steady_clock::now();
  while (driver.running()) {
    const NextStep next = driver.next_step();
    if (driver.stops_before_step(next, cancel)) break;
    driver.advance(next);
    if (driver.fails_after_step()) break;
    driver.observe_step(next.last);
  }
  const auto stop = std::chrono::steady_clock::now();
  return driver.result(stop - start);
}

}  // namespace mpmstab
