// RunResult as JSON: the keys of DESIGN.md section 4, in a fixed order.
#pragma once

#include <nlohmann/json.hpp>

#include "result.hpp"

namespace mpmstab {

// Absent quantities (an observer that was off, the error of an unstable run) are null, never NaN.
nlohmann::ordered_json to_json(const RunResult& r);
nlohmann::ordered_json history_to_json(const RunResult& r);

}  // namespace mpmstab
