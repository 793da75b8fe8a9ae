// Run one case to T (or to its failure) and measure it.
#pragma once

#include <atomic>
#include <functional>

#include "base/params.hpp"
#include "base/result.hpp"

namespace mpmstab {

// `p` must be valid (validate(p) empty). Never throws for a valid p; an unstable run returns
// with stable = false and the failure's reason, step and time. When `cancel` is given and
// becomes true, the run stops within a few thousand steps and returns with interrupted = true
// (such a result is incomplete: it is neither a verdict nor to be cached).
//
// With a `history` sink, the run hands it every history row as it is made (every
// observe.history_stride-th step, and the last admissible one) and keeps none: the memory of a
// run does not grow with its length. Without one, the rows are kept in RunResult::history when
// observe.history is set (validate() bounds their number).
using HistorySink = std::function<void(const HistoryRow&)>;
RunResult run(const RunParams& p, const std::atomic<bool>* cancel = nullptr,
              const HistorySink& history = {});

// The work of the runs on this thread as they go, for a progress line: while a counter is set,
// every run on the thread adds its particles x 1024 to it every 1024 steps. Null (the default)
// counts nothing. No result depends on it.
void count_work_on_this_thread(std::atomic<double>* counter);

}  // namespace mpmstab
