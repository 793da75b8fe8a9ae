// The accounting behind the progress line of a sweep or of make reproduce: cases done of all,
// particle-steps computed of the estimated total, and the time to go. Pure arithmetic on what
// the caller reports (no clock, no output), so that every queue's line can be tested.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace mpmstab {

class ProgressCounter {
 public:
  // `runs` tasks whose estimated work sums to `estimated_cost` particle-steps.
  ProgressCounter(std::size_t runs, double estimated_cost);

  // Tasks added after the start (follow-up runs), `cost` their estimated work.
  void add(std::size_t runs, double cost);

  // A task finished: from the cache (no work done, its estimate leaves the total) or computed
  // (its estimate `cost` replaced by the measured `work`); `unstable`: its verdict.
  void finished(bool from_cache, double cost, double work, bool unstable);

  std::size_t done() const { return done_; }
  std::size_t runs() const { return runs_; }
  // The estimated work still to do, never below 0 (the estimates of the tasks left).
  double remaining_cost() const;
  // Seconds to go at the rate measured so far, when it is known: none before any computed
  // task has finished, when `elapsed` is below a second, or when the answer would be more
  // than kMaxHorizon times the elapsed time (too little done to say).
  std::optional<double> seconds_to_go(double elapsed) const;
  static constexpr double kMaxHorizon = 100;

  // The line, without the leading carriage return: "[label] 3/10 cases, 1 unstable, 2.1e+06
  // of ~8.4e+06 particle-steps, 12 s elapsed, ~36 s to go". Done: the work computed, with the
  // count of cases from the cache.
  std::string text(const std::string& label, double elapsed) const;

 private:
  std::size_t runs_, done_ = 0, cached_ = 0, unstable_ = 0;
  double estimated_cost_;  // of every task not from the cache
  double done_cost_ = 0;   // the estimates of the computed tasks done
  double done_work_ = 0;   // their measured work
};

}  // namespace mpmstab
