// `mpmstab merge`: the reports of a sweep that ran in shards, gathered from the shards' folders
// (see README.md, "Running on a cluster", and `mpmstab slurm`).
#include <iostream>

#include "cache.hpp"
#include "commands.hpp"
#include "merge.hpp"
#include "report.hpp"
#include "sweep.hpp"

namespace mpmstab::cli {

namespace {

namespace fs = std::filesystem;

constexpr const char* kMergeHelp =
    R"(Usage: mpmstab merge <spec.json> <dir>... [--out DIR] [--timing keep|omit]
       mpmstab merge <spec.json>... <dir>... --records-only [--with-follow-ups] [--out DIR]

Gathers the per-case results of a sweep that ran in shards ('mpmstab sweep <spec> --shard
I/N --out <dir>', one <dir> per shard, or any folders holding <dir>/cache/) and writes the
reports a single-machine sweep writes: the same files, the same bytes for the same results.
Every case of the spec must be found in some <dir>; a case found in several must have the
same results there (machine measurements aside), and the first <dir> listed that has it is
used. The records are also copied into DIR/cache/, so that later sweeps reuse them.

With --records-only, of every spec given (the arguments before the first folder; the cases
of several specs sharded together by 'mpmstab reproduce --shard I/N'), the records are gathered
and checked the same way and copied into DIR/cache/, and no report is written: a later
'mpmstab reproduce' (make reproduce or make studies with RESULTS=DIR) finds every case there and
computes only what the studies ask for beyond them. A study without cases of its own is skipped.
With --with-follow-ups, the follow-up runs that the gathered records alone decide (those of
every study that reads no other experiment's results, which 'mpmstab reproduce --follow-ups
--shard I/N' computes) must be found too, each checked the same way, and are copied as well.

Options:
  --out DIR          where the reports go (default results)
  --timing keep|omit as for 'mpmstab sweep'
  --records-only     only the records, into DIR/cache/, of one or more specs
  --with-follow-ups  with --records-only: also the follow-up runs the records decide
  --help             show this text

Exit status: 0 when the reports were written; 2 for bad input or when cases are missing or
disagree (each is named; nothing is written); 1 for an internal error.
)";

// Copies the merged records of a spec's cases into `cache`, each unless it is there already.
void store_records(const Spec& spec, const SweepOutcome& outcome, const ResultCache& cache) {
  const std::string search = case_search(spec);
  for (std::size_t i = 0; i < spec.cases.size(); ++i) {
    const auto& p = spec.cases[i].params;
    const auto present = cache.load(p, search);
    if (!present || *present != outcome.records[i]) cache.store(p, outcome.records[i], search);
  }
}

// merge --records-only: every spec's records into OUT/cache and, with --with-follow-ups, those
// of the follow-up runs the records alone decide (follow_ups_from_records), all checked before
// any is copied.
int merge_records(const std::vector<Spec>& specs, const std::vector<fs::path>& dirs,
                  const fs::path& out, bool with_follow_ups) {
  std::vector<std::unique_ptr<FollowUps>> follow;  // own the specs merged below
  std::vector<std::pair<const Spec*, SweepOutcome>> merged;
  std::size_t cases = 0, experiments = 0;
  int rejected = 0;
  for (const Spec& spec : specs) {
    if (!spec.study->has_cases) continue;
    const Spec* what = &spec;
    try {
      merged.emplace_back(what, merge_shards(spec, dirs));
      rejected += merged.back().second.rejected;
      cases += spec.cases.size();
      ++experiments;
      if (!with_follow_ups) continue;
      follow.push_back(follow_ups_from_records(spec, merged.back().second));
      if (!follow.back()) continue;
      what = &follow.back()->spec;
      merged.emplace_back(what, merge_shards(*what, dirs));
      rejected += merged.back().second.rejected;
    } catch (const MergeError& e) {
      std::cerr << "mpmstab merge: error: " << spec.name
                << (what == &spec ? ": " : ": its follow-up runs: ") << e.what()
                << "\nNothing was written.\n";
      return 2;
    }
  }
  make_output_folder(out);
  const ResultCache cache(out / "cache");
  for (const auto& [spec, outcome] : merged)
    store_records(*spec, outcome, cache);
  std::size_t follow_runs = 0;
  for (const auto& f : follow)
    follow_runs += f ? f->spec.cases.size() : 0;
  std::cerr << "[merge] the records of " << cases << " cases of " << experiments << " experiments"
            << (with_follow_ups ? " and of their " + std::to_string(follow_runs) + " follow-up runs"
                                : std::string())
            << " from " << dirs.size() << " folders"
            << (rejected ? " (" + std::to_string(rejected) +
                               " records in the folders failed their checksum or shape and were "
                               "ignored)"
                         : std::string())
            << " -> " << (out / "cache").string() << "\n";
  return 0;
}

}  // namespace

int cmd_merge(const std::vector<std::string_view>& argv) {
  const Args args(
      argv,
      {{"out"}, {"timing"}, {"records-only", false}, {"with-follow-ups", false}, {"help", false}});
  if (args.flag("help")) {
    std::cout << kMergeHelp;
    return 0;
  }
  const auto& pos = args.positional();
  if (pos.size() < 2) throw UsageError("needs a spec and at least one folder of shard results");
  const bool omit = omit_timing(args);
  const SpecsAndFolders given = specs_and_folders(pos);
  const std::vector<Spec> specs = load_specs(given.specs);
  const std::vector<fs::path>& dirs = given.folders;
  const fs::path out = output_folder(args);
  if (args.flag("with-follow-ups") && !args.flag("records-only"))
    throw UsageError("--with-follow-ups: only with --records-only");
  if (args.flag("records-only")) {
    if (args.value("timing"))
      throw UsageError("--timing: no report is written with --records-only");
    return merge_records(specs, dirs, out, args.flag("with-follow-ups"));
  }
  if (specs.size() != 1) throw UsageError("takes one spec (several with --records-only)");
  const Spec& spec = specs.front();
  check_inputs(spec, out);
  make_output_folder(out);
  SweepOutcome outcome;
  try {
    outcome = merge_shards(spec, dirs);
  } catch (const MergeError& e) {
    std::cerr << "mpmstab merge: error: " << spec.name << ": " << e.what()
              << "\nNothing was written.\n";
    return 2;
  }
  store_records(spec, outcome, ResultCache(out / "cache"));
  if (omit) omit_machine_measurements(outcome);
  write_reports(spec, outcome, out);
  std::cerr << "[" << spec.name << "] merged " << spec.cases.size() << " cases from " << dirs.size()
            << " folders (" << outcome.unstable << " unstable"
            << (outcome.rejected ? "; " + std::to_string(outcome.rejected) +
                                       " records in the folders failed their checksum or shape "
                                       "and were ignored"
                                 : std::string())
            << ") -> " << (out / (spec.name + ".md")).string() << "\n";
  return 0;
}

}  // namespace mpmstab::cli
