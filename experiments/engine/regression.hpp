// The regression gate: our own results, blessed. `check` reruns a fast subset of every
// experiment and compares it with the blessed values; it also compares the tables studies
// declare as blessed outputs (Study::blessed) with their blessed expectations. `bless` rewrites the
// values that changed and logs why in BLESSED.md.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "spec.hpp"

namespace mpmstab {

struct RegressionOptions {
  std::filesystem::path reference = "reference/regression";  // blessed values
  std::filesystem::path results = "results";  // where studies write their blessed outputs
  int jobs = 1;
  double budget = 2e7;        // a case is in the fast subset when it needs at most this many
                              // particle-steps: a spec's check_budget, unless budget_given
  bool budget_given = false;  // --budget given: it applies to every spec
  double rtol = 0;            // relative tolerance for floating-point columns (see README)
};

// The cases of `spec` in its fast subset.
Spec fast_subset(const Spec& spec, double budget);
// The budget of a spec's fast subset under these options.
double budget_of(const Spec& spec, const RegressionOptions& o);

// Returns 0 when everything matches; otherwise prints one line per failing cell (parameters,
// column, expected, obtained, relative difference, tolerance) to stderr and returns 1.
int run_check(const std::vector<Spec>& specs, const RegressionOptions& options);

// Rewrites the blessed values that changed (and the verdict expectations) and appends the date,
// the commit, the reason and, per blessed table, how many rows and values changed to BLESSED.md
// (the values themselves are in the history of the committed tables). `reason` must not be empty.
int run_bless(const std::vector<Spec>& specs, const RegressionOptions& options,
              const std::string& reason);

}  // namespace mpmstab
