// `mpmstab sweep`: the cases of one spec, run in parallel (or from the cache), and its reports;
// for a study without cases of its own, its reports from its inputs. `mpmstab reproduce`: the
// cases of several specs in one queue, each spec's reports written as soon as it is complete.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <csignal>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "cache.hpp"
#include "commands.hpp"
#include "csv.hpp"
#include "files.hpp"
#include "merge.hpp"
#include "progress.hpp"
#include "provenance.hpp"
#include "report.hpp"
#include "report_util.hpp"
#include "spec.hpp"
#include "sweep.hpp"

namespace mpmstab::cli {

namespace {

// Follow-up runs (Study::follow_up) on the sweep's threads and through its cache, quietly: the
// progress line belongs to the main queue.
FollowUpRunner follow_up_runner(const SweepOptions& options) {
  return [options](const Spec& follow) {
    // The runs a study asks for once its sweep is done are not in the queue's progress line:
    // say that they run, so that the report's wait is not a silent one.
    if (!options.quiet)
      std::cerr << (options.progress_line ? "\r\033[K" : "") << "[" << follow.name << "] "
                << follow.cases.size() << " follow-up run" << (follow.cases.size() == 1 ? "" : "s")
                << " before the reports\n";
    SweepOptions o = options;
    o.quiet = true;
    o.progress_line = false;
    o.shard.reset();
    return run_sweep(follow, o);
  };
}

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
  --jobs N   cases run in parallel (default: the CPUs it may run on); results do not depend on N
  --out DIR  output folder (default results)
  --force    compute every case again
  --shard I/N  run only shard I (0 <= I < N) of the cases and write no report: each case
             belongs to the shard given by a hash of its key (parameters, solver version), so
             it always lands in the same shard whatever the order of the spec. The records go
             to DIR/cache/, with a manifest DIR/<name>.shard-I-of-N.json; 'mpmstab merge'
             gathers the shards and writes the reports (see README.md, "Running on a cluster").
  --timing keep|omit
             The reports never hold machine measurements: wall times, ns per
             particle-step, date and threads go to DIR/cache/timings.json only. omit writes
             zeros (and "omitted") there too, so that two whole folders compare byte for
             byte, whatever the machine or the number of shards. The cache keeps the
             measurements. Default keep.
  --help     show this text

Exit status: 0 when every case ran (unstable runs are results), 2 for an invalid spec or
option (nothing is run or written), 1 for an internal error.
)";

constexpr const char* kReproduceHelp =
    R"(Usage: mpmstab reproduce <spec.json>... [--jobs N] [--out DIR] [--force]
                        [--timing keep|omit] [--label NAME] [--shard I/N]
       mpmstab reproduce <spec.json>... <dir>... --follow-ups --shard I/N [--jobs N] [--out DIR]

Runs the cases of every spec given in one queue, longest first by their estimated
particle-steps, on N threads: no thread idles while another finishes a long case of another
experiment, and a case repeated within or across experiments (the same cache key) runs once.
Each experiment's reports (as 'mpmstab sweep' writes them) are written as soon as its cases are
done and the experiments it reads have been written; a study without cases of its own is
written when its inputs are. One progress line covers the whole run: cases done of all,
particle-steps done of the estimated total, elapsed time and the time to go at the rate
measured so far (on a terminal redrawn in place, otherwise printed every 10 s).

Each experiment's follow-up runs (runs its study chooses from its results: ensembles of
perturbed layouts near an edge, confirming runs of a recommendation) join the same queue as
soon as its cases are done and what it reads is written, and its reports are written when they
are done. The line's total grows as they join, and counts the dense spectral analyses the runs
ask for (kDenseAnalysisCost, engine/sweep.hpp) as the particle-steps that take as long, and the
runs a report makes itself while it renders (the advice sample's searches): as many as its last
render that made some counted, then as they are made. The tier's entry in DIR/cache/timings.json
counts those runs in its work and CPU time, and apart in report_runs.

The specs are taken in the order given ('mpmstab list' prints them in the order make reproduce
uses). An input that none of them produces must already be in DIR. --label NAME names the run
in the progress line and in DIR/cache/timings.json, whose key is NAME in parentheses (make
reproduce: 'make reproduce', make studies: 'make studies'; default 'reproduce'). Options as for
'mpmstab sweep'. With --shard I/N only shard I of the cases of every spec given runs (each case
in the shard 'mpmstab sweep --shard' gives it), in one queue, into DIR/cache/ with a manifest
DIR/<name>.shard-I-of-N.json per spec, and nothing else: no follow-up run, no report, no input
read ('mpmstab slurm --tier' runs a tier's shards so, then renders the tier from their records).
With --follow-ups, the folders given after the specs hold the records of every case (the shards'
folders, as 'mpmstab merge' takes them; a case missing from all is refused, naming it), and the
queue runs shard I of the follow-up runs those records alone decide: those of every study that
reads no other experiment's results, chosen as make reproduce chooses them. They go into
DIR/cache/ with a manifest per experiment; 'mpmstab merge --records-only --with-follow-ups'
gathers them. A study that reads another experiment's results chooses its follow-up runs when
make reproduce writes it.
Exit status: 0 when every case ran, 2 for an invalid spec or option (nothing is run or written),
1 for an internal error, 128 + the signal when interrupted (the finished cases stay in the
cache; reports of complete experiments stay written).
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

namespace {

SweepOptions sweep_options(const Args& args) {
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
  return options;
}

// A study without cases of its own: its reports from the results of its inputs.
int derive(const Spec& spec, const SweepOptions& options, const std::filesystem::path& out) {
  if (options.shard) throw UsageError("--shard: " + spec.path.string() + " has no cases");
  try {
    write_derived_reports(spec, out);
  } catch (const MissingInput& e) {
    throw UsageError(e.what());
  }
  std::cerr << "[" << spec.name << "] from " << spec.inputs.size() << " inputs -> " << out.string()
            << "\n";
  return 0;
}

int interrupted(const Spec& spec, const SweepOutcome& outcome, const SweepOptions& options) {
  const int sig = g_signal ? static_cast<int>(g_signal) : SIGINT;
  std::cerr << "\n[" << spec.name << "] interrupted by " << (sig == SIGTERM ? "SIGTERM" : "SIGINT")
            << ": " << outcome.computed + outcome.cached + outcome.shared << " of "
            << spec.cases.size() << " cases finished and are kept in " << options.cache.string()
            << "; no report was written. Run the same command again to resume.\n";
  return 128 + sig;
}

// A shard writes its records (in the cache) and a manifest, never a partial report.
int finish_shard(const Spec& spec, const SweepOutcome& outcome, const SweepOptions& options,
                 const std::filesystem::path& out) {
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
            << spec.cases.size() - outcome.other_shards << " of " << spec.cases.size() << " cases ("
            << outcome.computed << " computed, " << outcome.cached << " from the cache) in "
            << shortest(std::round(outcome.wall_seconds * 100) / 100) << " s -> "
            << options.cache.string() << "\n";
  return 0;
}

}  // namespace

namespace {

std::string summary_line(const Spec& spec, const SweepOutcome& outcome, double wall_seconds,
                         const std::filesystem::path& out) {
  std::ostringstream line;
  line << "[" << spec.name << "] " << spec.cases.size() << " cases (" << outcome.computed
       << " computed, " << outcome.cached << " from the cache, "
       << (outcome.shared
               ? std::to_string(outcome.shared) + " sharing the run of an identical case, "
               : std::string())
       << outcome.unstable << " unstable"
       << (outcome.rejected ? "; " + std::to_string(outcome.rejected) +
                                  " cache records failed their checksum or shape and were "
                                  "computed again"
                            : std::string())
       << ") in " << shortest(std::round(wall_seconds * 100) / 100) << " s -> "
       << (out / (spec.name + ".md")).string() << "\n";
  return line.str();
}

}  // namespace

namespace {

// What make reproduce runs: every spec, checked before any work, with the experiments each one
// reads that another of them writes.
struct ReproducePlan {
  std::vector<Spec> specs;
  std::vector<std::set<std::string>> waits_for;
};

// 1. Every spec, and every input none of them produces, read and checked before any work (a
// shard reads no input: it only runs cases).
ReproducePlan plan_reproduce(const std::vector<std::string_view>& spec_args,
                             const std::filesystem::path& out, bool shard) {
  ReproducePlan plan;
  plan.specs = load_specs(spec_args);
  std::set<std::string> produced;
  for (const auto& spec : plan.specs) {
    if (!produced.insert(spec.name).second) {
      throw UsageError(spec.path.string() + ": a second experiment named '" + spec.name + "'");
    }
  }
  plan.waits_for.resize(plan.specs.size());
  for (std::size_t s = 0; s < plan.specs.size(); ++s) {
    for (const auto& input : load_inputs(plan.specs[s]))
      if (produced.count(input.name)) plan.waits_for[s].insert(input.name);
    if (shard) continue;
    try {
      check_inputs(plan.specs[s], out, produced);
    } catch (const MissingInput& e) {
      throw UsageError(e.what());
    }
  }
  return plan;
}

// 2. Publishes each experiment once its cases are complete and what it reads is written: its
// follow-up runs (Study::follow_up) first join the queue, and it is published when they are
// done. Counts the work of the whole reproduction (a record shared by several cases once).
class ReproducePublisher {
 public:
  ReproducePublisher(const ReproducePlan& plan, const std::filesystem::path& out,
                     const SweepOptions& options, bool omit, SweepQueue& queue)
      : plan_(plan), out_(out), options_(options), omit_(omit), queue_(queue) {}

  // The follow-up runs each experiment's last published results ask for, and the runs its report
  // made itself when it last made some, counted in the progress line until its own are known (an
  // estimate only).
  void expect_follow_ups() {
    const std::map<std::string, double> report_work = published_report_work(out_);
    for (std::size_t s = 0; s < plan_.specs.size(); ++s) {
      double cost = 0;
      const std::vector<RunParams> follow = expected_follow_ups(plan_.specs[s], out_);
      const std::map<std::string, double> published =
          follow.empty() ? std::map<std::string, double>{} : published_work(plan_.specs[s], out_);
      for (const RunParams& p : follow)
        cost += estimated_work(p, "", CaseWork::run, published);
      expected_[s] = cost;
      queue_.expect(cost);
      // The runs its report makes itself, as its last render that made some counted them.
      const auto report = report_work.find(plan_.specs[s].name);
      expected_report_[s] = report == report_work.end() ? 0.0 : report->second;
      queue_.expect(expected_report_[s]);
    }
  }

  // Batch b of the queue is complete: an experiment's cases (b < the number of specs, added in
  // their order) or an experiment's follow-up runs.
  void complete(std::size_t b, SweepOutcome& outcome) {
    if (const auto f = follow_of_.find(b); f != follow_of_.end()) {
      follow_done_[f->second] = std::move(outcome);
    } else {
      waiting_.emplace(b, std::move(outcome));
    }
    for (bool again = true; again;) {
      again = false;
      for (auto it = waiting_.begin(); it != waiting_.end();) {
        const std::size_t s = it->first;
        if (!ready(s) || !follow_ups_done(s, it->second)) {
          ++it;
          continue;
        }
        publish(plan_.specs[s], it->second);
        it = waiting_.erase(it);
        again = true;
      }
    }
  }

  bool all_published() const { return waiting_.empty(); }
  // The experiment whose follow-up runs are batch b of the queue.
  std::size_t followed_by(std::size_t b) const { return follow_of_.at(b); }
  int computed = 0, cases = 0;
  double particle_steps = 0, compute_seconds = 0;

 private:
  bool ready(std::size_t s) const {
    const auto& needs = plan_.waits_for[s];
    return std::includes(written_.begin(), written_.end(), needs.begin(), needs.end());
  }

  // Whether experiment s's follow-up runs are done: asked for (into the queue) the first time it
  // is ready, then waited for.
  bool follow_ups_done(std::size_t s, const SweepOutcome& outcome) {
    if (follow_done_.count(s)) return true;
    if (asked_.count(s)) return false;
    asked_.insert(s);
    std::unique_ptr<FollowUps> f = follow_ups(plan_.specs[s], outcome, out_);
    const double expected = expected_[s];
    if (!f) {
      queue_.retire(expected);
      return true;
    }
    if (!options_.quiet)
      queue_.say("[" + f->spec.name + "] " + std::to_string(f->spec.cases.size()) +
                 " follow-up run" + (f->spec.cases.size() == 1 ? "" : "s") + " join the queue\n");
    follow_of_[queue_.add(f->spec, expected)] = s;
    follow_specs_[s] = std::move(f);
    return false;
  }

  void publish(const Spec& spec, SweepOutcome& outcome) {
    std::string line;
    if (!spec.study->has_cases) {
      write_derived_reports(spec, out_);
      line = "[" + spec.name + "] from " + std::to_string(spec.inputs.size()) + " inputs -> " +
             out_.string() + "\n";
    } else {
      const std::size_t s = index_of(spec);
      count(spec, outcome);
      const double wall = outcome.wall_seconds;
      if (omit_) omit_machine_measurements(outcome);
      // The follow-up runs were computed in the queue: the report takes their outcome.
      const auto given = follow_done_.find(s);
      const FollowUpRunner runner = [&](const Spec& follow) {
        if (given == follow_done_.end() || follow.cases.size() != given->second.records.size())
          throw std::logic_error(spec.name + ": follow-up runs asked for after the queue ran");
        if (const auto f = follow_specs_.find(s); f != follow_specs_.end()) {
          count(f->second->spec, given->second);
          if (omit_) omit_machine_measurements(given->second);
        }
        return given->second;
      };
      write_reports(spec, outcome, out_, runner);
      line = summary_line(spec, outcome, wall, out_);
    }
    // What the report's own runs made is done; the work expected of them leaves the line.
    const auto expected = expected_report_.find(index_of(spec));
    queue_.reports_rendered(expected == expected_report_.end() ? 0.0 : expected->second);
    queue_.say(line);
    written_.insert(spec.name);
  }

  std::size_t index_of(const Spec& spec) const { return std::size_t(&spec - plan_.specs.data()); }

  void count(const Spec& spec, const SweepOutcome& outcome) {
    computed += outcome.computed;
    cases += int(spec.cases.size());
    const std::string search = case_search(spec);
    for (std::size_t i = 0; i < spec.cases.size(); ++i) {
      if (!counted_.insert(case_key(spec.cases[i].params, search)).second) continue;
      particle_steps += record_particle_steps(outcome.records[i]);
      compute_seconds += outcome.records[i]["timing"]["wall_seconds"].get<double>();
    }
  }

  const ReproducePlan& plan_;
  const std::filesystem::path& out_;
  const SweepOptions& options_;
  bool omit_;
  SweepQueue& queue_;
  std::map<std::size_t, SweepOutcome> waiting_;  // complete, not yet published
  std::set<std::size_t> asked_;                  // experiments whose follow-ups were asked for
  std::map<std::size_t, std::unique_ptr<FollowUps>> follow_specs_;  // by experiment
  std::map<std::size_t, std::size_t> follow_of_;     // queue batch -> the experiment it follows up
  std::map<std::size_t, SweepOutcome> follow_done_;  // by experiment
  std::map<std::size_t, double> expected_;           // the follow-up work expected, by experiment
  std::map<std::size_t, double> expected_report_;    // its report's own runs' work expected
  std::set<std::string> written_;
  std::set<std::string> counted_;
};

// 3. The reproduction's own entry in the machine's timings.
// `reports`: the runs its reports made themselves (SweepQueue::report_account), counted in its
// work and CPU time beside its cases and follow-up runs, and apart in report_runs.
void record_reproduce(const ReproducePublisher& done, const RunAccount& reports,
                      std::size_t experiments, double wall, const std::filesystem::path& out,
                      const SweepOptions& options, bool omit, const std::string& label,
                      const EstimateAccuracy& estimate) {
  const Provenance when = current_provenance(options.jobs);
  nlohmann::ordered_json judged = nullptr;
  if (!omit && estimate.samples > 0) {
    judged = {{"samples", estimate.samples}, {"worst_factor", estimate.worst}, {"at", estimate.at}};
  }
  const double report_seconds = omit ? 0.0 : reports.seconds.load();
  write_reproduce_timing(
      out, label,
      {{"experiments", experiments},
       {"cases", done.cases},
       {"computed", done.computed},
       {"particle_steps", done.particle_steps + reports.particle_steps},
       {"compute_seconds", omit ? 0.0 : done.compute_seconds + report_seconds},
       {"report_runs", report_runs_json(reports.runs, reports.particle_steps, report_seconds)},
       {"commit", when.commit},
       {"cpu", when.cpu},
       {"kernels", when.kernels},
       {"threads", options.jobs},
       {"wall_seconds", omit ? 0.0 : wall},
       {"time_to_go", judged}},
      done.computed > 0);
}

// A shard of several specs' cases (reproduce --shard): one queue, no follow-up, no report; each
// spec with cases leaves its shard manifest, as a sweep's shard does.
int reproduce_shard(const ReproducePlan& plan, const SweepOptions& options,
                    const std::filesystem::path& out, const std::string& label) {
  SweepQueue queue(options, label);
  for (const auto& spec : plan.specs)
    queue.add(spec);
  const std::vector<SweepOutcome> outcomes = queue.run([](std::size_t, SweepOutcome&) {});
  for (std::size_t s = 0; s < plan.specs.size(); ++s)
    if (outcomes[s].interrupted) return interrupted(plan.specs[s], outcomes[s], options);
  for (std::size_t s = 0; s < plan.specs.size(); ++s)
    if (plan.specs[s].study->has_cases) finish_shard(plan.specs[s], outcomes[s], options, out);
  return 0;
}

// The follow-up runs of a tier's second job array (reproduce --follow-ups): each experiment's cases
// gathered from the folders of the tier's shards (as merge finds them; a missing or disagreeing
// case is refused before anything is written), and the follow-up runs they decide
// (follow_ups_from_records).
std::vector<std::unique_ptr<FollowUps>> follow_ups_of_shards(
    const ReproducePlan& plan, const std::vector<std::filesystem::path>& folders) {
  std::vector<std::unique_ptr<FollowUps>> follow;
  for (const Spec& spec : plan.specs) {
    if (!spec.study->has_cases || !spec.study->follow_up) continue;
    try {
      if (auto f = follow_ups_from_records(spec, merge_shards(spec, folders)))
        follow.push_back(std::move(f));
    } catch (const MergeError& e) {
      throw UsageError(spec.name +
                       ": its cases cannot be gathered from the folders given: " + e.what());
    }
  }
  return follow;
}

// A follow-up run of shard I that is also a case (the same key) is not run again: its record is
// copied from the cases' folders into DIR/cache/, as make reproduce finds it in its cache.
void copy_follow_ups_run_as_cases(const std::vector<std::unique_ptr<FollowUps>>& follow,
                                  const std::vector<std::filesystem::path>& folders,
                                  const SweepOptions& options) {
  const ResultCache into(options.cache);
  std::vector<ResultCache> cases;
  for (const auto& d : folders)
    cases.emplace_back(d / "cache");
  for (const auto& f : follow) {
    const std::string search = case_search(f->spec);
    for (const CaseSpec& c : f->spec.cases) {
      if (shard_of(case_key(c.params, search), options.shard->count) != options.shard->index)
        continue;
      for (const ResultCache& from : cases) {
        if (auto record = from.load(c.params, search)) {
          if (!into.load(c.params, search)) into.store(c.params, *record, search);
          break;
        }
      }
    }
  }
}

// A shard of those follow-up runs (reproduce --follow-ups --shard I/N): shard I of them, in one
// queue, into DIR/cache/, each experiment's with its shard manifest, as a shard of cases.
int follow_up_shard(const std::vector<std::unique_ptr<FollowUps>>& follow,
                    const std::vector<std::filesystem::path>& folders, const SweepOptions& options,
                    const std::filesystem::path& out, const std::string& label) {
  if (follow.empty()) {
    std::cerr << "[reproduce] none of these experiments has follow-up runs its cases' records "
                 "decide; nothing to run\n";
    return 0;
  }
  copy_follow_ups_run_as_cases(follow, folders, options);
  SweepQueue queue(options, label);
  for (const auto& f : follow)
    queue.add(f->spec);
  const std::vector<SweepOutcome> outcomes = queue.run([](std::size_t, SweepOutcome&) {});
  for (std::size_t s = 0; s < follow.size(); ++s)
    if (outcomes[s].interrupted) return interrupted(follow[s]->spec, outcomes[s], options);
  for (std::size_t s = 0; s < follow.size(); ++s)
    finish_shard(follow[s]->spec, outcomes[s], options, out);
  return 0;
}

// --label: letters, digits, spaces, '-' and '_' (it names a key of timings.json).
std::string run_label(const Args& args) {
  const std::string label = std::string(args.value("label").value_or("reproduce"));
  if (label.empty() || label.size() > 64 ||
      !std::all_of(label.begin(), label.end(), [](unsigned char ch) {
        return std::isalnum(ch) || ch == ' ' || ch == '-' || ch == '_';
      }))
    throw UsageError("--label: letters, digits, spaces, '-' and '_', at most 64, got '" + label +
                     "'");
  return label;
}

}  // namespace

int cmd_reproduce(const std::vector<std::string_view>& argv) {
  const Args args(argv, {{"jobs"},
                         {"out"},
                         {"force", false},
                         {"timing"},
                         {"label"},
                         {"shard"},
                         {"follow-ups", false},
                         {"help", false}});
  if (args.flag("help")) {
    std::cout << kReproduceHelp;
    return 0;
  }
  if (args.positional().empty()) throw UsageError("reproduce takes one or more specs");
  const std::string label = run_label(args);
  SweepOptions options = sweep_options(args);
  const bool omit = omit_timing(args);
  const auto out = output_folder(args);
  const bool follow_ups = args.flag("follow-ups");
  if (follow_ups && !options.shard) throw UsageError("--follow-ups: only with --shard I/N");
  const SpecsAndFolders given =
      follow_ups ? specs_and_folders(args.positional()) : SpecsAndFolders{args.positional(), {}};
  const ReproducePlan plan = plan_reproduce(given.specs, out, options.shard.has_value());
  const std::vector<std::unique_ptr<FollowUps>> follow =
      follow_ups ? follow_ups_of_shards(plan, given.folders)
                 : std::vector<std::unique_ptr<FollowUps>>{};
  make_output_folder(out);
  finish_publications_in(out);  // a report set a killed run left half published
  options.cache = out / "cache";
  options.published = out;
  remove_stale_temporaries(options.cache);
  options.progress_line = ::isatty(STDERR_FILENO) != 0;
  options.cancel = &g_stop;
  install_stop_handlers();
  if (follow_ups) return follow_up_shard(follow, given.folders, options, out, label);
  if (options.shard) return reproduce_shard(plan, options, out, label);

  // One queue; each experiment's follow-up runs join it once its cases are complete and what it
  // reads is written, and it is published once they are done.
  SweepQueue queue(options, label);
  for (const auto& spec : plan.specs)
    queue.add(spec);
  ReproducePublisher publisher(plan, out, options, omit, queue);
  publisher.expect_follow_ups();
  const auto start = std::chrono::steady_clock::now();
  // The reports render on this thread: the runs they make count in the queue's account.
  std::vector<SweepOutcome> rest;
  {
    const RunAccountScope counting(queue.report_account());
    rest = queue.run([&](std::size_t b, SweepOutcome& outcome) { publisher.complete(b, outcome); });
  }
  for (std::size_t b = 0; b < rest.size(); ++b) {
    if (!rest[b].interrupted) continue;
    const std::size_t s = b < plan.specs.size() ? b : publisher.followed_by(b);
    return interrupted(plan.specs[s], rest[s], options);
  }
  if (!publisher.all_published()) {
    throw std::logic_error("reproduce: an experiment waits for an input that never came");
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  record_reproduce(publisher, queue.report_account(), plan.specs.size(), wall, out, options, omit,
                   label, estimate_accuracy(queue.estimates(), wall));
  std::cerr << "[reproduce] " << plan.specs.size() << " experiments in "
            << shortest(std::round(wall * 10) / 10) << " s -> " << out.string() << "\n";
  return 0;
}

int cmd_sweep(const std::vector<std::string_view>& argv) {
  const Args args(argv,
                  {{"jobs"}, {"out"}, {"force", false}, {"shard"}, {"timing"}, {"help", false}});
  if (args.flag("help")) {
    std::cout << kSweepHelp;
    return 0;
  }
  if (args.positional().size() > 1) throw UsageError("sweep takes one spec");
  SweepOptions options = sweep_options(args);
  const bool omit = omit_timing(args);
  // 1. Every input is read and checked before any work: a refusal leaves every file as it was.
  // (A study without cases reads its inputs before it writes anything: derive checks them.)
  const Spec spec = load_specs(args.positional()).front();
  const auto out = output_folder(args);
  if (!spec.study->has_cases) return derive(spec, options, out);
  check_inputs(spec, out);
  make_output_folder(out);
  finish_publications_in(out);  // a report set a killed run left half published
  options.cache = out / "cache";
  options.published = out;
  remove_stale_temporaries(options.cache);  // of a sweep killed while storing a record
  options.progress_line = ::isatty(STDERR_FILENO) != 0;
  options.cancel = &g_stop;
  install_stop_handlers();

  // 2. The cases, from the cache or computed.
  SweepOutcome outcome = run_sweep(spec, options);
  if (outcome.interrupted) return interrupted(spec, outcome, options);
  if (options.shard) return finish_shard(spec, outcome, options, out);
  const double wall_seconds = outcome.wall_seconds;  // for the summary line, also when omitted
  if (omit) omit_machine_measurements(outcome);
  // 3. The reports, published together.
  write_reports(spec, outcome, out, follow_up_runner(options));
  std::cerr << summary_line(spec, outcome, wall_seconds, out);
  return 0;
}

}  // namespace mpmstab::cli
