// `mpmstab performance`: results/performance.md.
#include <iostream>

#include "commands.hpp"
#include "performance.hpp"

namespace mpmstab::cli {

int cmd_performance(const std::vector<std::string_view>& argv) {
  const Args args(argv, {{"out"}, {"bench"}, {"help", false}});
  if (args.flag("help")) {
    std::cout
        << "Usage: mpmstab performance <spec.json>... --bench <benchmark.json> [--out DIR]\n\n"
           "Writes DIR/performance.md from Google Benchmark's JSON output of the step\n"
           "benchmark and the timing of every experiment in DIR/<name>.json.\n";
    return 0;
  }
  const auto specs = load_specs(args.positional());
  const auto out = output_folder(args);
  make_output_folder(out);
  write_performance(
      specs, std::string(args.value("bench").value_or(out.string() + "/benchmark_step.json")), out);
  return 0;
}

}  // namespace mpmstab::cli
