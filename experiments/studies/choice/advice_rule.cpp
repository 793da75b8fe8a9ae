#include "choice/advice_rule.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <string_view>

#include "base/accuracy.hpp"
#include "csv.hpp"
#include "files.hpp"
#include "report_util.hpp"

namespace mpmstab {

namespace studies::advice_rule {
namespace {

using json_t = nlohmann::ordered_json;

// Each corner kind with its name in results/advice.json and its words in a report.
struct CornerNames {
  CornerKind kind;
  std::string_view name, words;
};
constexpr CornerNames kCornerNames[] = {{CornerKind::base, "base", "base"},
                                        {CornerKind::smallest_A, "smallest_A", ""},
                                        {CornerKind::largest_A, "largest_A", ""},
                                        {CornerKind::periodic, "periodic", "periodic"},
                                        {CornerKind::other_scene, "neo_hookean", "neo-Hookean"},
                                        {CornerKind::jittered, "jittered", "jittered"},
                                        {CornerKind::finer, "finer", ""}};

// The corner kind a name in results/advice.json gives (to_string's inverse).
std::optional<CornerKind> corner_kind(std::string_view name) {
  for (const auto& n : kCornerNames)
    if (n.name == name) return n.kind;
  return std::nullopt;
}

json_t corner_json(const CornerRun& c) {
  return {{"kind", std::string(to_string(c.kind))},
          {"cT", c.length},
          {"A", c.A},
          {"jitter", c.jitter},
          {"cells", c.cells},
          {"outcome", c.outcome},
          {"error_over_A", c.error_over_A ? json_t(*c.error_over_A) : json_t(nullptr)}};
}

json_t region_json(const Region& r) {
  json_t excluded = json_t::array();
  for (const auto& c : r.excluded)
    excluded.push_back(corner_json(c));
  return {{"cT_max", r.length},
          {"A_min", r.A_min},
          {"A_max", r.A_max},
          {"periodic", r.periodic},
          {"neo_hookean", r.other_scene},
          {"jitter_max", r.jitter},
          {"finer", r.finer},
          {"cells_max", r.cells_max},
          {"error_over_A", r.error_over_A},
          {"excluded", excluded}};
}

// Strict readers of results/advice.json: a missing or mistyped key names itself.
const json_t& at(const json_t& j, const char* key, const std::string& where) {
  if (!j.is_object() || !j.contains(key))
    throw InputError(where + ": missing \"" + std::string(key) + "\"");
  return j[key];
}
double number_at(const json_t& j, const char* key, const std::string& where) {
  const json_t& v = at(j, key, where);
  if (!v.is_number() || !std::isfinite(v.get<double>()))
    throw InputError(where + "." + key + ": must be a finite number");
  return v.get<double>();
}
constexpr long long kLargestCount = 1'000'000;  // cells or particles per cell in a setting
int int_at(const json_t& j, const char* key, const std::string& where) {
  const json_t& v = at(j, key, where);
  if (!v.is_number_integer() || v.get<long long>() < 1 || v.get<long long>() > kLargestCount)
    throw InputError(where + "." + key + ": must be a whole number from one to " +
                     std::to_string(kLargestCount));
  return v.get<int>();
}
bool bool_at(const json_t& j, const char* key, const std::string& where) {
  const json_t& v = at(j, key, where);
  if (!v.is_boolean()) throw InputError(where + "." + key + ": must be true or false");
  return v.get<bool>();
}
std::string string_at(const json_t& j, const char* key, const std::string& where) {
  const json_t& v = at(j, key, where);
  if (!v.is_string() || v.get<std::string>().size() > 64)
    throw InputError(where + "." + key + ": must be a short string");
  return v.get<std::string>();
}

CornerRun corner_from_json(const json_t& j, const std::string& where) {
  CornerRun c;
  const auto kind = corner_kind(string_at(j, "kind", where));
  if (!kind) throw InputError(where + ".kind: not a corner this program knows");
  c.kind = *kind;
  c.length = number_at(j, "cT", where);
  c.A = number_at(j, "A", where);
  c.jitter = number_at(j, "jitter", where);
  if (!(c.jitter >= 0 && c.jitter <= 1))
    throw InputError(where +
                     ".jitter: must be a fraction of the particle spacing, from zero to one");
  c.cells = int_at(j, "cells", where);
  c.outcome = string_at(j, "outcome", where);
  const json_t& e = at(j, "error_over_A", where);
  if (!e.is_null()) c.error_over_A = number_at(j, "error_over_A", where);
  return c;
}

Region region_from_json(const json_t& j, const std::string& where) {
  Region r;
  r.length = number_at(j, "cT_max", where);
  r.A_min = number_at(j, "A_min", where);
  r.A_max = number_at(j, "A_max", where);
  r.periodic = bool_at(j, "periodic", where);
  r.other_scene = bool_at(j, "neo_hookean", where);
  r.jitter = number_at(j, "jitter_max", where);
  r.finer = bool_at(j, "finer", where);
  r.cells_max = int_at(j, "cells_max", where);
  r.error_over_A = number_at(j, "error_over_A", where);
  const json_t& ex = at(j, "excluded", where);
  if (!ex.is_array()) throw InputError(where + ".excluded: must be an array");
  for (std::size_t i = 0; i < ex.size(); ++i)
    r.excluded.push_back(corner_from_json(ex[i], where + ".excluded[" + std::to_string(i) + "]"));
  if (!(r.A_min > 0 && r.A_min <= r.A_max && r.length > 0 && r.error_over_A >= 0))
    throw InputError(where + ": A_min, A_max, cT_max or error_over_A out of range");
  return r;
}

}  // namespace
}  // namespace studies::advice_rule

// ---------------------------------------------------------------------------------------------
// Regions

std::string_view to_string(CornerKind k) {
  for (const auto& n : studies::advice_rule::kCornerNames)
    if (n.kind == k) return n.name;
  return "base";
}

std::string_view corner_words(CornerKind k) {
  for (const auto& n : studies::advice_rule::kCornerNames)
    if (n.kind == k) return n.words;
  return "";
}

std::vector<Corner> region_corners(const RunParams& base, const RegionRule& rule) {
  const double c = wave_speed(base);
  std::vector<Corner> out;
  auto add = [&](CornerKind kind, double length, double A, double jitter = 0) {
    Corner corner{.kind = kind, .length = length, .jitter = jitter, .params = base};
    RunParams& p = corner.params;
    p.T = length / c;
    p.A = A;
    p.observe.error_over_time = true;
    if (kind == CornerKind::periodic) p.bc = Boundary::periodic;
    if (kind == CornerKind::other_scene) p.scene = SceneKind::steffen;
    p.layout.jitter = jitter;
    if (kind == CornerKind::finer) {
      p.cells = base.cells * rule.refine;
      if (p.stepping.policy == TimeStepPolicy::fixed) p.dt = base.dt / rule.refine;
    }
    out.push_back(std::move(corner));
  };
  const double small = rule.amplitudes[0], middle = rule.amplitudes[1], large = rule.amplitudes[2];
  for (const double length : rule.lengths) {
    if (length != rule.lengths.front()) add(CornerKind::base, length, middle);
    add(CornerKind::smallest_A, length, small);
    add(CornerKind::largest_A, length, large);
    add(CornerKind::periodic, length, large);
    add(CornerKind::other_scene, length, large);
    for (const double jitter : rule.jitters)
      add(CornerKind::jittered, length, large, jitter);
  }
  add(CornerKind::finer, rule.lengths.front(), middle);
  return out;
}

bool CornerRun::passes() const {
  return outcome == "stable" && error_over_A && *error_over_A < kAccurateFraction;
}

const CornerRun* CheckedSetting::corner(CornerKind kind, double length, double jitter) const {
  for (const auto& c : corners)
    if (c.kind == kind && c.length == length && c.jitter == jitter) return &c;
  return nullptr;
}

std::vector<Region> regions_of(const CheckedSetting& s, const RegionRule& rule) {
  std::vector<Region> out;
  if (s.corners.empty() || !s.courant_spectral ||
      !(s.courant <= *s.courant_spectral / rule.limit_margin))
    return out;
  const CornerRun* finer = s.corner(CornerKind::finer, rule.lengths.front());
  for (const double length : rule.lengths) {
    const CornerRun* base = s.corner(CornerKind::base, length);
    if (!base || !base->passes()) continue;
    Region r{.length = length, .A_min = rule.amplitudes[1], .A_max = rule.amplitudes[1]};
    r.cells_max = s.cells;
    r.error_over_A = *base->error_over_A;
    auto include = [&](const CornerRun* c) {
      if (!c) return false;
      if (!c->passes()) {
        r.excluded.push_back(*c);
        return false;
      }
      r.error_over_A = std::max(r.error_over_A, *c->error_over_A);
      return true;
    };
    if (include(s.corner(CornerKind::smallest_A, length))) r.A_min = rule.amplitudes[0];
    const bool large = include(s.corner(CornerKind::largest_A, length));
    if (large) r.A_max = rule.amplitudes[2];
    // At the largest amplitude: counted only where that amplitude is in the region.
    for (const auto& [kind, in] : {std::pair{CornerKind::periodic, &r.periodic},
                                   {CornerKind::other_scene, &r.other_scene}}) {
      const CornerRun* c = s.corner(kind, length);
      *in = large && include(c);
      if (!large && c && !c->passes()) r.excluded.push_back(*c);
    }
    // The jittered layouts in ascending jitter, up to the first that fails (include records
    // it); one beyond the region is recorded where it fails.
    bool jittered = large;
    for (const double jitter : rule.jitters) {
      const CornerRun* c = s.corner(CornerKind::jittered, length, jitter);
      if (jittered && include(c)) {
        r.jitter = jitter;
        continue;
      }
      if (!jittered && c && !c->passes()) r.excluded.push_back(*c);
      jittered = false;
    }
    r.finer = include(finer);
    if (r.finer) r.cells_max = s.cells * rule.refine;
    out.push_back(std::move(r));
  }
  return out;
}

bool advice_selected(const CheckedSetting& s, const std::vector<std::string>& methods) {
  if (methods.empty()) return true;
  std::string label = s.method;  // "gimp/apic": the parts other than flip and usl
  if (s.transfer != "flip") label += "/" + s.transfer;
  if (s.update != "usl") label += "/" + s.update;
  for (const auto& m : methods) {
    if (m == s.method || m == label || m == s.method + "/" + s.transfer + "/" + s.update ||
        m == s.method + "/" + s.transfer)
      return true;
  }
  return false;
}

std::string setting_name(const CheckedSetting& s) {
  std::ostringstream t;
  t << s.method_text() << ", " << s.cells << " cells, C = " << shortest(s.courant);
  return t.str();
}

std::string region_text(const Region& r, const RegionRule& rule) {
  std::ostringstream s;
  s << "A/L " << value_text(r.A_min);
  if (r.A_max != r.A_min) s << " to " << value_text(r.A_max);
  s << ", c T/L to " << value_text(r.length) << "; walls"
    << (r.periodic ? " and periodic" : " only") << "; the bar"
    << (r.other_scene ? " and the neo-Hookean scene" : " only") << "; uniform"
    << (r.jitter > 0 ? " and jittered to " + shortest(r.jitter) : std::string(" only")) << "; "
    << (r.finer ? "and one run on " + std::to_string(r.cells_max) + " cells (A/L " +
                      value_text(rule.amplitudes[1]) + ", walls, the bar, uniform, to c T/L " +
                      value_text(rule.lengths.front()) + ")"
                : std::string("no finer grid"));
  return s.str();
}

nlohmann::ordered_json to_json(const CheckedSetting& s) {
  using namespace studies::advice_rule;
  nlohmann::ordered_json corners = nlohmann::ordered_json::array(),
                         regions = nlohmann::ordered_json::array();
  for (const auto& c : s.corners)
    corners.push_back(corner_json(c));
  for (const auto& r : s.regions)
    regions.push_back(region_json(r));
  return {{"method", s.method},
          {"transfer", s.transfer},
          {"update", s.update},
          {"cells", s.cells},
          {"ppc", s.ppc},
          {"courant", s.courant},
          {"courant_spectral", s.courant_spectral ? nlohmann::ordered_json(*s.courant_spectral)
                                                  : nlohmann::ordered_json(nullptr)},
          {"corners", corners},
          {"regions", regions}};
}

std::string transfer_name(const std::string& transfer) {
  const auto open = transfer.find('(');
  if (open == std::string::npos) return transfer;
  if (transfer.back() != ')') return std::string();
  return transfer.substr(0, open);
}

CheckedSetting checked_setting_from_json(const nlohmann::ordered_json& j) {
  using namespace studies::advice_rule;
  const std::string where = "setting";
  CheckedSetting s;
  s.method = string_at(j, "method", where);
  s.transfer = string_at(j, "transfer", where);
  s.update = string_at(j, "update", where);
  if (!parse_method(s.method))
    throw InputError(where + ".method: unknown method '" + s.method + "' (expected " +
                     choices_text(names_of<Method>()) + ")");
  const std::string transfer = transfer_name(s.transfer);
  if (!parse_transfer(transfer))
    throw InputError(where + ".transfer: unknown transfer '" + s.transfer + "' (expected " +
                     choices_text(names_of<Transfer>()) + ", with its parameter in parentheses)");
  if (transfer != s.transfer) {
    const std::string parameter =
        s.transfer.substr(transfer.size() + 1, s.transfer.size() - transfer.size() - 2);
    double value = 0;
    const auto [end, ec] =
        std::from_chars(parameter.data(), parameter.data() + parameter.size(), value);
    if (parameter.empty() || ec != std::errc() || end != parameter.data() + parameter.size() ||
        !std::isfinite(value))
      throw InputError(where + ".transfer: '" + s.transfer + "' has no number in parentheses");
  }
  if (!parse_update_order(s.update))
    throw InputError(where + ".update: unknown update '" + s.update + "' (expected " +
                     choices_text(names_of<UpdateOrder>()) + ")");
  s.cells = int_at(j, "cells", where);
  s.ppc = int_at(j, "ppc", where);
  s.courant = number_at(j, "courant", where);
  if (!(s.courant > 0)) throw InputError(where + ".courant: must be positive");
  if (!at(j, "courant_spectral", where).is_null())
    s.courant_spectral = number_at(j, "courant_spectral", where);
  const nlohmann::ordered_json& corners = at(j, "corners", where);
  const nlohmann::ordered_json& regions = at(j, "regions", where);
  if (!corners.is_array() || !regions.is_array())
    throw InputError(where + ": corners and regions must be arrays");
  for (std::size_t i = 0; i < corners.size(); ++i)
    s.corners.push_back(corner_from_json(corners[i], "corners[" + std::to_string(i) + "]"));
  for (std::size_t i = 0; i < regions.size(); ++i)
    s.regions.push_back(region_from_json(regions[i], "regions[" + std::to_string(i) + "]"));
  return s;
}

std::vector<CheckedSetting> checked_settings_of(const nlohmann::ordered_json& doc) {
  if (!doc.is_object() || !doc.contains("study") || !doc["study"].is_object() ||
      !doc["study"].contains("settings") || !doc["study"]["settings"].is_array())
    throw InputError("study.settings: missing (not the advice study's results)");
  std::vector<CheckedSetting> out;
  const auto& list = doc["study"]["settings"];
  for (std::size_t i = 0; i < list.size(); ++i) {
    try {
      out.push_back(checked_setting_from_json(list[i]));
    } catch (const InputError& e) {
      throw InputError("study.settings[" + std::to_string(i) + "]: " + e.what());
    }
  }
  return out;
}

std::string transfer_options(const std::string& transfer) {
  const std::string name = transfer_name(transfer);
  std::string text = "--transfer " + name;
  if (name == transfer) return text;
  const std::string parameter = transfer.substr(name.size() + 1, transfer.size() - name.size() - 2);
  const Transfer t = *parse_transfer(name);
  if (t == Transfer::fmpm) text += " --fmpm-order " + parameter;
  if (t == Transfer::xpic) text += " --xpic-order " + parameter;
  if (t == Transfer::blend) text += " --flip-fraction " + parameter;
  return text;
}

}  // namespace mpmstab
