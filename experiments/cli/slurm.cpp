// `mpmstab merge` and `mpmstab slurm`: a sweep split into shards that run elsewhere (on a
// cluster under its scheduler, or over ssh with GNU parallel), gathered into the same reports a
// single machine writes. See experiments/README.md.
#include <unistd.h>

#include <cmath>
#include <iostream>
#include <sstream>

#include "atomic_file.hpp"
#include "cache.hpp"
#include "commands.hpp"
#include "csv.hpp"
#include "merge.hpp"
#include "report.hpp"

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

constexpr const char* kSlurmHelp =
    R"(Usage: mpmstab slurm <spec.json> --shards N [--partition P] [--time T] [--account A]
                    [--cpus-per-task C] [--work DIR] [--out DIR] [--timing keep|omit]
                    [--mpmstab PATH]

Writes a Slurm job array that runs the sweep of <spec.json> in N shards (one array task per
shard) and a merge job that depends on it, and a script that submits both:
  WORK/<name>.sweep.sbatch  array 0..N-1: mpmstab sweep <spec> --shard $SLURM_ARRAY_TASK_ID/N
                            --out WORK/shard-$SLURM_ARRAY_TASK_ID
  WORK/<name>.merge.sbatch  mpmstab merge <spec> WORK/shard-0 ... --out OUT, run after every
                            array task succeeded (--dependency=afterok)
  WORK/<name>.submit.sh     submits both; prints "sweep <job id>" and "merge <job id>"
Jobs run in the current folder (--chdir), which must be on a file system the nodes share;
job logs go to WORK/logs/. Nothing is submitted by this command.

Options:
  --shards N         number of shards (array tasks), 1..10000; required
  --partition P      Slurm partition (default: the cluster's default)
  --time T           time limit of each task, as Slurm takes it (e.g. 01:00:00, 2-00:00:00)
  --account A        Slurm account to charge
  --cpus-per-task C  cores per task, used as the shard's --jobs (default 1)
  --work DIR         folder of the scripts, shard outputs and logs (default slurm-<name>)
  --out DIR          folder of the merged reports (default results)
  --timing keep|omit passed to the merge (as for 'mpmstab sweep')
  --mpmstab PATH     the mpmstab binary the jobs run (default: this one)
  --help             show this text
)";

// A word for /bin/sh: single-quoted, with embedded single quotes escaped.
std::string sh_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'') {
      q += "'\\''";
    } else {
      q += c;
    }
  }
  return q + "'";
}

// A Slurm option value that needs no quoting: letters, digits and a few separators.
std::string slurm_word(std::string_view v, std::string_view option, std::string_view allowed) {
  if (v.empty() || v.find_first_not_of(allowed) != std::string_view::npos) {
    throw UsageError("--" + std::string(option) + ": '" + std::string(v) +
                     "' is not a valid value");
  }
  return std::string(v);
}

constexpr std::string_view kNameChars =
    "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_.-";
constexpr std::string_view kTimeChars = "0123456789:-";

fs::path this_binary() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw UsageError("--mpmstab: cannot find this program's path; give it");
  return self;
}

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
  SweepOutcome outcome;
  try {
    outcome = merge_shards(spec, dirs);
  } catch (const MergeError& e) {
    std::cerr << "mpmstab merge: error: " << spec.name << ": " << e.what()
              << "\nNothing was written.\n";
    return 2;
  }
  const fs::path out = output_folder(args);
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
            << " folders (" << outcome.unstable << " unstable) -> "
            << (out / (spec.name + ".md")).string() << "\n";
  return 0;
}

int cmd_slurm(const std::vector<std::string_view>& argv) {
  const Args args(argv, {{"shards"},
                         {"partition"},
                         {"time"},
                         {"account"},
                         {"cpus-per-task"},
                         {"work"},
                         {"out"},
                         {"timing"},
                         {"mpmstab"},
                         {"help", false}});
  if (args.flag("help")) {
    std::cout << kSlurmHelp;
    return 0;
  }
  if (args.positional().size() != 1) throw UsageError("slurm takes one spec");
  const auto shards_text = args.value("shards");
  if (!shards_text) throw UsageError("missing required option --shards");
  const std::int64_t shards = parse_int(*shards_text, "shards");
  if (shards < 1 || shards > 10000) {
    throw UsageError("--shards: must be in [1, 10000], got " + std::string(*shards_text));
  }
  std::int64_t cpus = 1;
  if (auto v = args.value("cpus-per-task")) {
    cpus = parse_int(*v, "cpus-per-task");
    if (cpus < 1 || cpus > 1024) {
      throw UsageError("--cpus-per-task: must be in [1, 1024], got " + std::string(*v));
    }
  }
  const bool omit = omit_timing(args);
  const std::string spec_arg(args.positional().front());
  const Spec spec = load_specs(args.positional()).front();
  const std::string work = std::string(args.value("work").value_or("slurm-" + spec.name));
  const std::string out = std::string(args.value("out").value_or("results"));
  const fs::path binary =
      args.value("mpmstab") ? fs::absolute(std::string(*args.value("mpmstab"))) : this_binary();
  std::error_code ec;
  if (!fs::is_regular_file(binary, ec) || ::access(binary.c_str(), X_OK) != 0) {
    throw UsageError("--mpmstab: " + binary.string() + " is not an executable file");
  }

  std::ostringstream common;  // directives of both jobs
  common << "#SBATCH --chdir=" << fs::current_path().string() << "\n";
  if (auto v = args.value("partition")) {
    common << "#SBATCH --partition=" << slurm_word(*v, "partition", kNameChars) << "\n";
  }
  if (auto v = args.value("time")) {
    common << "#SBATCH --time=" << slurm_word(*v, "time", kTimeChars) << "\n";
  }
  if (auto v = args.value("account")) {
    common << "#SBATCH --account=" << slurm_word(*v, "account", kNameChars) << "\n";
  }
  const std::string logs = (fs::path(work) / "logs").string();
  const std::string header = "#!/bin/bash\n# Written by 'mpmstab slurm' for " + spec_arg + " (" +
                             std::to_string(spec.cases.size()) + " cases in " +
                             std::to_string(shards) + " shards).\n";

  std::ostringstream sweep;
  sweep << header << "#SBATCH --job-name=mpmstab-" << spec.name << "\n#SBATCH --array=0-"
        << shards - 1 << "\n#SBATCH --cpus-per-task=" << cpus << "\n#SBATCH --output=" << logs
        << "/" << spec.name << "-sweep-%A_%a.out\n"
        << common.str() << "set -euo pipefail\nexec " << sh_quote(binary.string()) << " sweep "
        << sh_quote(spec_arg) << " --shard \"${SLURM_ARRAY_TASK_ID}/" << shards
        << "\" --jobs \"${SLURM_CPUS_PER_TASK:-" << cpus << "}\" --out "
        << sh_quote(work + "/shard-") << "\"${SLURM_ARRAY_TASK_ID}\"\n";

  std::ostringstream merge;
  merge << header << "#SBATCH --job-name=mpmstab-" << spec.name
        << "-merge\n#SBATCH --output=" << logs << "/" << spec.name << "-merge-%j.out\n"
        << common.str() << "set -euo pipefail\nexec " << sh_quote(binary.string()) << " merge "
        << sh_quote(spec_arg);
  for (std::int64_t i = 0; i < shards; ++i)
    merge << " " << sh_quote(work + "/shard-" + std::to_string(i));
  merge << " --out " << sh_quote(out) << (omit ? " --timing omit" : "") << "\n";

  const std::string sweep_file = work + "/" + spec.name + ".sweep.sbatch";
  const std::string merge_file = work + "/" + spec.name + ".merge.sbatch";
  std::ostringstream submit;
  submit << "#!/bin/sh\n# Submits the sweep array of " << spec_arg
         << " and its merge, which runs once every array task succeeded.\nset -eu\ncd "
         << sh_quote(fs::current_path().string()) << "\nsweep=$(sbatch --parsable "
         << sh_quote(sweep_file)
         << ")\nsweep=${sweep%%;*}\nmerge=$(sbatch --parsable --dependency=afterok:\"$sweep\" "
         << sh_quote(merge_file) << ")\necho \"sweep $sweep\"\necho \"merge ${merge%%;*}\"\n";

  fs::create_directories(logs, ec);
  if (ec) throw UsageError("--work: cannot create " + logs + ": " + ec.message());
  write_file_atomically(sweep_file, sweep.str());
  write_file_atomically(merge_file, merge.str());
  const std::string submit_file = work + "/" + spec.name + ".submit.sh";
  write_file_atomically(submit_file, submit.str());
  fs::permissions(submit_file, fs::perms::owner_exec | fs::perms::group_exec,
                  fs::perm_options::add);
  std::cout << "Wrote " << sweep_file << ", " << merge_file << " and " << submit_file
            << ".\nSubmit with: sh " << submit_file << "\nThe merged reports will be in " << out
            << "/" << spec.name << ".md\n";
  return 0;
}

}  // namespace mpmstab::cli
