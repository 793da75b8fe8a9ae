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
       mpmstab merge <spec.json>... <dir>... --records-only [--out DIR]

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

Options:
  --out DIR          where the reports go (default results)
  --timing keep|omit as for 'mpmstab sweep'
  --records-only     only the records, into DIR/cache/, of one or more specs
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

// The specs (the arguments before the first folder) and the folders (the rest).
std::pair<std::vector<Spec>, std::vector<fs::path>> specs_and_folders(
    const std::vector<std::string_view>& pos) {
  std::error_code ec;
  std::size_t first_dir = 0;
  while (first_dir < pos.size() && !fs::is_directory(fs::path(pos[first_dir]), ec))
    ++first_dir;
  if (first_dir == 0) throw UsageError(std::string(pos.front()) + ": a folder where a spec goes");
  const std::vector<std::string_view> spec_args(pos.begin(), pos.begin() + long(first_dir));
  std::vector<fs::path> dirs;
  for (std::size_t i = first_dir; i < pos.size(); ++i) {
    if (!fs::is_directory(fs::path(pos[i]), ec))
      throw UsageError(std::string(pos[i]) + ": not a folder");
    dirs.emplace_back(pos[i]);
  }
  if (dirs.empty()) throw UsageError(std::string(pos.back()) + ": not a folder");
  return {load_specs(spec_args), std::move(dirs)};
}

// merge --records-only: every spec's records into OUT/cache, all checked before any is copied.
int merge_records(const std::vector<Spec>& specs, const std::vector<fs::path>& dirs,
                  const fs::path& out) {
  std::vector<std::pair<const Spec*, SweepOutcome>> merged;
  int rejected = 0;
  for (const Spec& spec : specs) {
    if (!spec.study->has_cases) continue;
    try {
      merged.emplace_back(&spec, merge_shards(spec, dirs));
    } catch (const MergeError& e) {
      std::cerr << "mpmstab merge: error: " << spec.name << ": " << e.what()
                << "\nNothing was written.\n";
      return 2;
    }
    rejected += merged.back().second.rejected;
  }
  make_output_folder(out);
  const ResultCache cache(out / "cache");
  std::size_t records = 0;
  for (const auto& [spec, outcome] : merged) {
    store_records(*spec, outcome, cache);
    records += outcome.records.size();
  }
  std::cerr << "[merge] the records of " << records << " cases of " << merged.size()
            << " experiments from " << dirs.size() << " folders"
            << (rejected ? " (" + std::to_string(rejected) +
                               " records in the folders failed their checksum or shape and were "
                               "ignored)"
                         : std::string())
            << " -> " << (out / "cache").string() << "\n";
  return 0;
}

}  // namespace

int cmd_merge(const std::vector<std::string_view>& argv) {
  const Args args(argv, {{"out"}, {"timing"}, {"records-only", false}, {"help", false}});
  if (args.flag("help")) {
    std::cout << kMergeHelp;
    return 0;
  }
  const auto& pos = args.positional();
  if (pos.size() < 2) throw UsageError("needs a spec and at least one folder of shard results");
  const bool omit = omit_timing(args);
  const auto [specs, dirs] = specs_and_folders(pos);
  const fs::path out = output_folder(args);
  if (args.flag("records-only")) {
    if (args.value("timing"))
      throw UsageError("--timing: no report is written with --records-only");
    return merge_records(specs, dirs, out);
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
