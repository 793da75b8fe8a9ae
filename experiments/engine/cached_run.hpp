// One run through the result cache, for a study whose runs are chosen one after another from the
// runs before them (a search: `mpmstab advise`'s, which the advice sample runs on its problems),
// so that they cannot be declared up front as follow-ups: the record of these parameters where
// the cache holds one (stored by a sweep or by an earlier call), else the run, computed, stored
// and returned. A report rendered again then computes nothing, and a run a sweep already made is
// not made twice.
#pragma once

#include <atomic>
#include <cstdint>

#include "base/params.hpp"
#include "base/result.hpp"
#include "cache.hpp"

namespace mpmstab {

// The run's verdict, failure step, steps, particles and errors, as a fresh run gives them (the
// histories and final state are not kept). Throws std::runtime_error when the cache folder is not
// writable.
RunResult cached_run(const ResultCache& cache, const RunParams& p);

// What the runs cached_run computed (those it did not find in the cache) cost while an account
// was open on the calling thread: write_reports opens one around each experiment's report, so
// that timings.json counts the runs a report makes itself (the advice sample's searches) beside
// its cases and follow-up runs. for_each_in_parallel carries the caller's account to its workers.
// A run counted in an account is counted in its parent too, and so on up: make reproduce's queue
// holds the account of every report it renders (SweepQueue::report_account), so that its progress
// line and its tier's totals see those runs as they are made.
struct RunAccount {
  std::atomic<std::int64_t> runs{0};
  std::atomic<double> particle_steps{0};
  std::atomic<double> seconds{0};  // the runs' own wall times, summed
  RunAccount* parent = nullptr;

  void add(double run_particle_steps, double run_seconds) {
    for (RunAccount* a = this; a != nullptr; a = a->parent) {
      ++a->runs;
      a->particle_steps += run_particle_steps;
      a->seconds += run_seconds;
    }
  }
};

// The calling thread's open account (nullptr: none), and the one open from now on.
RunAccount* open_run_account();
void open_run_account(RunAccount* account);

// Opens `account` on the calling thread for its own lifetime, as a child of the one open before,
// which is open again when it ends (also when an exception leaves the scope).
class RunAccountScope {
 public:
  explicit RunAccountScope(RunAccount& account) : outer_(open_run_account()) {
    account.parent = outer_;
    open_run_account(&account);
  }
  ~RunAccountScope() { open_run_account(outer_); }
  RunAccountScope(const RunAccountScope&) = delete;
  RunAccountScope& operator=(const RunAccountScope&) = delete;

 private:
  RunAccount* outer_;
};

}  // namespace mpmstab
