#include "cache.hpp"

#include <cstdint>
#include <fstream>
#include <sstream>

#include "atomic_file.hpp"
#include "csv.hpp"
#include "version.hpp"

namespace mpmstab {

std::string canonical_parameters(const RunParams& p) {
  const Observe& o = p.observe;
  std::ostringstream s;
  s << "solver=" << kSolverVersion << ";method=" << to_string(p.method) << ";E=" << shortest(p.E)
    << ";A=" << shortest(p.A) << ";dt=" << shortest(p.dt) << ";T=" << shortest(p.T)
    << ";cells=" << p.cells << ";ppc=" << p.ppc << ";bc=" << to_string(p.bc)
    << ";position_update=" << to_string(p.position_update)
    << ";dt_stable_sigma=" << to_string(p.stable.sigma)
    << ";dt_stable_vnorm=" << to_string(p.stable.vnorm) << ";max_steps=" << p.max_steps
    << ";policy=" << to_string(p.stepping.policy)
    << ";cfl_factor=" << shortest(p.stepping.cfl_factor)
    << ";safety=" << shortest(p.stepping.safety) << ";record=" << (o.error_over_time ? "e" : "")
    << (o.dt_stable ? "s" : "") << (o.crossings ? "c" : "") << (o.final_state ? "f" : "");
  if (o.history) s << "h" << o.history_stride;
  // The implementation choices came after the first cached runs: they enter the key only when
  // one differs from its default, so that the keys of default runs did not change.
  if (!default_choices(p)) {
    s << ";scene=" << to_string(p.scene) << ";walls=" << to_string(p.walls)
      << ";transfer=" << to_string(p.transfer);
    if (p.transfer == Transfer::blend) s << ";flip_fraction=" << shortest(p.flip_fraction);
    s << ";update=" << to_string(p.update) << ";body_force_time=" << to_string(p.body_force_time);
  }
  return s.str();
}

namespace {
std::string canonical(const RunParams& p, const std::string& search) {
  return search.empty() ? canonical_parameters(p) : canonical_parameters(p) + ";search=" + search;
}
}  // namespace

std::string case_key(const RunParams& p, const std::string& search) {
  std::uint64_t h = 1469598103934665603ull;
  for (const unsigned char c : canonical(p, search)) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::optional<nlohmann::ordered_json> ResultCache::load(const RunParams& p,
                                                        const std::string& search) const {
  std::ifstream in(dir_ / (case_key(p, search) + ".json"), std::ios::binary);
  if (!in) return std::nullopt;
  std::stringstream buffer;
  buffer << in.rdbuf();
  try {
    auto record = nlohmann::ordered_json::parse(buffer.str());
    // A hash collision or a stale file must not pass for this case.
    if (record.value("canonical", "") != canonical(p, search)) return std::nullopt;
    return record;
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;  // unreadable: compute again
  }
}

void ResultCache::store(const RunParams& p, nlohmann::ordered_json record,
                        const std::string& search) const {
  std::filesystem::create_directories(dir_);
  record["key"] = case_key(p, search);
  record["canonical"] = canonical(p, search);
  write_file_atomically(dir_ / (case_key(p, search) + ".json"), record.dump());
}

}  // namespace mpmstab
