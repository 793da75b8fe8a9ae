// The paper comparison: every Table 1 cell, ours beside the paper's, with a verdict and a class
// of disagreement, and a section per class with its explanation and the supporting experiment.
#pragma once

#include <filesystem>
#include <vector>

#include "spec.hpp"

namespace mpmstab {

// Reads <out>/<name>.json of the table1 spec and of the supporting experiments (by name:
// courant, walls, crossing, eq108; any that is missing is reported as not run) and writes
// <out>/comparison.md and <out>/comparison.csv (one row per cell: verdict and class).
void write_comparison(const Spec& table1, const std::vector<Spec>& support,
                      const std::filesystem::path& out);

}  // namespace mpmstab
