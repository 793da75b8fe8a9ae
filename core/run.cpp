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

RunResult run(const RunParams& p) {
  RunResult r;
  r.params = p;
  const Observe& obs = p.observe;
  const double h = 1.0 / p.cells;

  // 1. Set up the scene and the quantities that do not depend on the run.
  Simulation sim(p);
  r.particles = sim.particles().size();
  r.steps_planned = *step_count(p.T, p.dt);
  r.c = sim.scene().c;
  r.dt_cfl = h / r.c;
  r.dt_sound = 1.0 / r.c;
  r.courant = r.c * p.dt / h;

  // 2. The observers this run asked for.
  std::optional<CrossingCounter> crossing_counter;
  if (obs.crossings) crossing_counter.emplace(sim.particles(), h);
  const StableDtGeometry geometry{p.method, p.E, h, p.ppc, h / p.ppc};
  double max_error_over_time = 0;
  double dt_stable_min = std::numeric_limits<double>::infinity();
  std::int64_t crossings = 0;
  if (obs.history) {
    const auto rows = r.steps_planned / obs.history_stride + 1;
    r.history.reserve(static_cast<std::size_t>(std::min<std::int64_t>(rows, 10'000'000)));
  }

  std::optional<HistoryRow> pending_row;  // last row not kept by the stride

  // 3. Step to T, checking the state after every step.
  const auto start = std::chrono::steady_clock::now();
  for (std::int64_t n = 0; n < r.steps_planned; ++n) {
    const bool last = n + 1 == r.steps_planned;
    sim.advance_to(last ? p.T : static_cast<double>(n + 1) * p.dt);
    if (auto failure = detect_failure(sim.particles(), p.bc)) {
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
    if (obs.dt_stable) {
      const double bound = stable_dt(stable_dt_inputs(sim.particles(), sim.grid(), p.stable.vnorm),
                                     geometry, p.stable.sigma);
      dt_stable_min = std::min(dt_stable_min, bound);
      row.dt_stable = bound;
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
  r.stable = !r.failure.has_value();
  if (r.stable) r.max_error = sim.max_error();
  if (obs.error_over_time) {
    r.max_error_over_time = max_error_over_time;
    if (r.stable) r.meaningless = max_error_over_time > 0 && max_error_over_time >= p.A;
  }
  if (obs.crossings) r.crossings = crossings;
  if (obs.dt_stable && r.steps > (r.failure ? 1 : 0)) r.dt_stable_min = dt_stable_min;
  if (obs.final_state) {
    const Particles& P = sim.particles();
    const BarScene& scene = sim.scene();
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
