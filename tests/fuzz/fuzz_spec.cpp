// libFuzzer target for the experiment-spec parser: any text must either load or be refused with
// a SpecError. Anything else (another exception, a crash, undefined behaviour, a leak) is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "spec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const mpmstab::Spec spec = mpmstab::parse_spec(text, "fuzz.json");
    // A spec that loads has valid cases.
    for (const auto& c : spec.cases) {
      if (!mpmstab::validate(c.params).empty()) __builtin_trap();
    }
  } catch (const mpmstab::SpecError&) {
  }
  return 0;
}
