// libFuzzer target for the experiment-spec parser: any text must either load or be refused with
// a SpecError. Anything else (another exception, a crash, undefined behaviour, a leak) is a bug.
// A spec may name another with cases_from; make fuzz runs from the repository root, so a path
// like experiments/table1.json reaches a real spec.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "scenes/validate.hpp"
#include "spec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const mpmstab::Spec spec = mpmstab::parse_spec(text, "fuzz.json");
    // A spec that loads has valid cases; a case compared at its largest error records it.
    for (const auto& c : spec.cases) {
      if (!mpmstab::validate(c.params).empty()) __builtin_trap();
      if (c.error_at == mpmstab::ErrorAt::max_over_time && !c.params.observe.error_over_time) {
        __builtin_trap();
      }
    }
    // The variants of a variants spec hold its cases, in order, and one of them is the default.
    if (!spec.variants.empty()) {
      std::size_t next = 0;
      bool baseline = false;
      for (const auto& v : spec.variants) {
        if (v.first_case != next || v.cases == 0) __builtin_trap();
        for (std::size_t i = v.first_case; i < v.first_case + v.cases; ++i) {
          if (spec.cases[i].variant != v.name) __builtin_trap();
        }
        next += v.cases;
        baseline = baseline || v.baseline;
      }
      if (next != spec.cases.size() || !baseline) __builtin_trap();
    }
  } catch (const mpmstab::SpecError&) {
  }
  return 0;
}
