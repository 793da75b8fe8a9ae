// libFuzzer target for the results reader (parse_results, behind load_results): any text must
// either pass, with every row a record of the right shape, or be refused with BadResults.
// Anything else (another exception, a crash, undefined behaviour, a leak) is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "report.hpp"
#include "result_json.hpp"
#include "spec.hpp"

namespace {

// A spec of two cases, as results files describe them.
const mpmstab::Spec& spec() {
  static const mpmstab::Spec s = mpmstab::parse_spec(
      R"({"name": "good", "report": "cases", "defaults": {"T": 0.01, "cells": 10, "dt": 1e-3},
          "cases": [{"method": "gimp", "E": 4, "A": 0.01}, {"method": "mpm", "E": 4, "A": 0.01}]})",
      "good.json");
  return s;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto doc = mpmstab::parse_results(text, "good.json", spec());
    if (!doc.is_object() || doc["cases"].size() != 2) __builtin_trap();
    for (const auto& row : doc["cases"]) {
      if (!mpmstab::record_defect(row).empty()) __builtin_trap();
    }
  } catch (const mpmstab::BadResults&) {
  }
  return 0;
}
