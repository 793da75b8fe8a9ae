#include "spec.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "args.hpp"
#include "cache.hpp"
#include "files.hpp"
#include "scenes/validate.hpp"
#include "strict_json.hpp"

namespace mpmstab {

namespace {

using nlohmann::json;

std::string where(const std::filesystem::path& file, const std::string& key_path) {
  return key_path.empty() ? file.string() : file.string() + ": " + key_path;
}

// Keys a case (or the defaults object) may set; everything else is an error.
const std::vector<std::string> kCaseKeys = [] {
  std::vector<std::string> keys = parameter_names();
  keys.push_back("max_steps");
  keys.push_back("dt_inferred");
  keys.push_back("error_at");
  return keys;
}();
// What a variant's "set" may change: the run's parameters (a variant's cases keep their base
// case's dt_inferred, and error_at is a key of the variant itself).
const std::vector<std::string> kVariantSetKeys = [] {
  std::vector<std::string> keys = parameter_names();
  keys.push_back("max_steps");
  return keys;
}();
const std::vector<std::string> kVariantKeys = {"name",    "description", "set",
                                               "methods", "error_at",    "dt_at_least"};
const std::vector<std::string> kTopKeys = {
    "name",     "title", "description", "report",   "record",      "history_stride", "reference",
    "defaults", "cases", "cases_from",  "variants", "index_order", "check_budget",   "tier"};
// A spec named by cases_from is read whole; larger files are refused rather than read.
constexpr std::uintmax_t kMaxSpecBytes = 4u << 20;
const std::vector<std::string> kRecordValues = {"error_over_time", "dt_stable",   "crossings",
                                                "history",         "final_state", "spectral",
                                                "energy",          "error_l2",    "tip"};

class Reader {
 public:
  explicit Reader(std::filesystem::path file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& key_path, const std::string& message) const {
    throw SpecError(file_, key_path, message);
  }

  void only_known_keys(const json& object, const std::string& path,
                       const std::vector<std::string>& known) const {
    for (const auto& [key, value] : object.items()) {
      if (std::find(known.begin(), known.end(), key) != known.end()) continue;
      std::string message = "unknown key '" + key + "'";
      if (auto guess = cli::nearest(key, known)) message += " (did you mean '" + *guess + "'?)";
      fail(path.empty() ? key : path + "." + key, message);
    }
  }

  std::string string_at(const json& v, const std::string& path) const {
    if (!v.is_string()) fail(path, "must be a string, got " + std::string(v.type_name()));
    return v.get<std::string>();
  }
  double number_at(const json& v, const std::string& path) const {
    if (!v.is_number()) fail(path, "must be a number, got " + std::string(v.type_name()));
    return v.get<double>();
  }
  std::int64_t integer_at(const json& v, const std::string& path) const {
    if (!v.is_number_integer()) {
      fail(path,
           "must be an integer, got " + (v.is_number() ? v.dump() : std::string(v.type_name())));
    }
    if (v.is_number_unsigned() && v.get<std::uint64_t>() > std::uint64_t(INT64_MAX)) {
      fail(path, "is too large");
    }
    return v.get<std::int64_t>();
  }
  int int_at(const json& v, const std::string& path) const {
    const std::int64_t i = integer_at(v, path);
    if (i < INT32_MIN || i > INT32_MAX) fail(path, "is out of range");
    return static_cast<int>(i);
  }
  bool bool_at(const json& v, const std::string& path) const {
    if (!v.is_boolean()) fail(path, "must be true or false, got " + std::string(v.type_name()));
    return v.get<bool>();
  }
  template <class Enum>
  Enum choice_at(const json& v, const std::string& path,
                 std::optional<Enum> (*parse)(std::string_view), const std::string& choices) const {
    const std::string s = string_at(v, path);
    if (auto e = parse(s)) return *e;
    fail(path, "unknown value '" + s + "' (expected " + choices + ")");
  }
  // A value of one of params.hpp's enums, refused with every name its table knows.
  template <class Enum>
  Enum choice_at(const json& v, const std::string& path,
                 std::optional<Enum> (*parse)(std::string_view)) const {
    return choice_at(v, path, parse, choices_text(names_of<Enum>()));
  }

  // Sets one parameter from a case or defaults entry.
  void set(RunParams& p, CaseSpec& c, const std::string& key, const json& v,
           const std::string& path) const {
    if (key == "method")
      p.method = choice_at(v, path, parse_method);
    else if (key == "E")
      p.E = number_at(v, path);
    else if (key == "A")
      p.A = number_at(v, path);
    else if (key == "dt")
      p.dt = number_at(v, path);
    else if (key == "T")
      p.T = number_at(v, path);
    else if (key == "cells")
      p.cells = int_at(v, path);
    else if (key == "ppc")
      p.ppc = int_at(v, path);
    else if (key == "bc")
      p.bc = choice_at(v, path, parse_boundary);
    else if (key == "position_update")
      p.position_update = choice_at(v, path, parse_position_update);
    else if (key == "scene")
      p.scene = choice_at(v, path, parse_scene);
    else if (key == "walls")
      p.walls = choice_at(v, path, parse_walls);
    else if (key == "transfer")
      p.transfer = choice_at(v, path, parse_transfer);
    else if (key == "flip_fraction")
      p.flip_fraction = number_at(v, path);
    else if (key == "xpic_order")
      p.xpic_order = int_at(v, path);
    else if (key == "fmpm_order")
      p.fmpm_order = int_at(v, path);
    else if (key == "shift")
      p.layout.shift = number_at(v, path);
    else if (key == "jitter")
      p.layout.jitter = number_at(v, path);
    else if (key == "update")
      p.update = choice_at(v, path, parse_update_order);
    else if (key == "body_force_time")
      p.body_force_time = choice_at(v, path, parse_body_force_time);
    else if (key == "start")
      p.start = choice_at(v, path, parse_velocity_start);
    else if (key == "body_start")
      p.body_start = number_at(v, path);
    else if (key == "body_length")
      p.body_length = number_at(v, path);
    else if (key == "small_mass")
      p.small_mass = choice_at(v, path, parse_small_mass);
    else if (key == "small_mass_fraction")
      p.small_mass_fraction = number_at(v, path);
    else if (key == "tip_load")
      p.tip_load = number_at(v, path);
    else if (key == "dt_stable_sigma")
      p.stable.sigma = choice_at(v, path, parse_stress_scaling);
    else if (key == "dt_stable_vnorm")
      p.stable.vnorm = choice_at(v, path, parse_velocity_norm);
    else if (key == "max_steps")
      p.max_steps = integer_at(v, path);
    else if (key == "policy")
      p.stepping.policy = choice_at(v, path, parse_time_step_policy);
    else if (key == "cfl_factor")
      p.stepping.cfl_factor = number_at(v, path);
    else if (key == "safety")
      p.stepping.safety = number_at(v, path);
    else if (key == "dt_inferred")
      c.dt_inferred = bool_at(v, path);
    else if (key == "error_at")
      c.error_at = choice_at(v, path, parse_error_at, "T or max_over_time");
  }

 private:
  std::filesystem::path file_;
};

json parse_text(std::string_view text, const std::filesystem::path& file) {
  if (text.find_first_not_of(" \t\r\n") == std::string_view::npos) {
    throw SpecError(file, "", "is empty");
  }
  try {
    return parse_json_strict<json>(text, file);
  } catch (const InputError& e) {
    throw SpecError(file, "", e.detail());
  }
}

}  // namespace

SpecError::SpecError(const std::filesystem::path& file, const std::string& key_path,
                     const std::string& message)
    : std::runtime_error(where(file, key_path) + ": " + message) {}

std::string_view to_string(Tier t) {
  return t == Tier::paper ? "paper" : "studies";
}

std::string_view to_string(ErrorAt e) {
  return e == ErrorAt::T ? "T" : "max_over_time";
}

std::optional<ErrorAt> parse_error_at(std::string_view s) {
  if (s == "T") return ErrorAt::T;
  if (s == "max_over_time") return ErrorAt::max_over_time;
  return std::nullopt;
}

namespace {

std::string read_whole(const std::filesystem::path& file) {
  try {
    return read_input(file, kMaxSpecBytes);
  } catch (const InputError& e) {
    throw SpecError(file, "", e.detail());
  }
}

Spec parse(std::string_view text, const std::filesystem::path& file, bool named_by_cases_from);

// The cases of the spec named by `cases_from` (relative to `file`), validated as a spec of its
// own: regular file, not too large, itself without cases_from or variants.
Spec cases_from_spec(const Reader& r, const std::filesystem::path& file, const std::string& name) {
  const std::filesystem::path base = file.parent_path() / name;
  std::error_code ec;
  if (name.empty()) r.fail("cases_from", "must name a spec file, got an empty string");
  const auto self = std::filesystem::weakly_canonical(file, ec);
  const auto other = std::filesystem::weakly_canonical(base, ec);
  if (!ec && !self.empty() && self == other) r.fail("cases_from", "names this spec itself");
  try {
    return parse(read_whole(base), base, true);
  } catch (const SpecError& e) {
    r.fail("cases_from", e.what());
  }
}

// ---------------------------------------------------------------------------------------------
// Variants: one block of cases per variant, each a base case with the variant's settings.

// A variant's own keys, before it is applied to any case.
struct VariantDecl {
  VariantSpec spec;
  json set = json::object();
  std::optional<ErrorAt> error_at;
};

json variant_settings(const Reader& r, const json& v, const std::string& at) {
  if (!v.contains("set")) return json::object();
  const json& set = v["set"];
  if (!set.is_object()) r.fail(at + ".set", "must be an object");
  if (set.contains("error_at")) {
    r.fail(at + ".set.error_at", "is a key of the variant itself: " + at + ".error_at");
  }
  for (const char* key : {"E", "A", "dt"}) {
    if (set.contains(key)) {
      r.fail(at + ".set." + key,
             "a variant keeps each cell's E, A and dt (it is compared with the same paper "
             "cell)");
    }
  }
  if (set.contains("dt_inferred")) {
    r.fail(at + ".set.dt_inferred", "a variant's cases keep their base case's dt_inferred");
  }
  r.only_known_keys(set, at + ".set", kVariantSetKeys);
  return set;
}

std::vector<Method> variant_methods(const Reader& r, const json& v, const std::string& at) {
  std::vector<Method> methods;
  if (!v.contains("methods")) return methods;
  const json& m = v["methods"];
  if (!m.is_array() || m.empty()) r.fail(at + ".methods", "must be a non-empty array");
  for (std::size_t k = 0; k < m.size(); ++k) {
    const std::string mp = at + ".methods[" + std::to_string(k) + "]";
    const Method method = r.choice_at(m[k], mp, parse_method);
    if (std::find(methods.begin(), methods.end(), method) != methods.end()) {
      r.fail(mp, "repeats '" + std::string(to_string(method)) + "'");
    }
    methods.push_back(method);
  }
  return methods;
}

VariantDecl read_variant(const Reader& r, const json& v, const std::string& at) {
  if (!v.is_object()) r.fail(at, "must be an object");
  r.only_known_keys(v, at, kVariantKeys);
  if (!v.contains("name")) r.fail(at + ".name", "is required");
  VariantDecl d;
  VariantSpec& vs = d.spec;
  vs.name = r.string_at(v["name"], at + ".name");
  if (vs.name.empty() ||
      vs.name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_+.-") != std::string::npos) {
    r.fail(at + ".name", "must be a non-empty name of [a-z0-9_+.-], got '" + vs.name + "'");
  }
  if (v.contains("description"))
    vs.description = r.string_at(v["description"], at + ".description");
  d.set = variant_settings(r, v, at);
  for (const auto& [key, value] : d.set.items()) {
    vs.change += (vs.change.empty() ? "" : ", ") + key + " = " +
                 (value.is_string() ? value.get<std::string>() : value.dump());
    if (key != "flip_fraction" && key != "xpic_order" && key != "fmpm_order") ++vs.changes;
  }
  if (v.contains("error_at")) {
    d.error_at = r.choice_at(v["error_at"], at + ".error_at", parse_error_at, "T or max_over_time");
    vs.change += std::string(vs.change.empty() ? "" : ", ") +
                 "error_at = " + std::string(to_string(*d.error_at));
    ++vs.changes;
  }
  if (vs.change.empty()) {
    vs.change = "none";
    vs.baseline = true;
  }
  vs.methods = variant_methods(r, v, at);
  if (v.contains("dt_at_least")) {
    const double dt = r.number_at(v["dt_at_least"], at + ".dt_at_least");
    if (!(dt > 0) || !std::isfinite(dt)) r.fail(at + ".dt_at_least", "must be a positive number");
    if (vs.baseline) r.fail(at + ".dt_at_least", "the default variant runs every cell");
    vs.dt_at_least = dt;
    std::ostringstream only;
    only << "; only the cells with dt >= " << dt;
    vs.change += only.str();
  }
  return d;
}

// Appends the variant's cases (its settings applied to every base case of its methods).
void apply_variant(const Reader& r, VariantDecl& d, const std::string& at,
                   const std::vector<CaseSpec>& base, Spec& spec) {
  VariantSpec& vs = d.spec;
  vs.first_case = spec.cases.size();
  std::map<std::string, std::size_t> seen;  // canonical parameters -> base case index
  for (std::size_t i = 0; i < base.size(); ++i) {
    const CaseSpec& b = base[i];
    if (!vs.methods.empty() &&
        std::find(vs.methods.begin(), vs.methods.end(), b.paper_method) == vs.methods.end()) {
      continue;
    }
    if (vs.dt_at_least) {
      if (b.params.stepping.policy != TimeStepPolicy::fixed) {
        r.fail(at + ".dt_at_least", "needs base cases with a fixed dt; base case " +
                                        std::to_string(i) + " chooses its own");
      }
      if (b.params.dt < *vs.dt_at_least) continue;
    }
    CaseSpec cs = b;
    cs.variant = vs.name;
    if (d.error_at) cs.error_at = *d.error_at;
    for (const auto& [key, value] : d.set.items())
      r.set(cs.params, cs, key, value, at + ".set." + key);
    for (const auto& [key, value] : d.set.items()) {
      if (const auto issue = check_given(cs.params, key)) {
        r.fail(at + ".set." + key, "with base case " + std::to_string(i) + ": " + issue->message);
      }
    }
    const auto issues = validate(cs.params);
    if (!issues.empty()) {
      const auto& issue = issues.front();
      r.fail(d.set.contains(issue.key) ? at + ".set." + issue.key : at,
             "with base case " + std::to_string(i) + ": " + issue.key + " " + issue.message);
    }
    if (const auto [it, inserted] = seen.emplace(canonical_parameters(cs.params), i); !inserted) {
      r.fail(at, "makes base cases " + std::to_string(it->second) + " and " + std::to_string(i) +
                     " the same run");
    }
    spec.cases.push_back(std::move(cs));
  }
  vs.cases = spec.cases.size() - vs.first_case;
  if (vs.cases == 0) {
    r.fail(at + (vs.dt_at_least ? ".dt_at_least" : ".methods"), "matches none of the base cases");
  }
}

// Applies the variants of `doc` to the base cases: spec.cases becomes every variant's cases.
void expand_variants(const Reader& r, const json& variants, const std::vector<CaseSpec>& base,
                     Spec& spec) {
  if (!variants.is_array() || variants.empty()) {
    r.fail("variants", "must be a non-empty array of variants");
  }
  std::set<std::string> names;
  bool has_default = false;
  for (std::size_t j = 0; j < variants.size(); ++j) {
    const std::string at = "variants[" + std::to_string(j) + "]";
    VariantDecl d = read_variant(r, variants[j], at);
    if (!names.insert(d.spec.name).second) r.fail(at + ".name", "repeats '" + d.spec.name + "'");
    has_default = has_default || d.spec.baseline;
    apply_variant(r, d, at, base, spec);
    spec.variants.push_back(std::move(d.spec));
  }
  if (!has_default) {
    r.fail("variants",
           "needs one variant that changes nothing (the default, which the others "
           "are read against)");
  }
}

// ---------------------------------------------------------------------------------------------
// The spec's parts, in the order parse() reads them.

// Files of the results folder that no experiment's name may claim: those other commands write
// (performance.md, benchmark_step.json, timings.json, the cache folder), the comparison's files
// (written under that name whatever its spec is called), and <name>_data and <name>_follow_up,
// which would collide with the figure data or the follow-up runs of the experiment <name>.
void check_reserved_name(const Reader& r, const std::string& name, const std::string& report) {
  static const std::vector<std::string> reserved = {"performance", "benchmark_step", "timings",
                                                    "cache", "readme"};
  const bool taken = std::find(reserved.begin(), reserved.end(), name) != reserved.end() ||
                     (name == "comparison" && report != "comparison");
  const auto ends_with = [&](const std::string& suffix) {
    return name.size() > suffix.size() &&
           name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  const bool data = ends_with("_data"), follow_up = ends_with("_follow_up");
  if (taken || data || follow_up) {
    r.fail("name", "'" + name + "' is reserved: " +
                       (data        ? "<name>_data.csv is the figure data of the experiment <name>"
                        : follow_up ? "<name>_follow_up.csv holds the follow-up runs of the "
                                      "experiment <name>"
                                    : "another command writes a file of that name in the results "
                                      "folder"));
  }
}

// The keys that say what the spec is: name, title, description and the study ("report"), and
// which of cases, cases_from and variants it may have.
void read_header(const Reader& r, const json& doc, bool named_by_cases_from, Spec& spec) {
  for (const char* key : {"name", "report"}) {
    if (!doc.contains(key)) r.fail(key, "is required");
  }
  if (named_by_cases_from) {
    for (const char* key : {"cases_from", "variants"}) {
      if (doc.contains(key)) {
        r.fail(key,
               "a spec named by cases_from must list its own cases (no nested cases_from, "
               "no variants)");
      }
    }
  }
  spec.name = r.string_at(doc["name"], "name");
  if (spec.name.empty() ||
      spec.name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") != std::string::npos) {
    r.fail("name", "must be a non-empty file name of [a-z0-9_-], got '" + spec.name + "'");
  }
  check_reserved_name(r, spec.name, r.string_at(doc["report"], "report"));
  if (doc.contains("title")) spec.title = r.string_at(doc["title"], "title");
  if (doc.contains("description")) {
    spec.description = r.string_at(doc["description"], "description");
  }
  const std::string report = r.string_at(doc["report"], "report");
  spec.study = find_study(report);
  if (!spec.study) {
    std::vector<std::string> names;
    std::string expected;
    for (const Study* s : all_studies()) {
      expected += (expected.empty() ? "" : ", ") + s->name;
      names.push_back(s->name);
    }
    std::string message = "unknown value '" + report + "' (expected one of " + expected + ")";
    if (auto guess = cli::nearest(report, names)) message += " (did you mean '" + *guess + "'?)";
    r.fail("report", message);
  }
  if (doc.contains("variants") && !spec.study->takes_variants) {
    r.fail("variants", "only a variants report takes variants");
  }
  if (spec.study->takes_variants && !doc.contains("variants")) {
    r.fail("variants", "is required for a " + report + " report");
  }
}

// Where the experiment is listed, its tier, and the budget of its fast subset in make check.
void read_listing(const Reader& r, const json& doc, Spec& spec) {
  if (doc.contains("tier")) {
    const std::string tier = r.string_at(doc["tier"], "tier");
    if (tier == "paper") {
      spec.tier = Tier::paper;
    } else if (tier != "studies") {
      r.fail("tier", "unknown value '" + tier + "' (expected paper or studies)");
    }
  }
  if (doc.contains("index_order")) {
    spec.index_order = r.number_at(doc["index_order"], "index_order");
    if (!std::isfinite(spec.index_order)) r.fail("index_order", "must be finite");
  }
  if (doc.contains("check_budget")) {
    const double b = r.number_at(doc["check_budget"], "check_budget");
    if (!(b > 0) || !std::isfinite(b)) r.fail("check_budget", "must be a positive number");
    spec.check_budget = b;
  }
}

// The experiments the study reads, as specs beside this one: a required one must exist, another
// is read when it does (and then its results must be there when the report is written).
void resolve_inputs(const Reader& r, const std::filesystem::path& file, Spec& spec) {
  for (const auto& [name, required] : spec.study->inputs) {
    const auto path = file.parent_path() / (name + ".json");
    std::error_code ec;
    if (std::filesystem::is_regular_file(path, ec)) {
      spec.inputs.push_back({name, path});
    } else if (required) {
      r.fail("report", "the " + spec.study->name + " study reads the results of '" + name +
                           "', whose spec " + path.string() + " does not exist");
    }
  }
}

// What every case records: nothing beyond its verdict and final error unless listed.
Observe read_observe(const Reader& r, const json& doc) {
  Observe observe;
  observe.dt_stable = observe.crossings = false;
  // Always on: every record's outcome (meaningless or stable) is read from the error over time.
  observe.error_over_time = true;
  if (doc.contains("record")) {
    const json& rec = doc["record"];
    if (!rec.is_array()) r.fail("record", "must be an array of strings");
    for (std::size_t i = 0; i < rec.size(); ++i) {
      const std::string path = "record[" + std::to_string(i) + "]";
      const std::string what = r.string_at(rec[i], path);
      if (what == "error_over_time")
        observe.error_over_time = true;
      else if (what == "dt_stable")
        observe.dt_stable = true;
      else if (what == "crossings")
        observe.crossings = true;
      else if (what == "history")
        observe.history = true;
      else if (what == "final_state")
        observe.final_state = true;
      else if (what == "spectral")
        observe.spectral = true;
      else if (what == "energy")
        observe.energy = true;
      else if (what == "error_l2")
        observe.error_l2 = true;
      else if (what == "tip")
        observe.tip = true;
      else {
        std::string message = "unknown value '" + what + "'";
        if (auto guess = cli::nearest(what, kRecordValues))
          message += " (did you mean '" + *guess + "'?)";
        r.fail(path, message);
      }
    }
  }
  if (doc.contains("history_stride")) {
    observe.history_stride = r.integer_at(doc["history_stride"], "history_stride");
  }
  return observe;
}

// The base cases of cases_from as their spec defines them; a "record" here replaces the base's.
std::vector<CaseSpec> cases_of_base(const Reader& r, const json& doc, const Spec& base,
                                    const Observe& observe) {
  std::vector<CaseSpec> cases = base.cases;
  if (doc.contains("record") || doc.contains("history_stride")) {
    for (auto& c : cases) {
      c.params.observe = observe;
      const auto issues = validate(c.params);
      if (!issues.empty()) r.fail(issues.front().key, issues.front().message);
    }
  }
  return cases;
}

// One entry of "cases", over the defaults.
CaseSpec read_case(const Reader& r, const json& defaults, const json& c, const std::string& at,
                   const Observe& observe, const Study& study) {
  if (!c.is_object()) r.fail(at, "must be an object");
  r.only_known_keys(c, at, kCaseKeys);
  CaseSpec cs;
  RunParams& p = cs.params;
  p.observe = observe;
  // The source of each key, for error messages: the case itself or the defaults.
  std::map<std::string, std::string> source;
  for (const auto& [key, value] : defaults.items()) {
    r.set(p, cs, key, value, "defaults." + key);
    source[key] = "defaults." + key;
  }
  for (const auto& [key, value] : c.items()) {
    r.set(p, cs, key, value, at + "." + key);
    source[key] = at + "." + key;
  }
  for (const char* key : {"method", "E", "A"}) {
    if (!source.count(key)) r.fail(at + "." + key, "is required (in the case or in defaults)");
  }
  if (study.work == CaseWork::edge_search) {
    if (source.count("dt")) r.fail(source["dt"], "an edge experiment searches dt: remove it");
    p.dt = p.T;  // a placeholder that validates; the search sets dt
  } else if (p.stepping.policy == TimeStepPolicy::fixed && !source.count("dt")) {
    r.fail(at + ".dt", "is required with the fixed policy (in the case or in defaults)");
  }
  for (const auto& key : conditional_parameters()) {
    if (!source.count(key)) continue;  // (an edge spec's dt was refused above)
    if (const auto issue = check_given(p, key)) r.fail(source[key], issue->message);
  }
  const auto issues = validate(p);
  if (!issues.empty()) {
    const auto& issue = issues.front();
    const auto it = source.find(issue.key);
    r.fail(it != source.end() ? it->second : at + "." + issue.key, issue.message);
  }
  cs.paper_method = p.method;
  return cs;
}

std::vector<CaseSpec> read_cases(const Reader& r, const json& doc, const Observe& observe,
                                 const Study& study) {
  json defaults = json::object();
  if (doc.contains("defaults")) {
    defaults = doc["defaults"];
    if (!defaults.is_object()) r.fail("defaults", "must be an object");
    r.only_known_keys(defaults, "defaults", kCaseKeys);
  }
  const json& list = doc["cases"];
  if (!list.is_array() || list.empty()) r.fail("cases", "must be a non-empty array of cases");
  if (study.one_case && list.size() != 1) {
    r.fail("cases", "a " + study.name + " experiment has exactly one case");
  }
  std::vector<CaseSpec> cases;
  std::map<std::string, std::size_t> seen;  // canonical parameters -> first case index
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string at = "cases[" + std::to_string(i) + "]";
    cases.push_back(read_case(r, defaults, list[i], at, observe, study));
    if (const auto [it, inserted] = seen.emplace(canonical_parameters(cases.back().params), i);
        !inserted) {
      r.fail(at, "repeats cases[" + std::to_string(it->second) + "]");
    }
  }
  return cases;
}

// A derived study has no cases of its own: it may name its paper table, nothing else.
Spec parse_derived(const Reader& r, const json& doc, Spec spec) {
  for (const char* key :
       {"cases", "cases_from", "defaults", "record", "history_stride", "variants"}) {
    if (doc.contains(key)) {
      r.fail(key, "a " + spec.study->name + " study has no cases: it reads its inputs");
    }
  }
  return spec;
}

Spec parse(std::string_view text, const std::filesystem::path& file, bool named_by_cases_from) {
  const Reader r(file);
  const json doc = parse_text(text, file);
  if (!doc.is_object()) r.fail("", "must be a JSON object, got " + std::string(doc.type_name()));
  r.only_known_keys(doc, "", kTopKeys);

  Spec spec;
  spec.path = file;
  read_header(r, doc, named_by_cases_from, spec);
  read_listing(r, doc, spec);
  const Study& study = *spec.study;
  resolve_inputs(r, file, spec);
  if (doc.contains("reference")) {
    spec.reference = file.parent_path() / r.string_at(doc["reference"], "reference");
  }
  if (!study.has_cases) return parse_derived(r, doc, std::move(spec));

  const bool from = doc.contains("cases_from");
  if (from && doc.contains("cases")) r.fail("cases", "cases and cases_from exclude each other");
  if (from && doc.contains("defaults")) {
    r.fail("defaults", "cases_from takes the cases with their defaults; change them in a variant");
  }
  if (!from && !doc.contains("cases")) r.fail("cases", "is required");
  // The base spec of cases_from, read first: its reference and record are the defaults here.
  Spec base;
  if (from) {
    base = cases_from_spec(r, file, r.string_at(doc["cases_from"], "cases_from"));
    if (base.study->work == CaseWork::edge_search) {
      r.fail("cases_from", "an edge experiment's cases have no dt (its search sets it)");
    }
    spec.cases_from = base.path;
    if (!doc.contains("reference")) spec.reference = base.reference;
  }
  if (study.needs_reference && spec.reference.empty()) {
    r.fail("reference", "is required for a " + study.name + " report");
  }

  const Observe observe = read_observe(r, doc);
  std::vector<CaseSpec> cases =
      from ? cases_of_base(r, doc, base, observe) : read_cases(r, doc, observe, study);
  if (doc.contains("variants")) {
    expand_variants(r, doc["variants"], cases, spec);
  } else {
    spec.cases = std::move(cases);
  }
  if (study.one_case && spec.cases.size() != 1) {
    r.fail("cases_from", "a " + study.name + " experiment has exactly one case");
  }
  return spec;
}

}  // namespace

Spec load_spec(const std::filesystem::path& file) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) throw SpecError(file, "", "is a directory");
  return parse_spec(read_whole(file), file);
}

Spec parse_spec(std::string_view text, const std::filesystem::path& file) {
  return parse(text, file, false);
}

}  // namespace mpmstab
