// One run through the result cache, for a study whose runs are chosen one after another from the
// runs before them (a search: `mpmstab advise`'s, which the advice sample runs on its problems),
// so that they cannot be declared up front as follow-ups: the record of these parameters where
// the cache holds one (stored by a sweep or by an earlier call), else the run, computed, stored
// and returned. A report rendered again then computes nothing, and a run a sweep already made is
// not made twice.
#pragma once

#include "base/params.hpp"
#include "base/result.hpp"
#include "cache.hpp"

namespace mpmstab {

// The run's verdict, failure step, steps, particles and errors, as a fresh run gives them (the
// histories and final state are not kept). Throws std::runtime_error when the cache folder is not
// writable.
RunResult cached_run(const ResultCache& cache, const RunParams& p);

}  // namespace mpmstab
