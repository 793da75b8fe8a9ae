// RunResult as JSON: the keys defined in docs/design.md, "Measured quantities", in a fixed order.
#pragma once

#include <nlohmann/json.hpp>

#include "edge.hpp"
#include "result.hpp"

namespace mpmstab {

// Absent quantities (an observer that was off, the error of an unstable run) are null, never NaN.
nlohmann::ordered_json to_json(const RunResult& r);
nlohmann::ordered_json history_to_json(const RunResult& r);

// The search of an edge experiment: dt_edge, the bracket, the probes and the warnings.
nlohmann::ordered_json edge_to_json(const EdgeResult& e);

}  // namespace mpmstab
