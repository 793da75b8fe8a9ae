// `mpmstab slurm`: a Slurm job array that runs a sweep in shards, and the job that merges them
// (`mpmstab merge`) once every shard succeeded. See README.md, "Running on a cluster".
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "files.hpp"

namespace mpmstab::cli {

namespace {

namespace fs = std::filesystem;

constexpr const char* kSlurmHelp =
    R"(Usage: mpmstab slurm <spec.json> --shards N [options]
       mpmstab slurm --tier paper|studies --shards N [--render-cpus R] [options]
Options: [--partition P] [--time T] [--account A] [--cpus-per-task C] [--throttle M]
         [--work DIR] [--out DIR] [--timing keep|omit] [--mpmstab PATH]

Writes a Slurm job array that runs the sweep of <spec.json> in N shards (one array task per
shard) and a merge job that depends on it, and a script that submits both:
  WORK/<name>.sweep.sbatch  array 0..N-1: mpmstab sweep <spec> --shard $SLURM_ARRAY_TASK_ID/N
                            --out WORK/shard-$SLURM_ARRAY_TASK_ID
  WORK/<name>.merge.sbatch  mpmstab merge <spec> WORK/shard-0 ... --out OUT, run after every
                            array task succeeded (--dependency=afterok)
  WORK/<name>.submit.sh     submits both; prints "sweep <job id>" and "merge <job id>"

With --tier T, the whole tier (make reproduce: paper, make studies: studies; its specs as
'mpmstab list --tier T' gives them) in one job array over all its cases, a second array over
the follow-up runs their records decide, and one job that renders the tier:
  WORK/T.sweep.sbatch   array 0..N-1: mpmstab reproduce <the tier's specs> --shard I/N
                        --out WORK/shard-I (each case in the shard of its key, as sweep's)
  WORK/T.follow.sbatch  array 0..N-1, once every task of the first succeeded: mpmstab reproduce
                        <specs> WORK/shard-* --follow-ups --shard I/N --out WORK/follow-I: the
                        follow-up runs of every study that reads no other experiment's results,
                        chosen from the gathered records as make reproduce chooses them
  WORK/T.render.sbatch  once every task of the second succeeded: mpmstab merge <specs>
                        WORK/shard-* WORK/follow-* --records-only --with-follow-ups --out OUT
                        (every record into OUT/cache), then make tier TIER=T RESULTS=OUT: what
                        make reproduce or make studies runs, which finds those runs in the cache
                        and computes only the rest (the follow-up runs of the studies that read
                        other experiments, the searches the advice sample makes one after
                        another), then writes the reports, figures and index
  WORK/T.submit.sh      submits the three; prints "sweep <id>", "follow <id>" and "render <id>"
The render job runs make in the current folder, which must be the checkout (its Makefile and
experiments/), with gnuplot; OUT results writes into the checkout as make does.

Jobs run in the current folder (--chdir), which must be on a file system the nodes share;
job logs go to WORK/logs/. Nothing is submitted by this command.

Options:
  --shards N         number of shards (array tasks), 1..10000; required
  --tier T           the tier paper or studies instead of one spec
  --partition P      Slurm partition (default: the cluster's default)
  --time T           time limit of each job, as Slurm takes it (e.g. 01:00:00, 2-00:00:00)
  --account A        Slurm account to charge
  --cpus-per-task C  cores per array task, used as the shard's --jobs (default 1)
  --render-cpus R    cores of the render job, its make JOBS (--tier; default C)
  --throttle M       at most M array tasks at once (Slurm's --array=0-(N-1)%M)
  --work DIR         folder of the scripts, shard outputs and logs (default slurm-<name>)
  --out DIR          folder of the merged reports (default results)
  --timing keep|omit passed to the merge (as for 'mpmstab sweep'; not with --tier)
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

// What the scripts are written from: the checked options and the specs.
struct SlurmJob {
  std::int64_t shards = 1;
  std::int64_t cpus = 1;               // per task, the shard's --jobs
  std::int64_t render_cpus = 1;        // the render job's make JOBS (a tier)
  std::int64_t throttle = 0;           // array tasks at once (0: as many as the cluster gives)
  bool omit = false;                   // --timing omit, passed to the merge
  std::string tier;                    // the tier, or empty: one spec
  std::string name;                    // the spec's name, or the tier
  std::vector<std::string> spec_args;  // the specs as given, which the jobs read
  std::size_t cases = 0;               // over every spec
  std::string work;                    // scripts, shard outputs and logs
  std::string out;                     // merged reports
  fs::path binary;                     // the mpmstab the jobs run
  std::string logs;                    // WORK/logs
};

std::int64_t count_option(const Args& args, std::string_view option, std::int64_t fallback,
                          std::int64_t most) {
  const auto v = args.value(option);
  if (!v) return fallback;
  const std::int64_t n = parse_int(*v, option);
  if (n < 1 || n > most) {
    throw UsageError("--" + std::string(option) + ": must be in [1, " + std::to_string(most) +
                     "], got " + std::string(*v));
  }
  return n;
}

// The spec, or the tier's specs (UsageError for a bad one).
void load_job_specs(const Args& args, SlurmJob& job) {
  if (const auto tier = args.value("tier")) {
    if (!args.positional().empty()) throw UsageError("--tier: takes no spec (the tier's are run)");
    if (args.value("timing")) throw UsageError("--timing: not with --tier (make writes the tier)");
    job.tier = std::string(*tier);
    job.spec_args = tier_spec_paths("experiments", job.tier);
    job.name = job.tier;
    std::error_code ec;
    if (!fs::is_regular_file("Makefile", ec))
      throw UsageError("--tier: the render job runs 'make tier' in the current folder, " +
                       fs::current_path().string() +
                       ", which has no Makefile (run it in the checkout)");
  } else {
    if (args.positional().size() != 1) throw UsageError("slurm takes one spec (or --tier)");
    job.spec_args = {std::string(args.positional().front())};
  }
  std::vector<std::string_view> views(job.spec_args.begin(), job.spec_args.end());
  for (const Spec& spec : load_specs(views)) {
    job.cases += spec.cases.size();
    if (job.tier.empty()) job.name = spec.name;
  }
}

// Checks the options and loads the specs; UsageError for the first bad one.
SlurmJob job_from(const Args& args) {
  SlurmJob job;
  const auto shards_text = args.value("shards");
  if (!shards_text) throw UsageError("missing required option --shards");
  job.shards = count_option(args, "shards", 1, 10000);
  job.cpus = count_option(args, "cpus-per-task", 1, 1024);
  job.render_cpus = count_option(args, "render-cpus", job.cpus, 1024);
  job.throttle = count_option(args, "throttle", 0, 10000);
  job.omit = omit_timing(args);
  load_job_specs(args, job);
  if (job.tier.empty() && args.value("render-cpus"))
    throw UsageError("--render-cpus: only with --tier");
  job.work = std::string(args.value("work").value_or("slurm-" + job.name));
  job.out = std::string(args.value("out").value_or("results"));
  job.binary =
      args.value("mpmstab") ? fs::absolute(std::string(*args.value("mpmstab"))) : this_binary();
  std::error_code ec;
  if (!fs::is_regular_file(job.binary, ec) || ::access(job.binary.c_str(), X_OK) != 0) {
    throw UsageError("--mpmstab: " + job.binary.string() + " is not an executable file");
  }
  // make takes a variable's value up to the first blank.
  if (!job.tier.empty())
    for (const auto& [option, v] : {std::pair{"out", job.out}, {"mpmstab", job.binary.string()}})
      if (v.find_first_of(" \t") != std::string::npos)
        throw UsageError("--" + std::string(option) + ": '" + v +
                         "' has a blank, which make "
                         "cannot take in RESULTS or MPMSTAB");
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
  const std::string what =
      job.tier.empty()
          ? job.spec_args.front()
          : "the " + job.tier + " tier of " + std::to_string(job.spec_args.size()) + " experiments";
  return "#!/bin/bash\n# Written by 'mpmstab slurm' for " + what + " (" +
         std::to_string(job.cases) + " cases in " + std::to_string(job.shards) + " shards).\n";
}

std::string quoted_specs(const SlurmJob& job) {
  std::string words;
  for (const auto& spec : job.spec_args)
    words += " " + sh_quote(spec);
  return words;
}

// WORK/<prefix>0 ... WORK/<prefix>(N-1), quoted: the folders of an array's tasks.
std::string shard_folders(const SlurmJob& job, const std::string& prefix = "shard-") {
  std::string words;
  for (std::int64_t i = 0; i < job.shards; ++i)
    words += " " + sh_quote(job.work + "/" + prefix + std::to_string(i));
  return words;
}

// The merge of every shard's folder into OUT.
std::string merge_script(const SlurmJob& job, const std::string& common) {
  std::ostringstream merge;
  merge << header(job) << "#SBATCH --job-name=mpmstab-" << job.name
        << "-merge\n#SBATCH --output=" << job.logs << "/" << job.name << "-merge-%j.out\n"
        << common << "set -euo pipefail\nexec " << sh_quote(job.binary.string()) << " merge"
        << quoted_specs(job) << shard_folders(job) << " --out " << sh_quote(job.out)
        << (job.omit ? " --timing omit" : "") << "\n";
  return merge.str();
}

// A job array of N tasks named `log` in the logs: task I runs `mpmstab <command> --shard I/N
// --jobs C --out WORK/<prefix>I`.
std::string array_script(const SlurmJob& job, const std::string& common,
                         const std::string& name_suffix, const std::string& log,
                         const std::string& command, const std::string& prefix) {
  std::ostringstream array;
  array << header(job) << "#SBATCH --job-name=mpmstab-" << job.name << name_suffix
        << "\n#SBATCH --array=0-" << job.shards - 1
        << (job.throttle ? "%" + std::to_string(job.throttle) : "")
        << "\n#SBATCH --cpus-per-task=" << job.cpus << "\n#SBATCH --output=" << job.logs << "/"
        << job.name << "-" << log << "-%A_%a.out\n"
        << common << "set -euo pipefail\nexec " << sh_quote(job.binary.string()) << command
        << " --shard \"${SLURM_ARRAY_TASK_ID}/" << job.shards
        << "\" --jobs \"${SLURM_CPUS_PER_TASK:-" << job.cpus << "}\" --out "
        << sh_quote(job.work + "/" + prefix) << "\"${SLURM_ARRAY_TASK_ID}\"\n";
  return array.str();
}

// The job array over the cases: task I runs shard I/N into WORK/shard-I (a tier's cases in one
// queue).
std::string sweep_script(const SlurmJob& job, const std::string& common) {
  return array_script(job, common, "", "sweep",
                      (job.tier.empty() ? " sweep" : " reproduce") + quoted_specs(job), "shard-");
}

// A tier's second array: task I runs shard I/N of the follow-up runs the records of the first
// decide into WORK/follow-I.
std::string follow_script(const SlurmJob& job, const std::string& common) {
  return array_script(job, common, "-follow", "follow",
                      " reproduce" + quoted_specs(job) + shard_folders(job) + " --follow-ups",
                      "follow-");
}

// A tier's render: every shard's records and the follow-up runs' into OUT/cache, then the tier
// as make writes it.
std::string render_script(const SlurmJob& job, const std::string& common) {
  std::ostringstream render;
  render << header(job) << "#SBATCH --job-name=mpmstab-" << job.name
         << "-render\n#SBATCH --cpus-per-task=" << job.render_cpus
         << "\n#SBATCH --output=" << job.logs << "/" << job.name << "-render-%j.out\n"
         << common << "set -euo pipefail\n"
         << sh_quote(job.binary.string()) << " merge" << quoted_specs(job) << shard_folders(job)
         << shard_folders(job, "follow-") << " --records-only --with-follow-ups --out "
         << sh_quote(job.out) << "\nexec make --no-print-directory tier "
         << sh_quote("TIER=" + job.tier) << " " << sh_quote("RESULTS=" + job.out) << " "
         << sh_quote("MPMSTAB=" + job.binary.string()) << " \"JOBS=${SLURM_CPUS_PER_TASK:-"
         << job.render_cpus << "}\"\n";
  return render.str();
}

// Submits the array, then each later job with --dependency=afterok on the one before it: the
// merge (a spec), or the follow-up array and the render (a tier).
std::string submit_script(const SlurmJob& job,
                          const std::vector<std::pair<std::string, std::string>>& jobs) {
  std::ostringstream submit;
  submit << "#!/bin/sh\n# Submits the sweep array of "
         << (job.tier.empty() ? job.spec_args.front() : "the " + job.tier + " tier");
  for (std::size_t j = 1; j < jobs.size(); ++j)
    submit << ", then its "
           << (jobs[j].first == "follow" ? "follow-up array" : jobs[j].first + " job");
  submit << ", each started once every task of the one before succeeded.\nset -eu\ncd "
         << sh_quote(fs::current_path().string()) << "\n";
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    const std::string& name = jobs[j].first;
    submit << name << "=$(sbatch --parsable "
           << (j == 0 ? std::string() : "--dependency=afterok:\"$" + jobs[j - 1].first + "\" ")
           << sh_quote(jobs[j].second) << ")\n"
           << name << "=${" << name << "%%;*}\n";
  }
  for (const auto& [name, file] : jobs)
    submit << "echo \"" << name << " $" << name << "\"\n";
  return submit.str();
}

}  // namespace

int cmd_slurm(const std::vector<std::string_view>& argv) {
  const Args args(argv, {{"shards"},
                         {"tier"},
                         {"partition"},
                         {"time"},
                         {"account"},
                         {"cpus-per-task"},
                         {"render-cpus"},
                         {"throttle"},
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
  auto file = [&](const std::string& what) { return job.work + "/" + job.name + "." + what; };
  // Each job's name and script, in the order they run.
  std::vector<std::pair<std::string, std::string>> jobs = {{"sweep", file("sweep.sbatch")}};
  if (job.tier.empty()) {
    jobs.emplace_back("merge", file("merge.sbatch"));
  } else {
    jobs.emplace_back("follow", file("follow.sbatch"));
    jobs.emplace_back("render", file("render.sbatch"));
  }
  const std::string submit_file = file("submit.sh");
  std::error_code ec;
  fs::create_directories(job.logs, ec);
  if (ec) throw UsageError("--work: cannot create " + job.logs + ": " + ec.message());
  write_file_atomically(jobs[0].second, sweep_script(job, common));
  if (job.tier.empty()) {
    write_file_atomically(jobs[1].second, merge_script(job, common));
  } else {
    write_file_atomically(jobs[1].second, follow_script(job, common));
    write_file_atomically(jobs[2].second, render_script(job, common));
  }
  write_file_atomically(submit_file, submit_script(job, jobs));
  fs::permissions(submit_file, fs::perms::owner_exec | fs::perms::group_exec,
                  fs::perm_options::add);
  std::string written;
  for (const auto& [name, path] : jobs)
    written += path + ", ";
  std::cout << "Wrote " << written << "and " << submit_file << ".\nSubmit with: sh " << submit_file
            << "\nThe "
            << (job.tier.empty() ? "merged reports will be in " + job.out + "/" + job.name + ".md"
                                 : "rendered tier will be in " + job.out + "/README.md")
            << "\n";
  return 0;
}

}  // namespace mpmstab::cli
