// What `mpmstab run` and `mpmstab edge` share: the options that describe one case, their
// conversion to RunParams, and the number format of the text summaries.
#pragma once

#include <string>
#include <vector>

#include "args.hpp"
#include "base/params.hpp"
#include "run_summary.hpp"

namespace mpmstab::cli {

// The options of `mpmstab run`, in the order of its help text.
const std::vector<OptionSpec>& run_options();

// The parameters given by the options, validated (UsageError names every bad option). With
// `searching_dt` (edge, spectral) no dt is read: dt = T, the search replaces it. Without
// `amplitude_required` (spectral) a missing --A is 0.
RunParams params_from(const Args& a, bool searching_dt = false, bool amplitude_required = true);

// A number in the text summaries: four significant digits (run_summary.hpp).
using mpmstab::fmt;

}  // namespace mpmstab::cli
