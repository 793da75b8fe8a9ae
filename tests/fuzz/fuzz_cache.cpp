// libFuzzer target for the cache reader (ResultCache::check, behind lookup): any text must give
// a record that passed every check or a rejection, and never throw. A record that passes holds
// a result of the record's shape and is what the sweep then reads.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "cache.hpp"
#include "result_json.hpp"
#include "sweep.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  mpmstab::RunParams p;
  p.method = mpmstab::Method::gimp;
  p.E = 4;
  p.A = 0.01;
  p.dt = 1e-3;
  p.T = 0.01;
  p.cells = 10;
  p.observe.dt_stable = false;  // what a spec records by default (the seeds' records)
  p.observe.crossings = false;
  const mpmstab::CacheLookup found = mpmstab::ResultCache::check(text, "fuzz.json", p);
  if (found.record.has_value() == found.rejected) __builtin_trap();
  if (found.record) {
    if (!mpmstab::record_defect((*found.record)["result"]).empty()) __builtin_trap();
    (void)mpmstab::deterministic_part(*found.record);
  }
  return 0;
}
