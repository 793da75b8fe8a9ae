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

Gathers the per-case results of a sweep that ran in shards ('mpmstab sweep <spec> --shard
I/N --out <dir>', one <dir> per shard, or any folders holding <dir>/cache/) and writes the
reports a single-machine sweep writes: the same files, the same bytes for the same results.
Every case of the spec must be found in some <dir>; a case found in several must have the
same results there (machine measurements aside), and the first <dir> listed that has it is
used. The records are also copied into DIR/cache/, so that later sweeps reuse them.

Options:
  --out DIR          where the reports go (default results)
  --timing keep|omit as for 'mpmstab sweep'
  --help             show this text

Exit status: 0 when the reports were written; 2 for bad input or when cases are missing or
disagree (each is named; nothing is written); 1 for an internal error.
)";

}  // namespace

int cmd_merge(const std::vector<std::string_view>& argv) {
  const Args args(argv, {{"out"}, {"timing"}, {"help", false}});
  if (args.flag("help")) {
    std::cout << kMergeHelp;
    return 0;
  }
  const auto& pos = args.positional();
  if (pos.size() < 2) throw UsageError("needs a spec and at least one folder of shard results");
  const bool omit = omit_timing(args);
  const Spec spec = load_specs({pos.front()}).front();
  std::vector<fs::path> dirs;
  for (std::size_t i = 1; i < pos.size(); ++i) {
    const fs::path d(pos[i]);
    std::error_code ec;
    if (!fs::is_directory(d, ec)) throw UsageError(d.string() + ": not a folder");
    dirs.push_back(d);
  }
  const fs::path out = output_folder(args);
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
  const std::string search = case_search(spec);
  const ResultCache cache(out / "cache");
  for (std::size_t i = 0; i < spec.cases.size(); ++i) {
    const auto& p = spec.cases[i].params;
    const auto present = cache.load(p, search);
    if (!present || *present != outcome.records[i]) cache.store(p, outcome.records[i], search);
  }
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
