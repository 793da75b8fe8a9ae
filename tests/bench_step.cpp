// Google Benchmark of the time step on the paper's bar (100 cells x 2 particles = 200 particles).
//
// BM_Step: the four phases only (p2g, grid update, g2p, stress update), what every run pays.
// BM_StepChecked: the step plus the failure check every run does after each step.
// BM_StepInstrumented: plus every observer (error over time, eq. 108, crossings).
// BM_StepBaseline: the same step as a first textbook implementation would write it (below), so
// that one run shows the solver's kernel and a straightforward one side by side.
// BM_RunObservers: a whole run (run(), GIMP, 1000 steps) with the default observers (0), with
// the energy observer on as well (1), and with the L2 error over time on as well (2): what an
// observer costs when it is asked for, and that a run without it pays nothing for it.
// The counter ns_per_particle_step is the time per step divided by the number of particles.
// The output's context names the CPU, the kernels' instruction set on it and the commit, as
// every timing of the harness does (engine/provenance.hpp), so that results/performance.md says
// which machine and which code its figures are of.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "analysis/stable_dt.hpp"
#include "base/failure.hpp"
#include "observers/crossings.hpp"
#include "run/run.hpp"
#include "scenes/bar.hpp"
#include "step/simulation.hpp"

#include "provenance.hpp"

namespace {

using mpmstab::Method;

mpmstab::RunParams bar(Method method) {
  mpmstab::RunParams p;
  p.method = method;
  p.E = 4;
  p.A = 0.015;
  p.dt = 1e-3;
  return p;
}

// What runs after the step: nothing, the failure check, one observer on top of the check, or
// every observer.
enum class Level { step, checked, error, stable_dt, crossings, instrumented };

void set_counters(benchmark::State& state, Method method, double particles) {
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(particles));
  // (particles * 1e-9) per iteration, as a rate, inverted: wall ns per particle-step.
  state.counters["ns_per_particle_step"] =
      benchmark::Counter(particles * 1e-9, benchmark::Counter::kIsIterationInvariantRate |
                                               benchmark::Counter::kInvert);
  state.SetLabel(std::string(to_string(method)));
}

template <Level level>
void BM_Step(benchmark::State& state) {
  const auto method = static_cast<Method>(state.range(0));
  const auto p = bar(method);
  mpmstab::Simulation sim(p);
  mpmstab::CrossingCounter crossings(sim.particles(), 1.0 / p.cells);
  const mpmstab::StableDtGeometry geo{p.method, p.E, 1.0 / p.cells, p.ppc, 1.0 / (p.cells * p.ppc)};
  std::int64_t n = 0;
  for (auto _ : state) {
    if (n == 1000) {  // the run reached T = 1: start it again, as a real run would not go on
      state.PauseTiming();
      sim = mpmstab::Simulation(p);
      crossings = mpmstab::CrossingCounter(sim.particles(), 1.0 / p.cells);
      n = 0;
      state.ResumeTiming();
    }
    // The state's extremes come with the step (in its last pass where it allows it), read by
    // the check, eq. (108) and the error over time, as run() does.
    mpmstab::StateExtremes extremes;
    constexpr bool error = level == Level::error || level == Level::instrumented;
    const double t_next = static_cast<double>(++n) * p.dt;
    if constexpr (level == Level::step) {
      sim.advance_to(t_next);
    } else {
      sim.advance_to(t_next, &extremes, error);
      benchmark::DoNotOptimize(mpmstab::detect_failure(sim.particles(), extremes, p.bc));
    }
    if constexpr (error) benchmark::DoNotOptimize(extremes.error_max);
    if constexpr (level == Level::crossings || level == Level::instrumented) {
      benchmark::DoNotOptimize(crossings.update(sim.particles()));
    }
    if constexpr (level == Level::stable_dt || level == Level::instrumented) {
      benchmark::DoNotOptimize(
          mpmstab::stable_dt(mpmstab::stable_dt_inputs(sim.particles(), extremes, sim.grid(),
                                                       p.stable.vnorm, p.method),
                             geo, p.stable.sigma));
    }
  }
  set_counters(state, method, static_cast<double>(sim.particles().size()));
}

// The textbook step: one loop per phase, every particle visits the nodes near it and evaluates
// S_ip and G_ip from their piecewise definitions in each phase, the sums go straight into the
// grid, particles are an array of structs. The same equations, parameters and initial state as
// mpmstab::Simulation (the stress update uses the gradients at x^n, as USL does).
namespace textbook {

struct Particle {
  double X, x, x_old, v, F, sigma, mass, volume0, body_profile;
};

// S_i and dS_i/dx for a particle at distance r = x_p - X_i: the hat (MPM) or the five uGIMP
// branches of Bardenhagen & Kober (2004).
std::pair<double, double> shape(Method method, double r, double h, double lp) {
  if (method == Method::mpm) {
    if (std::abs(r) >= h) return {0.0, 0.0};
    return {1.0 - std::abs(r) / h, r < 0 ? 1.0 / h : -1.0 / h};
  }
  if (r <= -h - lp || r >= h + lp) return {0.0, 0.0};
  if (r <= -h + lp)
    return {(h + lp + r) * (h + lp + r) / (4 * h * lp), (h + lp + r) / (2 * h * lp)};
  if (r <= -lp) return {1 + r / h, 1 / h};
  if (r <= lp) return {1 - (r * r + lp * lp) / (2 * h * lp), -r / (h * lp)};
  if (r <= h - lp) return {1 - r / h, -1 / h};
  return {(h + lp - r) * (h + lp - r) / (4 * h * lp), -(h + lp - r) / (2 * h * lp)};
}

struct Bar {
  mpmstab::RunParams p;
  mpmstab::BarScene scene;
  double h, lp;
  std::vector<Particle> particles;
  std::vector<double> m, q, f, vel, acc;  // nodes 0 .. N
  double t = 0;

  explicit Bar(const mpmstab::RunParams& params)
      : p(params),
        scene(p.E, p.A),
        h(1.0 / p.cells),
        lp(p.method == Method::gimp ? h / (2.0 * p.ppc) : 0.0),
        m(p.cells + 1),
        q(p.cells + 1),
        f(p.cells + 1),
        vel(p.cells + 1),
        acc(p.cells + 1) {
    const mpmstab::Particles P = scene.initial_particles(p.cells, p.ppc);
    for (Eigen::Index i = 0; i < P.size(); ++i) {
      particles.push_back({P.X[i], P.x[i], P.x[i], P.v[i], P.F[i], P.sigma[i], P.mass[i],
                           P.volume0[i], scene.body_force_profile(P.X[i])});
    }
  }

  // Nodes whose support can contain x.
  std::pair<int, int> nodes_near(double x) const {
    const double reach = h + lp;
    return {std::max(0, static_cast<int>(std::floor((x - reach) / h))),
            std::min(p.cells, static_cast<int>(std::ceil((x + reach) / h)))};
  }

  void step(double dt) {
    const double factor = scene.body_force_factor(t);
    // p2g, eqs. (5)-(7)
    std::fill(m.begin(), m.end(), 0.0);
    std::fill(q.begin(), q.end(), 0.0);
    std::fill(f.begin(), f.end(), 0.0);
    for (const Particle& pt : particles) {
      const auto [first, last] = nodes_near(pt.x);
      for (int i = first; i <= last; ++i) {
        const auto [S, G] = shape(p.method, pt.x - i * h, h, lp);
        m[i] += S * pt.mass;
        q[i] += S * pt.mass * pt.v;
        f[i] += -G * pt.sigma * pt.F * pt.volume0 + S * pt.mass * pt.body_profile * factor;
      }
    }
    // grid update, eqs. (7), (8); nodes 0 and N fixed
    for (int i = 0; i <= p.cells; ++i) {
      if (i == 0 || i == p.cells || m[i] <= 0.0) {
        vel[i] = acc[i] = 0.0;
      } else {
        acc[i] = f[i] / m[i];
        vel[i] = q[i] / m[i] + dt * acc[i];
      }
    }
    // g2p, eqs. (9), (10)
    for (Particle& pt : particles) {
      pt.x_old = pt.x;
      const auto [first, last] = nodes_near(pt.x_old);
      double dv = 0, dx = 0;
      for (int i = first; i <= last; ++i) {
        const double S = shape(p.method, pt.x_old - i * h, h, lp).first;
        dv += S * acc[i];
        dx += S * vel[i];
      }
      pt.v += dt * dv;
      pt.x += dt * dx;
    }
    // stress update, eqs. (11), (13), (14), gradients at x^n
    for (Particle& pt : particles) {
      const auto [first, last] = nodes_near(pt.x_old);
      double L = 0;
      for (int i = first; i <= last; ++i)
        L += shape(p.method, pt.x_old - i * h, h, lp).second * vel[i];
      pt.F *= 1.0 + dt * L;
      pt.sigma = p.E * (pt.F - 1.0);
    }
    t += dt;
  }
};

}  // namespace textbook

void BM_StepBaseline(benchmark::State& state) {
  const auto method = static_cast<Method>(state.range(0));
  const auto p = bar(method);
  textbook::Bar sim(p);
  std::int64_t n = 0;
  for (auto _ : state) {
    if (n == 1000) {  // as BM_Step: start the run again at T = 1
      state.PauseTiming();
      sim = textbook::Bar(p);
      n = 0;
      state.ResumeTiming();
    }
    sim.step(p.dt);
    ++n;
    benchmark::DoNotOptimize(sim.particles.data());
  }
  set_counters(state, method, static_cast<double>(sim.particles.size()));
}

void methods(benchmark::internal::Benchmark* b) {
  b->Arg(static_cast<int>(Method::gimp))->Arg(static_cast<int>(Method::mpm));
}

BENCHMARK(BM_Step<Level::step>)->Name("BM_Step")->Apply(methods);
BENCHMARK(BM_Step<Level::checked>)->Name("BM_StepChecked")->Apply(methods);
BENCHMARK(BM_Step<Level::error>)->Name("BM_StepError")->Apply(methods);
BENCHMARK(BM_Step<Level::stable_dt>)->Name("BM_StepStableDt")->Apply(methods);
BENCHMARK(BM_Step<Level::crossings>)->Name("BM_StepCrossings")->Apply(methods);
BENCHMARK(BM_Step<Level::instrumented>)->Name("BM_StepInstrumented")->Apply(methods);
BENCHMARK(BM_StepBaseline)->Apply(methods);

void BM_RunObservers(benchmark::State& state) {
  mpmstab::RunParams p = bar(Method::gimp);
  p.observe.energy = state.range(0) >= 1;
  p.observe.error_l2 = state.range(0) >= 2;
  double particles = 0, steps = 0;
  for (auto _ : state) {
    const mpmstab::RunResult r = mpmstab::run(p);
    benchmark::DoNotOptimize(r.max_error);
    particles = static_cast<double>(r.particles);
    steps = static_cast<double>(r.steps);
  }
  state.counters["ns_per_particle_step"] =
      benchmark::Counter(particles * steps * 1e-9, benchmark::Counter::kIsIterationInvariantRate |
                                                       benchmark::Counter::kInvert);
  state.SetLabel(state.range(0) == 0   ? "default observers"
                 : state.range(0) == 1 ? "+ energy"
                                       : "+ energy + error_l2");
}
BENCHMARK(BM_RunObservers)->DenseRange(0, 2);
// The other bases' step, against BM_Step's gimp in the same run (no baseline: that is for the
// paper's two bases).
BENCHMARK(BM_Step<Level::step>)
    ->Name("BM_StepNewBases")
    ->Arg(static_cast<int>(Method::cpgimp))
    ->Arg(static_cast<int>(Method::cpdi))
    ->Arg(static_cast<int>(Method::bspline2))
    ->Arg(static_cast<int>(Method::bspline3));

// GIMP's step under each update order and transfer other than USL-FLIP (the choices of the
// methods study), against BM_Step's gimp in the same run.
struct Scheme {
  const char* label;
  mpmstab::UpdateOrder update;
  mpmstab::Transfer transfer;
  int order;  // xpic_order or fmpm_order
};
constexpr Scheme kSchemes[] = {
    {"usf/flip", mpmstab::UpdateOrder::usf, mpmstab::Transfer::flip, 1},
    {"musl/flip", mpmstab::UpdateOrder::musl, mpmstab::Transfer::flip, 1},
    {"usl/pic", mpmstab::UpdateOrder::usl, mpmstab::Transfer::pic, 1},
    {"usl/blend", mpmstab::UpdateOrder::usl, mpmstab::Transfer::blend, 1},
    {"usl/apic", mpmstab::UpdateOrder::usl, mpmstab::Transfer::apic, 1},
    {"usl/xpic(2)", mpmstab::UpdateOrder::usl, mpmstab::Transfer::xpic, 2},
    {"usl/fmpm(2)", mpmstab::UpdateOrder::usl, mpmstab::Transfer::fmpm, 2},
    {"usf/pic", mpmstab::UpdateOrder::usf, mpmstab::Transfer::pic, 1},
    {"musl/pic", mpmstab::UpdateOrder::musl, mpmstab::Transfer::pic, 1},
};

void BM_StepScheme(benchmark::State& state) {
  const Scheme& scheme = kSchemes[state.range(0)];
  auto p = bar(Method::gimp);
  p.update = scheme.update;
  p.transfer = scheme.transfer;
  if (scheme.transfer == mpmstab::Transfer::blend) p.flip_fraction = 0.95;
  if (scheme.transfer == mpmstab::Transfer::xpic) p.xpic_order = scheme.order;
  if (scheme.transfer == mpmstab::Transfer::fmpm) p.fmpm_order = scheme.order;
  mpmstab::Simulation sim(p);
  std::int64_t n = 0;
  for (auto _ : state) {
    if (n == 1000) {
      state.PauseTiming();
      sim = mpmstab::Simulation(p);
      n = 0;
      state.ResumeTiming();
    }
    sim.advance_to(static_cast<double>(++n) * p.dt);
  }
  set_counters(state, Method::gimp, static_cast<double>(sim.particles().size()));
  state.SetLabel(scheme.label);
}
BENCHMARK(BM_StepScheme)->DenseRange(0, static_cast<int>(std::size(kSchemes)) - 1);

}  // namespace

int main(int argc, char** argv) {
  const mpmstab::Provenance here = mpmstab::current_provenance(1);
  benchmark::AddCustomContext("cpu", here.cpu);
  benchmark::AddCustomContext("kernels", here.kernels);
  benchmark::AddCustomContext("commit", here.commit);
  benchmark::AddCustomContext("dirty", here.dirty ? "true" : "false");  // as timings.json says it
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
