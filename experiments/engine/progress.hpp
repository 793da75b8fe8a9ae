// The accounting behind the progress line of a sweep or of make reproduce: cases done of all,
// particle-steps computed of the estimated total, and the time to go. Pure arithmetic on what
// the caller reports (no clock, no output), so that every queue's line can be tested.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mpmstab {

class ProgressCounter {
 public:
  // `runs` tasks whose estimated work sums to `estimated_cost` particle-steps.
  ProgressCounter(std::size_t runs, double estimated_cost);

  // Tasks added after the start (follow-up runs), `cost` their estimated work; `retire` of the
  // expected work (below) they replace leaves it.
  void add(std::size_t runs, double cost, double retire = 0);
  // Work expected to be added later (an experiment's follow-up runs, as its last published
  // results ask for them): in the total until the tasks that replace it are added.
  void expect(double cost);
  // The work done so far by the tasks running now (particle-steps; their runs count it as they
  // go, run.hpp).
  void running(double work) { running_ = std::max(0.0, work); }

  // Work done outside the tasks (the runs a report makes itself while it renders), now over:
  // counted as done, its estimate being the work itself; `retire` of the work expected for it
  // leaves the total.
  void finished_work(double work, double retire);
  // A task finished: from the cache (no work done, its estimate leaves the total) or computed
  // (its estimate `cost` replaced by the measured `work`); `unstable`: its verdict.
  void finished(bool from_cache, double cost, double work, bool unstable);

  std::size_t done() const { return done_; }
  // Every task done and none expected.
  bool finished() const { return done_ >= runs_ && !(expected_ > 0); }
  std::size_t runs() const { return runs_; }
  // The estimated work still to do, never below 0: the estimates of the tasks left and of those
  // expected, less what the running ones have done.
  double remaining_cost() const;
  // Seconds to go for the estimated work left, when it is known: the geometric mean of that work
  // at two rates, the finished tasks' estimates per second and their measured work per second
  // (each with the running tasks' work so far). None before any work is counted, when `elapsed`
  // is below a second, or when the answer would be more than kMaxHorizon times the elapsed time
  // (too little done to say).
  std::optional<double> seconds_to_go(double elapsed) const;
  static constexpr double kMaxHorizon = 100;

  // The line, without the leading carriage return: "[label] 3/10 cases, 1 unstable, 2.1e+06
  // of ~8.4e+06 particle-steps, 12 s elapsed, ~36 s to go". Done: the work computed, with the
  // count of cases from the cache.
  std::string text(const std::string& label, double elapsed) const;

 private:
  std::size_t runs_, done_ = 0, cached_ = 0, unstable_ = 0;
  double estimated_cost_;  // of every task not from the cache
  double expected_ = 0;    // of tasks not added yet
  double done_cost_ = 0;   // the estimates of the computed tasks done
  double done_work_ = 0;   // their measured work
  double running_ = 0;     // the work so far of the tasks running
};

// How the time to go a queue's progress line showed compared with the truth, once the queue ended
// `wall` seconds after it started. Judged from the first kSkip of the wall (the rate is not known
// before) until the last kTail (where both times are a few seconds and their ratio says little).
struct EstimateAccuracy {
  static constexpr double kSkip = 0.1;
  static constexpr double kTail = 0.05;
  std::size_t samples = 0;  // estimates judged
  double worst = 0;         // the largest factor between an estimate and the truth (>= 1)
  // At about 10, 25, 50 and 75% of the wall: (fraction of the wall, estimated, true seconds to go).
  std::vector<std::vector<double>> at;
};
// `estimates`: (seconds elapsed, seconds to go) as the line showed them.
EstimateAccuracy estimate_accuracy(const std::vector<std::pair<double, double>>& estimates,
                                   double wall);

}  // namespace mpmstab
