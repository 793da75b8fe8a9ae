// `mpmstab sweep`, `mpmstab index` and `mpmstab plot`: experiments from JSON specs.
#include <unistd.h>

#include <atomic>
#include <csignal>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <thread>

#include "args.hpp"
#include "atomic_file.hpp"
#include "commands.hpp"
#include "comparison.hpp"
#include "csv.hpp"
#include "merge.hpp"
#include "performance.hpp"
#include "regression.hpp"
#include "report.hpp"
#include "spec.hpp"
#include "sweep.hpp"

namespace mpmstab::cli {

namespace {

constexpr const char* kSweepHelp =
    R"(Usage: mpmstab sweep <spec.json> [--jobs N] [--out DIR] [--force] [--shard I/N]
                    [--timing keep|omit]

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
  --shard I/N  run only shard I (0 <= I < N) of the cases and write no report: each case
             belongs to the shard given by a hash of its key (parameters, solver version), so
             it always lands in the same shard whatever the order of the spec. The records go
             to DIR/cache/, with a manifest DIR/<name>.shard-I-of-N.json; 'mpmstab merge'
             gathers the shards and writes the reports (see experiments/README.md).
  --timing keep|omit
             omit: reports leave out the machine measurements (wall times and ns per
             particle-step read 0, date and threads "omitted"), so that two runs of the same
             spec compare byte for byte, whatever the machine or the number of shards. The
             cache keeps the measurements. Default keep.
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

// SIGINT and SIGTERM during a sweep: the handler only raises this flag (async-signal-safe);
// the sweep stops promptly, keeps its finished cases in the cache and writes no report. A
// second signal gets the default action (the handler is reset when it runs).
std::atomic<bool> g_stop{false};
volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_stop_signal(int sig) {
  g_signal = sig;
  g_stop.store(true);
}

void install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

}  // namespace

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

bool omit_timing(const Args& args) {
  const auto v = args.value("timing");
  if (!v || *v == "keep") return false;
  if (*v == "omit") return true;
  throw UsageError("--timing: unknown value '" + std::string(*v) + "' (expected keep or omit)");
}

namespace {

Shard parse_shard(std::string_view text) {
  const auto slash = text.find('/');
  const std::string_view message = "must be I/N with integers 0 <= I < N <= 100000, got '";
  if (slash == std::string_view::npos) {
    throw UsageError("--shard: " + std::string(message) + std::string(text) + "'");
  }
  Shard s;
  try {
    s.index = static_cast<int>(parse_int(text.substr(0, slash), "shard"));
    s.count = static_cast<int>(parse_int(text.substr(slash + 1), "shard"));
  } catch (const UsageError&) {
    throw UsageError("--shard: " + std::string(message) + std::string(text) + "'");
  }
  if (s.count < 1 || s.count > 100000 || s.index < 0 || s.index >= s.count) {
    throw UsageError("--shard: " + std::string(message) + std::string(text) + "'");
  }
  return s;
}

}  // namespace

int cmd_sweep(const std::vector<std::string_view>& argv) {
  const Args args(argv,
                  {{"jobs"}, {"out"}, {"force", false}, {"shard"}, {"timing"}, {"help", false}});
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
  if (auto v = args.value("shard")) options.shard = parse_shard(*v);
  const bool omit = omit_timing(args);
  const Spec spec = load_specs(args.positional()).front();
  const auto out = output_folder(args);
  options.cache = out / "cache";
  options.progress_line = ::isatty(STDERR_FILENO) != 0;
  options.cancel = &g_stop;
  install_stop_handlers();

  SweepOutcome outcome = run_sweep(spec, options);
  if (outcome.interrupted) {
    const int sig = g_signal ? static_cast<int>(g_signal) : SIGINT;
    std::cerr << "\n[" << spec.name << "] interrupted by "
              << (sig == SIGTERM ? "SIGTERM" : "SIGINT") << ": "
              << outcome.computed + outcome.cached + outcome.shared << " of " << spec.cases.size()
              << " cases finished and are kept in " << options.cache.string()
              << "; no report was written. Run the same command again to resume.\n";
    return 128 + sig;
  }
  if (options.shard) {
    // A shard writes its records (in the cache) and a manifest, never a partial report.
    const Shard& sh = *options.shard;
    const nlohmann::ordered_json manifest = {{"spec", spec.path.generic_string()},
                                             {"name", spec.name},
                                             {"shard", sh.index},
                                             {"of", sh.count},
                                             {"cases", spec.cases.size() - outcome.other_shards},
                                             {"computed", outcome.computed},
                                             {"cached", outcome.cached},
                                             {"wall_seconds", outcome.wall_seconds}};
    write_file_atomically(shard_manifest(out, spec.name, sh), manifest.dump(2) + "\n");
    std::cerr << "[" << spec.name << "] shard " << sh.index << "/" << sh.count << ": "
              << spec.cases.size() - outcome.other_shards << " of " << spec.cases.size()
              << " cases (" << outcome.computed << " computed, " << outcome.cached
              << " from the cache) in " << shortest(std::round(outcome.wall_seconds * 100) / 100)
              << " s -> " << options.cache.string() << "\n";
    return 0;
  }
  const double wall_seconds = outcome.wall_seconds;  // for the summary line, also when omitted
  if (omit) omit_machine_measurements(outcome);
  write_reports(spec, outcome, out);
  std::cerr << "[" << spec.name << "] " << spec.cases.size() << " cases (" << outcome.computed
            << " computed, " << outcome.cached << " from the cache, "
            << (outcome.shared
                    ? std::to_string(outcome.shared) + " sharing the run of an identical case, "
                    : std::string())
            << outcome.unstable << " unstable) in "
            << shortest(std::round(wall_seconds * 100) / 100) << " s -> "
            << (out / (spec.name + ".md")).string() << "\n";
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

int cmd_compare(const std::vector<std::string_view>& argv) {
  const Args args(argv, {{"out"}, {"error-at"}, {"help", false}});
  if (args.flag("help")) {
    std::cout
        << "Usage: mpmstab compare <table1 spec> [<supporting spec>...] [--out DIR]\n"
           "                       [--error-at T|max_over_time]\n\n"
           "Writes DIR/comparison.md and DIR/comparison.csv: every Table 1 cell against the "
           "paper,\nwith its verdict, its class of disagreement and the supporting experiments "
           "(courant,\nwalls, crossing, eq108) read from DIR/<name>.json. Each class section "
           "links the variants\nstudy (DIR/variants.json, experiments/variants.json) when it "
           "has been run.\n\n"
           "Options:\n"
           "  --out DIR       folder of the results and of the comparison (default results)\n"
           "  --error-at X    which of our errors is compared with the paper's \"Max Error\": "
           "T, the max\n"
           "                  error at the final time (max_error, the default), or "
           "max_over_time, the\n"
           "                  largest over the run (max_error_over_time; the table1 spec must "
           "record\n"
           "                  error_over_time). Without it, each case's error_at in the spec "
           "decides\n"
           "                  (default T).\n";
    return 0;
  }
  std::optional<ErrorAt> error_at;
  if (auto v = args.value("error-at")) {
    error_at = parse_error_at(*v);
    if (!error_at) {
      throw UsageError("--error-at: unknown value '" + std::string(*v) +
                       "' (expected T or max_over_time)");
    }
  }
  auto specs = load_specs(args.positional());
  if (specs.front().report != ReportKind::table1) {
    throw UsageError(specs.front().path.string() + ": the first spec must be a table1 spec");
  }
  const Spec table1 = specs.front();
  specs.erase(specs.begin());
  if (error_at == ErrorAt::max_over_time) {
    for (const auto& c : table1.cases) {
      if (!c.params.observe.error_over_time) {
        throw UsageError("--error-at max_over_time: " + table1.path.string() +
                         " does not record error_over_time");
      }
    }
  }
  const auto out = output_folder(args);
  if (!std::filesystem::exists(out / (table1.name + ".json"))) {
    throw UsageError((out / (table1.name + ".json")).string() +
                     " does not exist: run mpmstab sweep " + table1.path.string() + " first");
  }
  write_comparison(table1, specs, out, error_at);
  return 0;
}

namespace {

const std::vector<OptionSpec> kRegressionOptions = {
    {"reference"}, {"results"}, {"jobs"}, {"rtol"}, {"budget"}, {"reason"}, {"help", false}};

constexpr const char* kCheckHelp = R"(Usage: mpmstab check <spec.json>... [options]
       mpmstab bless <spec.json>... --reason "..." [options]

check reruns the fast subset of every given experiment (its cases needing at most --budget
particle-steps, computed afresh, never from the cache), compares them with the blessed values
in --reference, and compares the paper-comparison verdicts (--results/comparison.csv) with
their blessed expectations. Every failing cell is printed with its parameters, the column,
the expected and obtained values, the relative difference and the tolerance. Exit status 1
when anything differs.

bless rewrites the blessed values that changed and appends the date, the commit, the reason
and the cells changed to --reference/BLESSED.md. It refuses to run without a reason.

Options:
  --reference DIR  blessed values (default reference/regression)
  --results DIR    where comparison.csv is (default results)
  --jobs N         cases run in parallel (default: all cores)
  --rtol X         relative tolerance of floating-point columns (default 0: the runs are
                   deterministic, so any difference is a real change)
  --budget X       particle-steps of the largest case in the fast subset (default 2e7)
)";

RegressionOptions regression_options(const Args& args) {
  RegressionOptions o;
  o.jobs = default_jobs();
  if (auto v = args.value("reference")) o.reference = std::string(*v);
  if (auto v = args.value("results")) o.results = std::string(*v);
  if (auto v = args.value("jobs")) {
    const auto jobs = parse_int(*v, "jobs");
    if (jobs < 1 || jobs > 1024) throw UsageError("--jobs: must be in [1, 1024]");
    o.jobs = static_cast<int>(jobs);
  }
  if (auto v = args.value("rtol")) {
    o.rtol = parse_double(*v, "rtol");
    if (!(o.rtol >= 0 && o.rtol < 1)) throw UsageError("--rtol: must be in [0, 1)");
  }
  if (auto v = args.value("budget")) {
    o.budget = parse_double(*v, "budget");
    if (!(o.budget > 0 && std::isfinite(o.budget))) throw UsageError("--budget: must be > 0");
  }
  return o;
}

}  // namespace

int cmd_check(const std::vector<std::string_view>& argv) {
  const Args args(argv, kRegressionOptions);
  if (args.flag("help")) {
    std::cout << kCheckHelp;
    return 0;
  }
  if (args.value("reason")) throw UsageError("--reason belongs to mpmstab bless");
  const auto specs = load_specs(args.positional());
  return run_check(specs, regression_options(args));
}

int cmd_bless(const std::vector<std::string_view>& argv) {
  const Args args(argv, kRegressionOptions);
  if (args.flag("help")) {
    std::cout << kCheckHelp;
    return 0;
  }
  const std::string reason(args.value("reason").value_or(""));
  if (reason.find_first_not_of(" \t\n") == std::string::npos) {
    throw UsageError("--reason: a blessing needs a reason, e.g. make bless REASON=\"...\"");
  }
  const auto specs = load_specs(args.positional());
  return run_bless(specs, regression_options(args), reason);
}

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
  write_performance(
      specs, std::string(args.value("bench").value_or(out.string() + "/benchmark_step.json")), out);
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
  if (spec.report == ReportKind::table1 || spec.report == ReportKind::table2 ||
      spec.report == ReportKind::cases) {  // tables only
    throw UsageError(spec.path.string() + ": a " + std::string(to_string(spec.report)) +
                     " experiment has no figure");
  }
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
  std::string subtitle, dt = "0";
  if (spec.report == ReportKind::figure) {
    subtitle = std::string(c["method"]) + ", E = " + shortest(c["E"]) +
               ", A = " + shortest(c["A"]) + ", dt = " + shortest(c["dt"]) + ", " +
               c["cells"].dump() + " cells x " + c["ppc"].dump() + " ppc, " + std::string(c["bc"]) +
               "; ";
    subtitle += c["stable"] == true ? "stable to T"
                                    : "unstable: " + std::string(c["failure_reason"]) +
                                          " at step " + c["failure_step"].dump();
    dt = shortest(c["dt"]);
  } else {
    // Studies over several scenes draw the first one (report.cpp: by_scene); say so.
    std::size_t drawn = 0;
    for (const auto& r : doc["cases"])
      drawn += r.value("scene", "") == c.value("scene", "");
    subtitle = std::to_string(drawn) + " cases";
    if (drawn < doc["cases"].size()) {
      subtitle += " of the scene " + c.value("scene", std::string()) + " (of " +
                  std::to_string(doc["cases"].size()) + "; every scene is in the tables)";
    }
    subtitle += "; the parameters of each are in " + spec.name + ".md";
  }
  const auto tmp = out / ("." + spec.name + ".tmp");
  const std::string command = "gnuplot -e \"datafile='" + data.string() + "'; outbase='" +
                              tmp.string() + "'; subtitle='" + subtitle + "'; dt=" + dt + "\" '" +
                              script.string() + "'";
  if (std::system(command.c_str()) != 0) {
    throw std::runtime_error("gnuplot failed: " + command);
  }
  for (const char* ext : {".png", ".svg"}) {
    std::filesystem::rename(tmp.string() + ext, out / (spec.name + ext));
  }
  return 0;
}

}  // namespace mpmstab::cli
