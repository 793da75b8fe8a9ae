// build/mpmstab: the command-line front end.
#include <csignal>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <exception>
#include <iostream>
#include <string_view>
#include <vector>

#include "args.hpp"
#include "base/version.hpp"
#include "commands.hpp"
#include "files.hpp"
#include "provenance.hpp"
#include "report.hpp"
#include "spec.hpp"

namespace {

constexpr const char* kUsage = R"(Usage: mpmstab <command> [options]

Commands:
  run     run one case of the paper's 1D bar and report every measured quantity
  edge    find the largest fixed dt with which one case survives to T
  advise  the cheapest checked setting for a problem (A/L, c T/L, a target error / A)
  spectral  the largest dt at which the linearised step of a scheme amplifies nothing
  sweep   run the cases of an experiment spec in parallel and write its reports
  reproduce  run the cases of several specs in one queue, writing each one's reports when done
  index   write results/README.md, the index of the reports
  documents  write (or --check) the generated blocks of README.md and docs/
  plot    draw a figure experiment with gnuplot
  compare write results/comparison.md: every Table 1 cell against the paper
  performance  write results/performance.md (benchmark and experiment wall times)
  check   rerun a fast subset of every experiment against the blessed values
  bless   accept the current values as the blessed ones, with a reason
  merge   write the reports of a sweep that ran in shards (sweep --shard I/N)
  slurm   write a Slurm job array that runs a sweep in shards, and its merge job
  list    the experiment specs in the order they run, or the studies the program knows
  build-time  record the wall time of a fresh build of the tool (make calls it)
  cluster-time  record the wall time of a tier run as a Slurm job array (make studies-cluster)

'mpmstab <command> --help' describes a command; 'mpmstab --version' prints the version, the
commit, the compiler and the flags of this build.
)";

}  // namespace

int main(int argc, char** argv) {
  // A closed standard output (mpmstab ... | head) must not kill the program before its reports
  // are written: a write to it then fails with EPIPE instead, which the streams ignore.
  std::signal(SIGPIPE, SIG_IGN);
#ifdef __GLIBC__
  // The arrays of a run (a particle array of the largest cases is 6 MB) are kept by the allocator
  // when freed and reused by the next run, rather than returned to the system and faulted in
  // again page by page: extremes (1344 cases) 13.3 -> 12.4 s wall, 2.9 -> 1.8 s of system time.
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
#endif
  std::vector<std::string_view> args(argv + 1, argv + argc);
  if (args.size() == 1 && args[0] == "--version") {
    const mpmstab::Provenance p = mpmstab::current_provenance(1);
    std::cout << "mpmstab " << MPMSTAB_VERSION << ", solver version " << mpmstab::kSolverVersion
              << "\ncommit: " << p.commit << (p.dirty ? " (with uncommitted changes)" : "")
              << "\ncompiler: " << p.compiler << "\nflags: " << p.flags << "\neigen: " << p.eigen
              << "\n";
    return 0;
  }
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    (args.empty() ? std::cerr : std::cout) << kUsage;
    return args.empty() ? 2 : 0;
  }
  const std::string_view command = args[0];
  args.erase(args.begin());
  try {
    if (command == "run") return mpmstab::cli::cmd_run(args);
    if (command == "edge") return mpmstab::cli::cmd_edge(args);
    if (command == "advise") return mpmstab::cli::cmd_advise(args);
    if (command == "spectral") return mpmstab::cli::cmd_spectral(args);
    if (command == "sweep") return mpmstab::cli::cmd_sweep(args);
    if (command == "reproduce") return mpmstab::cli::cmd_reproduce(args);
    if (command == "index") return mpmstab::cli::cmd_index(args);
    if (command == "documents") return mpmstab::cli::cmd_documents(args);
    if (command == "plot") return mpmstab::cli::cmd_plot(args);
    if (command == "performance") return mpmstab::cli::cmd_performance(args);
    if (command == "compare") return mpmstab::cli::cmd_compare(args);
    if (command == "check") return mpmstab::cli::cmd_check(args);
    if (command == "bless") return mpmstab::cli::cmd_bless(args);
    if (command == "merge") return mpmstab::cli::cmd_merge(args);
    if (command == "slurm") return mpmstab::cli::cmd_slurm(args);
    if (command == "list") return mpmstab::cli::cmd_list(args);
    if (command == "build-time") return mpmstab::cli::cmd_build_time(args);
    if (command == "cluster-time") return mpmstab::cli::cmd_cluster_time(args);
    std::string message = "unknown command '" + std::string(command) + "'";
    if (auto guess = mpmstab::cli::nearest(
            command, {"run", "edge", "advise", "spectral", "sweep", "reproduce", "index",
                      "documents", "plot", "compare", "check", "bless", "performance", "merge",
                      "slurm", "list", "build-time", "cluster-time"})) {
      message += " (did you mean '" + *guess + "'?)";
    }
    throw mpmstab::cli::UsageError(message);
  } catch (const mpmstab::cli::UsageError& e) {
    std::cerr << "mpmstab " << command << ": error: " << e.what() << "\n"
              << "Try 'mpmstab " << command << " --help'.\n";
    return 2;
  } catch (const mpmstab::InputError& e) {  // a refused input file or output target
    std::cerr << "mpmstab " << command << ": error: " << e.what() << "\n";
    return 2;
  } catch (const mpmstab::SpecError& e) {
    std::cerr << "mpmstab " << command << ": error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "mpmstab " << command << ": internal error: " << e.what() << "\n";
    return 1;
  }
}
