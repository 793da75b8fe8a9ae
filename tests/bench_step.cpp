// Google Benchmark of the time step on the paper's bar (100 cells x 2 particles = 200 particles).
//
// BM_Step: the four phases only (p2g, grid update, g2p, stress update), what every run pays.
// BM_StepChecked: the step plus the failure check every run does after each step.
// BM_StepInstrumented: plus every observer (error over time, eq. 108, crossings).
// The counter ns_per_particle_step is the time per step divided by the number of particles.
#include <benchmark/benchmark.h>

#include "crossings.hpp"
#include "failure.hpp"
#include "simulation.hpp"
#include "stable_dt.hpp"

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

enum class Level { step, checked, instrumented };

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
    sim.advance_to(static_cast<double>(++n) * p.dt);
    if constexpr (level != Level::step) {
      benchmark::DoNotOptimize(mpmstab::detect_failure(sim.particles(), p.bc));
    }
    if constexpr (level == Level::instrumented) {
      benchmark::DoNotOptimize(sim.max_error());
      benchmark::DoNotOptimize(crossings.update(sim.particles()));
      benchmark::DoNotOptimize(
          mpmstab::stable_dt(mpmstab::stable_dt_inputs(sim.particles(), sim.grid(), p.stable.vnorm),
                             geo, p.stable.sigma));
    }
  }
  const double particles = static_cast<double>(sim.particles().size());
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(particles));
  // (particles * 1e-9) per iteration, as a rate, inverted: wall ns per particle-step.
  state.counters["ns_per_particle_step"] =
      benchmark::Counter(particles * 1e-9, benchmark::Counter::kIsIterationInvariantRate |
                                               benchmark::Counter::kInvert);
  state.SetLabel(method == Method::gimp ? "gimp" : "mpm");
}

void methods(benchmark::internal::Benchmark* b) {
  b->Arg(static_cast<int>(Method::gimp))->Arg(static_cast<int>(Method::mpm));
}

BENCHMARK(BM_Step<Level::step>)->Name("BM_Step")->Apply(methods);
BENCHMARK(BM_Step<Level::checked>)->Name("BM_StepChecked")->Apply(methods);
BENCHMARK(BM_Step<Level::instrumented>)->Name("BM_StepInstrumented")->Apply(methods);

}  // namespace

BENCHMARK_MAIN();
