// Where a result came from: the source tree, the build, the machine and the date.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace mpmstab {

struct Provenance {
  std::string commit;  // git commit of the source tree, or "unknown"
  bool dirty = false;  // uncommitted changes outside results/
  std::string compiler;
  std::string flags;
  std::string eigen;
  std::string date;  // UTC, ISO 8601
  std::string cpu;
  std::string kernels;  // the kernels' instruction set on this CPU (core/base/instruction_set.hpp)
  int threads = 1;      // parallel cases in the sweep that computed the result
};

// The provenance of a computation starting now with `threads` parallel cases. The commit, whether
// the tree has uncommitted changes and the CPU are read once per process, at the first call.
Provenance current_provenance(int threads);

nlohmann::ordered_json to_json(const Provenance& p);

}  // namespace mpmstab
