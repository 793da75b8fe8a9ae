// The regression gate: our own results, blessed. `check` reruns a fast subset of every
// experiment and compares it with the blessed values; it also compares the paper-comparison
// verdicts with their blessed expectations. `bless` rewrites the values that changed and logs
// why in BLESSED.md.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "spec.hpp"

namespace mpmstab {

struct RegressionOptions {
  std::filesystem::path reference = "reference/regression";  // blessed values
  std::filesystem::path results = "results";                 // for comparison.csv
  int jobs = 1;
  double budget = 2e7;  // a case is in the fast subset when it needs at most this many
                        // particle-steps
  double rtol = 0;      // relative tolerance for floating-point columns (see README)
};

// The cases of `spec` in its fast subset.
Spec fast_subset(const Spec& spec, double budget);

// Returns 0 when everything matches; otherwise prints one line per failing cell (parameters,
// column, expected, obtained, relative difference, tolerance) to stderr and returns 1.
int run_check(const std::vector<Spec>& specs, const RegressionOptions& options);

// Rewrites the blessed values that changed (and the verdict expectations) and appends the date,
// the commit, the reason and the cells changed to BLESSED.md. `reason` must not be empty.
int run_bless(const std::vector<Spec>& specs, const RegressionOptions& options,
              const std::string& reason);

}  // namespace mpmstab
