#include "run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "crossings.hpp"
#include "failure.hpp"
#include "simulation.hpp"
#include "stable_dt.hpp"

namespace mpmstab {

RunResult run(const RunParams& p, const std::atomic<bool>* cancel) {
  RunResult r;
  r.params = p;
  const Observe& obs = p.observe;
  const double h = 1.0 / p.cells;
  const TimeStepPolicy policy = p.stepping.policy;
  const bool uses_bound = policy == TimeStepPolicy::adaptive || policy == TimeStepPolicy::min;

  // 1. Set up the scene and the quantities that do not depend on the run.
  Simulation sim(p);
  r.particles = sim.particles().size();
  r.c = sim.scene().c;
  r.dt_cfl = h / r.c;
  r.dt_sound = 1.0 / r.c;
  const std::optional<double> fixed_dt = fixed_step(p);
  if (fixed_dt) r.steps_planned = *step_count(p.T, std::min(*fixed_dt, p.T));

  // 2. The observers this run asked for.
  std::optional<CrossingCounter> crossing_counter;
  if (obs.crossings) crossing_counter.emplace(sim.particles(), h);
  const StableDtGeometry geometry{p.method, p.E, h, p.ppc, h / p.ppc};
  auto bound_now = [&] {
    return stable_dt(stable_dt_inputs(sim.particles(), sim.grid(), p.stable.vnorm, p.method),
                     geometry, p.stable.sigma);
  };
  const double max_F = max_admissible_F(p.method, p.ppc);
  double max_error_over_time = 0;
  double dt_stable_min = std::numeric_limits<double>::infinity();
  std::int64_t crossings = 0;
  if (obs.history && r.steps_planned > 0) {
    const auto rows = r.steps_planned / obs.history_stride + 1;
    r.history.reserve(static_cast<std::size_t>(std::min<std::int64_t>(rows, 10'000'000)));
  }
  std::optional<HistoryRow> pending_row;        // last row not kept by the stride
  double bound = uses_bound ? bound_now() : 0;  // of the current state
  double dt_min = std::numeric_limits<double>::infinity(), dt_max = 0;

  // 3. Step to T, checking the state after every step. A scene's initial state can already be
  // inadmissible (a steffen amplitude with F_p(0) <= 0, or a cpGIMP support wider than 2 h): the
  // run then fails at step 0, before any step reads it.
  if (auto failure = detect_failure(sim.particles(), p.bc, max_F)) r.failure = failure;
  const auto start = std::chrono::steady_clock::now();
  while (!r.failure && sim.time() < p.T) {
    // The next time: fixed steps are counted (t = n dt, no drift); adaptive ones accumulate.
    double t_next;
    bool last;
    if (fixed_dt) {
      last = sim.steps() + 1 >= r.steps_planned;
      t_next = last ? p.T : static_cast<double>(sim.steps() + 1) * *fixed_dt;
    } else {
      double dt = p.stepping.safety * bound;
      if (policy == TimeStepPolicy::min) dt = std::min(dt, p.stepping.cfl_factor * r.dt_cfl);
      // Land on T exactly, without leaving a sliver of a step.
      last = sim.time() + dt >= p.T - 1e-9 * dt;
      t_next = last ? p.T : sim.time() + dt;
    }
    // Cancellation is polled every 1024 steps: cheap, and prompt (well under a second).
    if (cancel && (sim.steps() & 1023) == 0 && cancel->load(std::memory_order_relaxed)) {
      r.interrupted = true;
      break;
    }
    if (sim.steps() >= p.max_steps) {
      r.failure = Failure{FailureReason::step_limit, -1, sim.steps(), sim.time()};
      break;
    }
    // The nominal step for fixed policies (t_next - t differs from it by rounding).
    const double dt = fixed_dt && !last ? *fixed_dt : t_next - sim.time();
    if (!last || sim.steps() == 0) {
      dt_min = std::min(dt_min, dt);
      dt_max = std::max(dt_max, dt);
    }
    sim.advance_to(t_next);
    if (auto failure = detect_failure(sim.particles(), p.bc, max_F)) {
      failure->step = sim.steps();
      failure->time = sim.time();
      r.failure = failure;
      // Keep the last admissible step in the history even when the stride skipped it.
      if (pending_row) r.history.push_back(*pending_row);
      break;
    }
    HistoryRow row{sim.steps(), sim.time(), {}, {}, {}};
    if (obs.error_over_time) {
      const double e = sim.max_error();
      max_error_over_time = std::max(max_error_over_time, e);
      row.error = e;
    }
    if (obs.crossings) {
      crossings += crossing_counter->update(sim.particles());
      row.crossings = crossings;
    }
    if (obs.dt_stable || uses_bound) {
      bound = bound_now();
      if (obs.dt_stable) {
        dt_stable_min = std::min(dt_stable_min, bound);
        row.dt_stable = bound;
      }
    }
    if (obs.history) {
      if (sim.steps() % obs.history_stride == 0 || last) {
        r.history.push_back(row);
        pending_row.reset();
      } else {
        pending_row = row;
      }
    }
  }
  const auto stop = std::chrono::steady_clock::now();

  // 4. The verdict and the measured quantities.
  r.steps = sim.steps();
  r.dt_min = std::isfinite(dt_min) ? dt_min : 0;
  r.dt_max = dt_max;
  r.courant = r.c * dt_max / h;
  r.stable = !r.failure.has_value() && !r.interrupted;
  if (r.stable) r.max_error = sim.max_error();
  if (obs.error_over_time) {
    r.max_error_over_time = max_error_over_time;
    if (r.stable) r.meaningless = max_error_over_time > 0 && max_error_over_time >= p.A;
  }
  if (obs.crossings) r.crossings = crossings;
  const bool failed_in_a_step = r.failure && r.failure->reason != FailureReason::step_limit;
  if (obs.dt_stable && r.steps > (failed_in_a_step ? 1 : 0)) r.dt_stable_min = dt_stable_min;
  if (obs.final_state) {
    const Particles& P = sim.particles();
    const Scene& scene = sim.scene();
    const double t = sim.time();
    FinalState f{t, P.X, P.x, P.v, P.F, P.sigma, {}, {}, {}};
    f.u_exact = P.X.unaryExpr([&](double X) { return scene.displacement(X, t); });
    f.v_exact = P.X.unaryExpr([&](double X) { return scene.velocity(X, t); });
    f.sigma_exact = P.X.unaryExpr([&](double X) { return scene.stress(X, t); });
    r.final_state = std::move(f);
  }
  r.wall_seconds = std::chrono::duration<double>(stop - start).count();
  if (r.steps > 0) {
    r.ns_per_particle_step = r.wall_seconds * 1e9 / (double(r.steps) * double(r.particles));
  }
  return r;
}

}  // namespace mpmstab
