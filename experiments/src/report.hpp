// Reports of an experiment: CSV and JSON (one row per case, with provenance), Markdown laid out
// like the paper's table with the paper's values beside ours, and the data a figure plots.
// Every file is written atomically, and only when its content changed.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "spec.hpp"
#include "sweep.hpp"

namespace mpmstab {

// Writes <out>/<name>.csv, .json, .md and, for figures, <name>_data.csv.
void write_reports(const Spec& spec, const SweepOutcome& outcome, const std::filesystem::path& out);

// Writes <out>/README.md, the index a reader browses, from the <name>.json of each spec.
void write_index(const std::vector<Spec>& specs, const std::filesystem::path& out);

// Writes `content` to `path` atomically unless the file already holds exactly that.
void write_if_changed(const std::filesystem::path& path, const std::string& content);

// "5.1e-5": `digits` significant digits, compact exponent.
std::string sci(double v, int digits = 2);

}  // namespace mpmstab
