// results/performance.md: the step benchmark (Google Benchmark medians), what each measured
// quantity costs, the fraction of the core's peak, and the wall time of every experiment.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "spec.hpp"

namespace mpmstab {

// <out>/performance.md, and <out>/timings.json published from the machine's timings
// (machine_timings(out), report.hpp) when there are any. `bench` is Google Benchmark's JSON
// output of tests/bench_step.cpp (may be missing: the report then says so).
void write_performance(const std::vector<Spec>& specs, const std::filesystem::path& bench,
                       const std::filesystem::path& out);

// The follow-up runs of an experiment (Study::follow_up) as its published results in `out` ask
// for them (expected_follow_ups, report.hpp), each read back from the cache <out>/cache/: how
// many distinct runs (a follow-up that repeats one of the experiment's cases or another follow-up
// is not counted again), how many of them the cache holds with their timing, and the
// particle-steps, CPU seconds and ns per particle-step of those. All zero where the study asks for
// none or its results cannot be read. write_performance records it in timings.json beside the
// experiment's cases when it publishes this machine's timings; performance.md reads it there.
struct FollowUpWork {
  std::size_t runs = 0;
  std::size_t cached = 0;
  double particle_steps = 0;
  double seconds = 0;
  std::vector<double> ns_per_particle_step;
};
FollowUpWork follow_up_work(const Spec& spec, const std::filesystem::path& out);

// The machine of an entry of timings.json: its CPU and the kernels' instruction set it ran
// ("AMD EPYC, AVX2 kernels"); "CPU not recorded" without a CPU, the CPU alone without a version
// (entries written before it was recorded).
std::string machine_of(const nlohmann::ordered_json& timing);

// The step kernel in brief, for README.md's generated block: where and when it was measured,
// the bare, checked and instrumented step and the straightforward baseline per method, and per
// method what each adds. A sentence saying so where `bench` is missing.
std::string kernel_brief(const std::filesystem::path& bench);

}  // namespace mpmstab
