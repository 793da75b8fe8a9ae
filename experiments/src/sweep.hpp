// Running the cases of a spec: in parallel, from the cache where possible, with progress.
#pragma once

#include <atomic>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "spec.hpp"

namespace mpmstab {

struct SweepOptions {
  int jobs = 1;                 // cases run at once
  bool force = false;           // compute every case again, ignoring the cache
  std::filesystem::path cache;  // cache folder; empty: compute every case, store nothing
  bool progress_line = false;   // one updating line (terminal) instead of a line per case
  bool quiet = false;           // no progress at all
  // Set (by a signal handler) to stop: no new case starts, running cases stop within a few
  // thousand steps, finished cases stay in the cache.
  const std::atomic<bool>* cancel = nullptr;
};

struct SweepOutcome {
  // One record per case, in spec order: {"result", "provenance"[, "history"][, "final_state"]}.
  std::vector<nlohmann::ordered_json> records;
  int computed = 0;
  int cached = 0;
  // Cases whose run (canonical parameters and search) repeats an earlier case of the same spec,
  // for example two variants that differ only in what they compare: run once, record shared.
  int shared = 0;
  int unstable = 0;
  double wall_seconds = 0;
  bool interrupted = false;  // stopped by `cancel`: records of unfinished cases are null
};

// The work of a case in particle-steps (an estimate for the adaptive policies and for edge
// searches), for scheduling, progress and the fast subset of make check.
double case_cost(const RunParams& p, ReportKind kind);

// Results do not depend on `jobs`: every case is an independent, deterministic computation and
// the records are returned in spec order. Cases with the same canonical parameters are computed
// (or read from the cache) once.
SweepOutcome run_sweep(const Spec& spec, const SweepOptions& options);

}  // namespace mpmstab
