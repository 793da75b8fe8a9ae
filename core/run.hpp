// Run one case to T (or to its failure) and measure it.
#pragma once

#include <atomic>

#include "params.hpp"
#include "result.hpp"

namespace mpmstab {

// `p` must be valid (validate(p) empty). Never throws for a valid p; an unstable run returns
// with stable = false and the failure's reason, step and time. When `cancel` is given and
// becomes true, the run stops within a few thousand steps and returns with interrupted = true
// (such a result is incomplete: it is neither a verdict nor to be cached).
RunResult run(const RunParams& p, const std::atomic<bool>* cancel = nullptr);

}  // namespace mpmstab
