// RunResult as JSON: the keys defined in docs/theory.md, "Measured quantities", in a fixed order.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/result.hpp"
#include "run/edge.hpp"

namespace mpmstab {

// The record of a run: one flat object with exactly record_columns(), in that order. It is the
// output of `mpmstab run --json`, the "result" of a cached case and the start of every row of a
// sweep's JSON and CSV. A quantity that was not measured (an observer that was off, the error of
// an unstable run, a parameter the policy does not use) is null, never 0 or NaN. Measurements of
// the machine are not in it: see timing_json.
const std::vector<std::string>& record_columns();
nlohmann::ordered_json to_json(const RunResult& r);
// The first way `row` differs from a record's shape ("" if none): an object with every column
// of record_columns(), each null or of the JSON type a record gives it, and an outcome that is
// unstable, meaningless or stable. Every reader of stored records checks it first.
std::string record_defect(const nlohmann::ordered_json& row);

// The machine's measurements of a run: wall_seconds and ns_per_particle_step. They differ between
// identical runs, so they are kept apart from the record (results/timings.json).
nlohmann::ordered_json timing_json(const RunResult& r);
nlohmann::ordered_json history_to_json(const RunResult& r);

// The search of an edge experiment: dt_edge, the bracket, the probes and the warnings.
nlohmann::ordered_json edge_to_json(const EdgeResult& e);
// The columns an edge case adds to its flat row (after the record of its run at dt_edge), read
// from edge_to_json's object.
nlohmann::ordered_json edge_columns(const nlohmann::ordered_json& edge);

}  // namespace mpmstab
