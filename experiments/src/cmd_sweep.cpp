// `mpmstab sweep`, `mpmstab index` and `mpmstab plot`: experiments from JSON specs.
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <thread>

#include "args.hpp"
#include "atomic_file.hpp"
#include "commands.hpp"
#include "csv.hpp"
#include "report.hpp"
#include "spec.hpp"
#include "sweep.hpp"

namespace mpmstab::cli {

namespace {

constexpr const char* kSweepHelp =
    R"(Usage: mpmstab sweep <spec.json> [--jobs N] [--out DIR] [--force]

Runs every case of an experiment spec and writes its reports:
  DIR/<name>.csv    one row per case, every measured quantity, '#' provenance lines
  DIR/<name>.json   the same content
  DIR/<name>.md     the paper's layout with the paper's values beside ours
  DIR/<name>_data.csv  (figures) the history or final state the gnuplot script draws
Finished cases are cached in DIR/cache/ under a hash of their parameters and the solver
version, and are not computed again unless that key changes or --force is given.

Options:
  --jobs N   cases run in parallel (default: all cores); results do not depend on N
  --out DIR  output folder (default results)
  --force    compute every case again
  --help     show this text

Exit status: 0 when every case ran (unstable runs are results), 2 for an invalid spec or
option (nothing is run or written), 1 for an internal error.
)";

constexpr const char* kIndexHelp = R"(Usage: mpmstab index <spec.json>... [--out DIR]

Writes DIR/README.md (default results/README.md), the index of the reports of the given specs.
)";

constexpr const char* kPlotHelp = R"(Usage: mpmstab plot <spec.json> [--out DIR]

Draws a figure experiment with gnuplot: runs experiments/<name>.gp (beside the spec) on
DIR/<name>_data.csv and writes DIR/<name>.png and DIR/<name>.svg atomically.
)";

int default_jobs() {
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : static_cast<int>(n);
}

std::vector<Spec> load_specs(const std::vector<std::string_view>& paths) {
  if (paths.empty()) throw UsageError("missing <spec.json>");
  std::vector<Spec> specs;
  for (auto path : paths) {
    try {
      specs.push_back(load_spec(std::string(path)));
    } catch (const SpecError& e) {
      throw UsageError(e.what());
    }
  }
  return specs;
}

// The output folder must exist or be creatable, and be writable, before anything runs.
std::filesystem::path output_folder(const Args& args) {
  const std::filesystem::path out(args.value("out").value_or("results"));
  std::error_code ec;
  if (std::filesystem::exists(out, ec) && !std::filesystem::is_directory(out, ec)) {
    throw UsageError("--out: " + out.string() + " is not a folder");
  }
  std::filesystem::create_directories(out, ec);
  if (ec) throw UsageError("--out: cannot create " + out.string() + ": " + ec.message());
  if (::access(out.c_str(), W_OK) != 0) {
    throw UsageError("--out: " + out.string() + " is not writable");
  }
  return out;
}

}  // namespace

int cmd_sweep(const std::vector<std::string_view>& argv) {
  const Args args(argv, {{"jobs"}, {"out"}, {"force", false}, {"help", false}});
  if (args.flag("help")) {
    std::cout << kSweepHelp;
    return 0;
  }
  if (args.positional().size() > 1) throw UsageError("sweep takes one spec");
  SweepOptions options;
  options.jobs = default_jobs();
  if (auto v = args.value("jobs")) {
    const auto jobs = parse_int(*v, "jobs");
    if (jobs < 1 || jobs > 1024)
      throw UsageError("--jobs: must be in [1, 1024], got " + std::string(*v));
    options.jobs = static_cast<int>(jobs);
  }
  options.force = args.flag("force");
  const Spec spec = load_specs(args.positional()).front();
  const auto out = output_folder(args);
  options.cache = out / "cache";
  options.progress_line = ::isatty(STDERR_FILENO) != 0;

  const SweepOutcome outcome = run_sweep(spec, options);
  write_reports(spec, outcome, out);
  std::cerr << "[" << spec.name << "] " << spec.cases.size() << " cases (" << outcome.computed
            << " computed, " << outcome.cached << " from the cache, " << outcome.unstable
            << " unstable) in " << shortest(std::round(outcome.wall_seconds * 100) / 100)
            << " s -> " << (out / (spec.name + ".md")).string() << "\n";
  return 0;
}

int cmd_index(const std::vector<std::string_view>& argv) {
  const Args args(argv, {{"out"}, {"help", false}});
  if (args.flag("help")) {
    std::cout << kIndexHelp;
    return 0;
  }
  const auto specs = load_specs(args.positional());
  write_index(specs, output_folder(args));
  return 0;
}

int cmd_plot(const std::vector<std::string_view>& argv) {
  const Args args(argv, {{"out"}, {"help", false}});
  if (args.flag("help")) {
    std::cout << kPlotHelp;
    return 0;
  }
  if (args.positional().size() != 1) throw UsageError("plot takes one spec");
  const Spec spec = load_specs(args.positional()).front();
  if (spec.report != ReportKind::figure) throw UsageError(spec.path.string() + ": not a figure");
  const auto out = output_folder(args);
  const auto script = spec.path.parent_path() / (spec.name + ".gp");
  const auto data = out / (spec.name + "_data.csv");
  const auto summary = out / (spec.name + ".json");
  for (const auto& f : {script, data, summary}) {
    if (!std::filesystem::exists(f)) throw UsageError(f.string() + " does not exist");
  }
  std::ifstream in(summary);
  const auto doc = nlohmann::json::parse(in);
  const auto& c = doc["cases"][0];
  std::string subtitle = std::string(c["method"]) + ", E = " + shortest(c["E"]) +
                         ", A = " + shortest(c["A"]) + ", dt = " + shortest(c["dt"]) + ", " +
                         c["cells"].dump() + " cells x " + c["ppc"].dump() + " ppc, " +
                         std::string(c["bc"]) + "; ";
  subtitle += c["stable"] == true ? "stable to T"
                                  : "unstable: " + std::string(c["failure_reason"]) + " at step " +
                                        c["failure_step"].dump();
  const auto tmp = out / ("." + spec.name + ".tmp");
  const std::string command = "gnuplot -e \"datafile='" + data.string() + "'; outbase='" +
                              tmp.string() + "'; subtitle='" + subtitle +
                              "'; dt=" + shortest(c["dt"]) + "\" '" + script.string() + "'";
  if (std::system(command.c_str()) != 0) {
    throw std::runtime_error("gnuplot failed: " + command);
  }
  for (const char* ext : {".png", ".svg"}) {
    std::filesystem::rename(tmp.string() + ext, out / (spec.name + ext));
  }
  return 0;
}

}  // namespace mpmstab::cli
