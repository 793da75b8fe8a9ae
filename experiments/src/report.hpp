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

// The CSV columns of a spec's result rows: in a variants experiment (or where a case compares
// another error than the one at T) the variant, the paper's column and the error compared, then
// the run's columns (the last two of which are timing measurements).
std::vector<std::string> result_columns(const Spec& spec);
// One case as a flat row: every column of result_columns(), for edge experiments also those of
// the search.
nlohmann::ordered_json flat_row(const CaseSpec& c, const nlohmann::ordered_json& record);
// A JSON value as a CSV field: "" for null, shortest round-trip text for numbers.
std::string csv_cell(const nlohmann::ordered_json& v);

// Writes `content` to `path` atomically unless the file already holds exactly that.
void write_if_changed(const std::filesystem::path& path, const std::string& content);

}  // namespace mpmstab
