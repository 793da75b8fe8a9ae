// `mpmstab slurm`: a Slurm job array that runs a sweep in shards, and the job that merges them
// (`mpmstab merge`) once every shard succeeded. See README.md, "Running on a cluster".
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>

#include "commands.hpp"
#include "files.hpp"

namespace mpmstab::cli {

namespace {

namespace fs = std::filesystem;

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

// Text that goes into a job script: a control character (a newline would start a new line of
// the script) is refused.
const std::string& no_control(const std::string& s) {
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c == 0x7f) {
      throw UsageError("a control character in '" + s.substr(0, s.find(ch)) +
                       "...' cannot go into a job script");
    }
  }
  return s;
}

// A word for /bin/sh: single-quoted, with embedded single quotes escaped; no control character.
std::string sh_quote(const std::string& s) {
  no_control(s);
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

// What the scripts are written from: the checked options and the spec.
struct SlurmJob {
  std::int64_t shards = 1;
  std::int64_t cpus = 1;  // per task, the shard's --jobs
  bool omit = false;      // --timing omit, passed to the merge
  std::string spec_arg;   // the spec as given, which the jobs read
  Spec spec;
  std::string work;  // scripts, shard outputs and logs
  std::string out;   // merged reports
  fs::path binary;   // the mpmstab the jobs run
  std::string logs;  // WORK/logs
};

// Checks the options and loads the spec; UsageError for the first bad one.
SlurmJob job_from(const Args& args) {
  if (args.positional().size() != 1) throw UsageError("slurm takes one spec");
  SlurmJob job;
  const auto shards_text = args.value("shards");
  if (!shards_text) throw UsageError("missing required option --shards");
  job.shards = parse_int(*shards_text, "shards");
  if (job.shards < 1 || job.shards > 10000) {
    throw UsageError("--shards: must be in [1, 10000], got " + std::string(*shards_text));
  }
  if (auto v = args.value("cpus-per-task")) {
    job.cpus = parse_int(*v, "cpus-per-task");
    if (job.cpus < 1 || job.cpus > 1024) {
      throw UsageError("--cpus-per-task: must be in [1, 1024], got " + std::string(*v));
    }
  }
  job.omit = omit_timing(args);
  job.spec_arg = std::string(args.positional().front());
  job.spec = load_specs(args.positional()).front();
  job.work = std::string(args.value("work").value_or("slurm-" + job.spec.name));
  job.out = std::string(args.value("out").value_or("results"));
  job.binary =
      args.value("mpmstab") ? fs::absolute(std::string(*args.value("mpmstab"))) : this_binary();
  std::error_code ec;
  if (!fs::is_regular_file(job.binary, ec) || ::access(job.binary.c_str(), X_OK) != 0) {
    throw UsageError("--mpmstab: " + job.binary.string() + " is not an executable file");
  }
  job.logs = (fs::path(job.work) / "logs").string();
  return job;
}

// The #SBATCH directives of both jobs.
std::string common_directives(const Args& args) {
  std::ostringstream common;
  common << "#SBATCH --chdir=" << no_control(fs::current_path().string()) << "\n";
  if (auto v = args.value("partition")) {
    common << "#SBATCH --partition=" << slurm_word(*v, "partition", kNameChars) << "\n";
  }
  if (auto v = args.value("time")) {
    common << "#SBATCH --time=" << slurm_word(*v, "time", kTimeChars) << "\n";
  }
  if (auto v = args.value("account")) {
    common << "#SBATCH --account=" << slurm_word(*v, "account", kNameChars) << "\n";
  }
  return common.str();
}

std::string header(const SlurmJob& job) {
  return "#!/bin/bash\n# Written by 'mpmstab slurm' for " + job.spec_arg + " (" +
         std::to_string(job.spec.cases.size()) + " cases in " + std::to_string(job.shards) +
         " shards).\n";
}

// The job array: task I runs shard I/N into WORK/shard-I.
std::string sweep_script(const SlurmJob& job, const std::string& common) {
  std::ostringstream sweep;
  sweep << header(job) << "#SBATCH --job-name=mpmstab-" << job.spec.name << "\n#SBATCH --array=0-"
        << job.shards - 1 << "\n#SBATCH --cpus-per-task=" << job.cpus
        << "\n#SBATCH --output=" << job.logs << "/" << job.spec.name << "-sweep-%A_%a.out\n"
        << common << "set -euo pipefail\nexec " << sh_quote(job.binary.string()) << " sweep "
        << sh_quote(job.spec_arg) << " --shard \"${SLURM_ARRAY_TASK_ID}/" << job.shards
        << "\" --jobs \"${SLURM_CPUS_PER_TASK:-" << job.cpus << "}\" --out "
        << sh_quote(job.work + "/shard-") << "\"${SLURM_ARRAY_TASK_ID}\"\n";
  return sweep.str();
}

// The merge of every shard's folder into OUT.
std::string merge_script(const SlurmJob& job, const std::string& common) {
  std::ostringstream merge;
  merge << header(job) << "#SBATCH --job-name=mpmstab-" << job.spec.name
        << "-merge\n#SBATCH --output=" << job.logs << "/" << job.spec.name << "-merge-%j.out\n"
        << common << "set -euo pipefail\nexec " << sh_quote(job.binary.string()) << " merge "
        << sh_quote(job.spec_arg);
  for (std::int64_t i = 0; i < job.shards; ++i)
    merge << " " << sh_quote(job.work + "/shard-" + std::to_string(i));
  merge << " --out " << sh_quote(job.out) << (job.omit ? " --timing omit" : "") << "\n";
  return merge.str();
}

// Submits the array, then the merge with --dependency=afterok on it.
std::string submit_script(const SlurmJob& job, const std::string& sweep_file,
                          const std::string& merge_file) {
  std::ostringstream submit;
  submit << "#!/bin/sh\n# Submits the sweep array of " << job.spec_arg
         << " and its merge, which runs once every array task succeeded.\nset -eu\ncd "
         << sh_quote(fs::current_path().string()) << "\nsweep=$(sbatch --parsable "
         << sh_quote(sweep_file)
         << ")\nsweep=${sweep%%;*}\nmerge=$(sbatch --parsable --dependency=afterok:\"$sweep\" "
         << sh_quote(merge_file) << ")\necho \"sweep $sweep\"\necho \"merge ${merge%%;*}\"\n";
  return submit.str();
}

}  // namespace

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
  const SlurmJob job = job_from(args);
  const std::string common = common_directives(args);
  const std::string sweep_file = job.work + "/" + job.spec.name + ".sweep.sbatch";
  const std::string merge_file = job.work + "/" + job.spec.name + ".merge.sbatch";
  const std::string submit_file = job.work + "/" + job.spec.name + ".submit.sh";
  std::error_code ec;
  fs::create_directories(job.logs, ec);
  if (ec) throw UsageError("--work: cannot create " + job.logs + ": " + ec.message());
  write_file_atomically(sweep_file, sweep_script(job, common));
  write_file_atomically(merge_file, merge_script(job, common));
  write_file_atomically(submit_file, submit_script(job, sweep_file, merge_file));
  fs::permissions(submit_file, fs::perms::owner_exec | fs::perms::group_exec,
                  fs::perm_options::add);
  std::cout << "Wrote " << sweep_file << ", " << merge_file << " and " << submit_file
            << ".\nSubmit with: sh " << submit_file << "\nThe merged reports will be in " << job.out
            << "/" << job.spec.name << ".md\n";
  return 0;
}

}  // namespace mpmstab::cli
