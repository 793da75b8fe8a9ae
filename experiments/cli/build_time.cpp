// `mpmstab build-time`: the wall time of a fresh build of the tool, which the Makefile measures,
// recorded in the machine's timings beside the tiers' runs.
#include <cmath>
#include <iostream>
#include <string>

#include "commands.hpp"
#include "provenance.hpp"
#include "report.hpp"

namespace mpmstab::cli {

namespace {

constexpr const char* kBuildTimeHelp =
    R"help(Usage: mpmstab build-time --seconds <x> [--jobs <n>] [--out DIR]

Records the wall time of a fresh build of the tool in DIR/cache/timings.json (DIR default
results) as the entry "(make)", with this machine's CPU, the kernels' instruction set and the
commit. `make` calls it after building the tool in a build folder it had to create: the time
runs from configuring to the linked tool, the installation of Debian packages excluded.
`make timings` publishes it with the tiers' runs (results/timings.json, README.md,
results/performance.md).

  --seconds <x>  the build's wall time, > 0
  --jobs <n>     the parallel compile jobs it ran with, 1 to 1024 (default: the CPUs this
                 process may run on)
)help";

}  // namespace

int cmd_build_time(const std::vector<std::string_view>& argv) {
  const Args args(argv, {{"seconds"}, {"jobs"}, {"out"}, {"help", false}});
  if (args.flag("help")) {
    std::cout << kBuildTimeHelp;
    return 0;
  }
  if (!args.positional().empty()) throw UsageError("build-time takes no positional argument");
  const auto text = args.value("seconds");
  if (!text) throw UsageError("--seconds is required");
  const double seconds = parse_double(*text, "seconds");
  if (!std::isfinite(seconds) || seconds <= 0)
    throw UsageError("--seconds: must be a positive number of seconds, got " + std::string(*text));
  int jobs = default_jobs();
  if (const auto v = args.value("jobs")) {
    const auto n = parse_int(*v, "jobs");
    if (n < 1 || n > 1024) throw UsageError("--jobs: must be in [1, 1024], got " + std::string(*v));
    jobs = static_cast<int>(n);
  }
  const auto out = output_folder(args);
  make_output_folder(out);
  const Provenance p = current_provenance(jobs);
  // Recording the time is a convenience of `make`: a record that cannot be written is said in
  // one plain line, with status 1, and the Makefile goes on.
  try {
    write_reproduce_timing(out, "make",
                           {{"wall_seconds", seconds},
                            {"commit", p.commit},
                            {"dirty", p.dirty},
                            {"cpu", p.cpu},
                            {"kernels", p.kernels},
                            {"threads", jobs}},
                           true);
  } catch (const std::exception& e) {
    std::cerr << "mpmstab build-time: the build time was not recorded: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace mpmstab::cli
