// Run one case to T (or to its failure) and measure it.
#pragma once

#include "params.hpp"
#include "result.hpp"

namespace mpmstab {

// `p` must be valid (validate(p) empty). Never throws for a valid p; an unstable run returns
// with stable = false and the failure's reason, step and time.
RunResult run(const RunParams& p);

}  // namespace mpmstab
