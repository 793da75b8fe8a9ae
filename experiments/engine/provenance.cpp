#include "provenance.hpp"

#include <Eigen/Core>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

#include "base/instruction_set.hpp"
#include "process.hpp"

namespace mpmstab {

namespace {

// First line of a git command's standard output in the source tree ("" when it fails).
std::string git_line(std::vector<std::string> args) {
  args.insert(args.begin(), {"git", "-C", MPMSTAB_SOURCE_DIR});
  std::string out = run_program(args).value_or("");
  out = out.substr(0, out.find('\n'));
  while (!out.empty() && out.back() == '\r')
    out.pop_back();
  return out;
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
    }
  }
  return "unknown";
}

std::string utc_now() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

// What the source tree and the machine give a provenance, read once per process: the two git
// commands (the second walks the whole tree) cost more than many a run, and a search that
// stores each run's record as it goes (the advice sample's) spent about a fifth of its time in
// them when they ran for every record.
struct Origin {
  std::string commit;
  bool dirty = false;
  std::string cpu;
};

const Origin& origin() {
  static const Origin o = [] {
    Origin read;
    read.commit = git_line({"rev-parse", "HEAD"});
    if (read.commit.empty()) {
      read.commit = "unknown";
    } else {
      read.dirty = !git_line({"status", "--porcelain", "--untracked-files=no", "--", ".",
                              ":(exclude)results"})
                        .empty();
    }
    read.cpu = cpu_model();
    return read;
  }();
  return o;
}

}  // namespace

Provenance current_provenance(int threads) {
  Provenance p;
  const Origin& o = origin();
  p.commit = o.commit;
  p.dirty = o.dirty;
  p.compiler = MPMSTAB_COMPILER;
  p.flags = MPMSTAB_CXX_FLAGS;
  p.eigen = std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
            std::to_string(EIGEN_MINOR_VERSION);
  p.date = utc_now();
  p.cpu = o.cpu;
  p.kernels = kernel_instruction_set();
  p.threads = threads;
  return p;
}

nlohmann::ordered_json to_json(const Provenance& p) {
  return {{"commit", p.commit}, {"dirty", p.dirty},     {"compiler", p.compiler},
          {"flags", p.flags},   {"eigen", p.eigen},     {"date", p.date},
          {"cpu", p.cpu},       {"kernels", p.kernels}, {"threads", p.threads}};
}

}  // namespace mpmstab
