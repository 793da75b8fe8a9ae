#include "cache.hpp"

#include "scenes/scene_registry.hpp"

#include <cmath>

#include <cstdint>
#include <fstream>
#include <initializer_list>
#include <sstream>

#include "base/version.hpp"
#include "csv.hpp"
#include "files.hpp"
#include "result_json.hpp"
#include "strict_json.hpp"

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
    << (o.dt_stable ? "s" : "") << (o.crossings ? "c" : "") << (o.final_state ? "f" : "")
    << (o.spectral ? "p" : "") << (o.energy ? "n" : "") << (o.error_l2 ? "l" : "")
    << (o.tip ? "t" : "");
  if (o.history) s << "h" << o.history_stride;
  // The implementation choices came after the first cached runs: they enter the key only when
  // one differs from its default, so that the keys of default runs did not change.
  if (!default_choices(p)) {
    s << ";scene=" << to_string(p.scene) << ";walls=" << to_string(p.walls)
      << ";transfer=" << to_string(p.transfer);
    if (p.transfer == Transfer::blend) s << ";flip_fraction=" << shortest(p.flip_fraction);
    if (p.transfer == Transfer::xpic) s << ";xpic_order=" << p.xpic_order;
    if (p.transfer == Transfer::fmpm) s << ";fmpm_order=" << p.fmpm_order;
    s << ";update=" << to_string(p.update) << ";body_force_time=" << to_string(p.body_force_time);
    if (p.layout.shift != 0) s << ";shift=" << shortest(p.layout.shift);
    if (p.layout.jitter != 0) s << ";jitter=" << shortest(p.layout.jitter);
    if (!std::isnan(p.body_start)) s << ";body_start=" << shortest(p.body_start);
    if (!std::isnan(p.body_length)) s << ";body_length=" << shortest(p.body_length);
    if (p.small_mass != SmallMass::none) {
      s << ";small_mass=" << to_string(p.small_mass)
        << ";small_mass_fraction=" << shortest(p.small_mass_fraction);
    }
    if (p.tip_load != 0) s << ";tip_load=" << shortest(p.tip_load);
    // After the choices that came before it, and only where not the default: every other key
    // stays as it was.
    if (p.start != VelocityStart::exact) s << ";start=" << to_string(p.start);
  }
  return s.str();
}

namespace {
std::string canonical(const RunParams& p, const std::string& search) {
  return search.empty() ? canonical_parameters(p) : canonical_parameters(p) + ";search=" + search;
}
}  // namespace

namespace {

// FNV-1a of the pieces one after the other, as of their concatenation, in hexadecimal.
std::string fnv1a_hex(std::initializer_list<std::string_view> pieces) {
  std::uint64_t h = 1469598103934665603ull;
  for (const std::string_view text : pieces) {
    for (const unsigned char c : text) {
      h ^= c;
      h *= 1099511628211ull;
    }
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace

std::string fnv1a_hex(std::string_view text) {
  return fnv1a_hex({text});
}

std::string case_key(const RunParams& p, const std::string& search) {
  return fnv1a_hex(canonical(p, search));
}

namespace {

// The checksum of a record: its canonical parameters and its content without the checksum.
std::string checksum(const nlohmann::ordered_json& record, const std::string& canonical_text) {
  nlohmann::ordered_json content = record;
  content.erase("checksum");
  return fnv1a_hex({canonical_text, "\n", content.dump()});
}

// The same checksum read from the text of a record as store() writes it: the record's dump, its
// checksum the last member, `,"checksum":"<16 hex digits>"}`. Without that member, the text
// before it and the closing brace are the dump of the content (store() checksums the record as
// it reads back), so hashing them gives checksum() without parsing and dumping again a record
// that may hold megabytes of history. True when the text is laid out so and its checksum holds;
// false says nothing (the parsed record is then checked by checksum()).
bool checksum_holds_in_text(std::string_view text, const std::string& canonical_text) {
  constexpr std::string_view kMember = ",\"checksum\":\"";
  constexpr std::size_t kDigits = 16, kTail = kMember.size() + kDigits + 2;  // digits, "}
  if (text.size() < kTail + 1 || text.substr(text.size() - 2) != "\"}") return false;
  const std::size_t member = text.size() - kTail;
  if (text.substr(member, kMember.size()) != kMember) return false;
  const std::string_view sum = text.substr(member + kMember.size(), kDigits);
  return fnv1a_hex({canonical_text, "\n", text.substr(0, member), "}"}) == sum;
}

// The columns added to the record after the first cached runs, each with the value every run
// before it had (its canonical key names none of them) and the column it follows:
//  - body_start, body_length, small_mass, small_mass_fraction (before "policy"): every such run
//    was of a scene that fills the grid, without a small-mass treatment;
//  - tip_load (after "small_mass_fraction"): no run had a tip load, so 0 where the scene takes
//    one and null where it does not.
// A record lacking them gets these values where to_json puts them.
void add_scene_columns(nlohmann::ordered_json& result) {
  if (!result.is_object() || !result.contains("policy")) return;
  const auto scene = result.find("scene");
  if (scene == result.end() || !scene->is_string()) return;
  const auto kind = parse_scene(scene->get<std::string>());
  if (!kind) return;
  const bool had_extent = result.contains("small_mass");
  if (!had_extent && !scene_info(*kind).fills_grid) return;
  if (had_extent && result.contains("tip_load")) return;
  nlohmann::ordered_json out;
  for (auto& [key, value] : result.items()) {
    if (key == "policy" && !had_extent) {
      out["body_start"] = nullptr;
      out["body_length"] = nullptr;
      out["small_mass"] = to_string(SmallMass::none);
      out["small_mass_fraction"] = nullptr;
    }
    if (key == "policy" && !result.contains("tip_load")) {
      out["tip_load"] = scene_info(*kind).tip_load ? nlohmann::ordered_json(0.0) : nullptr;
    }
    out[key] = value;
  }
  result = std::move(out);
}

// A stored record's checks, in order; true when it may stand for the case.
// `summed`: the checksum is already known to hold (checksum_holds_in_text).
bool intact(nlohmann::ordered_json& record, const std::string& canonical_text, bool summed) {
  if (!record.is_object()) return false;
  const auto canon = record.find("canonical");
  const auto sum = record.find("checksum");
  if (canon == record.end() || sum == record.end() || *canon != canonical_text ||
      !sum->is_string() || (!summed && *sum != checksum(record, canonical_text))) {
    return false;
  }
  const auto result = record.find("result");
  const auto provenance = record.find("provenance");
  if (result != record.end())
    add_scene_columns(*result);  // after the checksum: it covers
                                 // the record as written
  return result != record.end() && record_defect(*result).empty() && provenance != record.end() &&
         provenance->is_object();
}

}  // namespace

CacheLookup ResultCache::lookup(const RunParams& p, const std::string& search) const {
  const std::filesystem::path file = dir_ / (case_key(p, search) + ".json");
  std::optional<std::string> text;
  try {
    text = read_if_present(file);
  } catch (const InputError&) {
    return CacheLookup{std::nullopt, true};  // not a regular file, too large: computed again
  }
  if (!text) return {};
  return check(*text, file, p, search);
}

CacheLookup ResultCache::check(std::string_view text, const std::filesystem::path& file,
                               const RunParams& p, const std::string& search) {
  CacheLookup found;
  try {
    auto record = parse_json_strict<nlohmann::ordered_json>(text, file);
    const std::string canonical_text = canonical(p, search);
    if (intact(record, canonical_text, checksum_holds_in_text(text, canonical_text))) {
      found.record = std::move(record);
      return found;
    }
  } catch (const InputError&) {
    // not JSON: computed again
  } catch (const nlohmann::json::exception&) {
    // (not expected after parsing; a record that cannot be checked is not used)
  }
  found.rejected = true;
  return found;
}

void ResultCache::store(const RunParams& p, nlohmann::ordered_json record,
                        const std::string& search) const {
  std::filesystem::create_directories(dir_);
  const std::string canonical_text = canonical(p, search);
  record["key"] = case_key(p, search);
  record["canonical"] = canonical_text;
  record.erase("checksum");
  // Checksummed as it will be read back (the reader turns -0 into 0, NaN was written as null).
  const std::filesystem::path file = dir_ / (case_key(p, search) + ".json");
  record = parse_json_strict<nlohmann::ordered_json>(record.dump(), file);
  record["checksum"] = checksum(record, canonical_text);
  write_file_atomically(file, record.dump(), Durability::checksummed);
}

}  // namespace mpmstab
