// results/performance.md: the step benchmark (Google Benchmark medians), what each measured
// quantity costs, the fraction of the core's peak, and the wall time of every experiment.
#pragma once

#include <filesystem>
#include <vector>

#include "spec.hpp"

namespace mpmstab {

// <out>/performance.md, and <out>/timings.json published from the machine's timings
// (machine_timings(out), report.hpp) when there are any. `bench` is Google Benchmark's JSON
// output of tests/bench_step.cpp (may be missing: the report then says so).
void write_performance(const std::vector<Spec>& specs, const std::filesystem::path& bench,
                       const std::filesystem::path& out);

}  // namespace mpmstab
