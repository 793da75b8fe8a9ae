#include "spec.hpp"

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "args.hpp"
#include "cache.hpp"

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
  return keys;
}();
const std::vector<std::string> kTopKeys = {"name",      "title",    "description",
                                           "report",    "record",   "history_stride",
                                           "reference", "defaults", "cases"};
const std::vector<std::string> kRecordValues = {"error_over_time", "dt_stable", "crossings",
                                                "history", "final_state"};

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
                 std::optional<Enum> (*parse)(std::string_view), const char* choices) const {
    const std::string s = string_at(v, path);
    if (auto e = parse(s)) return *e;
    fail(path, "unknown value '" + s + "' (expected " + choices + ")");
  }

  // Sets one parameter from a case or defaults entry.
  void set(RunParams& p, CaseSpec& c, const std::string& key, const json& v,
           const std::string& path) const {
    if (key == "method")
      p.method = choice_at(v, path, parse_method, "gimp, cpgimp or mpm");
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
      p.bc = choice_at(v, path, parse_boundary, "dirichlet or periodic");
    else if (key == "position_update")
      p.position_update = choice_at(v, path, parse_position_update, "grid or particle");
    else if (key == "scene")
      p.scene = choice_at(v, path, parse_scene, "bar or steffen");
    else if (key == "walls")
      p.walls = choice_at(v, path, parse_walls, "clip or ghost");
    else if (key == "transfer")
      p.transfer = choice_at(v, path, parse_transfer, "flip, pic or blend");
    else if (key == "flip_fraction")
      p.flip_fraction = number_at(v, path);
    else if (key == "update")
      p.update = choice_at(v, path, parse_update_order, "usl, usf or musl");
    else if (key == "body_force_time")
      p.body_force_time = choice_at(v, path, parse_body_force_time, "start or end");
    else if (key == "dt_stable_sigma")
      p.stable.sigma = choice_at(v, path, parse_stress_scaling, "scaled or raw");
    else if (key == "dt_stable_vnorm")
      p.stable.vnorm = choice_at(v, path, parse_velocity_norm, "l2 or max");
    else if (key == "max_steps")
      p.max_steps = integer_at(v, path);
    else if (key == "policy")
      p.stepping.policy = choice_at(v, path, parse_time_step_policy, "fixed, cfl, adaptive or min");
    else if (key == "cfl_factor")
      p.stepping.cfl_factor = number_at(v, path);
    else if (key == "safety")
      p.stepping.safety = number_at(v, path);
    else if (key == "dt_inferred")
      c.dt_inferred = bool_at(v, path);
  }

 private:
  std::filesystem::path file_;
};

json parse_text(std::string_view text, const std::filesystem::path& file) {
  if (text.find_first_not_of(" \t\r\n") == std::string_view::npos) {
    throw SpecError(file, "", "is empty");
  }
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    // Line and column of the byte where parsing stopped.
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i + 1 < e.byte && i < text.size(); ++i) {
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    std::string what = e.what();
    if (const auto at = what.find("syntax error"); at != std::string::npos) what = what.substr(at);
    throw SpecError(file, "",
                    "malformed JSON at line " + std::to_string(line) + ", column " +
                        std::to_string(column) + ": " + what);
  } catch (const json::exception& e) {
    // For example a number that overflows a double ("1e999").
    std::string what = e.what();
    if (const auto at = what.find("] "); at != std::string::npos) what = what.substr(at + 2);
    throw SpecError(file, "", "malformed JSON: " + what);
  }
}

}  // namespace

SpecError::SpecError(const std::filesystem::path& file, const std::string& key_path,
                     const std::string& message)
    : std::runtime_error(where(file, key_path) + ": " + message) {}

std::string_view to_string(ReportKind k) {
  switch (k) {
    case ReportKind::table1:
      return "table1";
    case ReportKind::table2:
      return "table2";
    case ReportKind::figure:
      return "figure";
    case ReportKind::cases:
      return "cases";
    case ReportKind::edge:
      return "edge";
    case ReportKind::tradeoff:
      return "tradeoff";
    case ReportKind::extremes:
      return "extremes";
  }
  return "?";
}

Spec load_spec(const std::filesystem::path& file) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) throw SpecError(file, "", "is a directory");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SpecError(file, "", "cannot be read");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_spec(buffer.str(), file);
}

Spec parse_spec(std::string_view text, const std::filesystem::path& file) {
  const Reader r(file);
  const json doc = parse_text(text, file);
  if (!doc.is_object()) r.fail("", "must be a JSON object, got " + std::string(doc.type_name()));
  r.only_known_keys(doc, "", kTopKeys);

  Spec spec;
  spec.path = file;
  for (const char* key : {"name", "report", "cases"}) {
    if (!doc.contains(key)) r.fail(key, "is required");
  }
  spec.name = r.string_at(doc["name"], "name");
  if (spec.name.empty() ||
      spec.name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") != std::string::npos) {
    r.fail("name", "must be a non-empty file name of [a-z0-9_-], got '" + spec.name + "'");
  }
  if (doc.contains("title")) spec.title = r.string_at(doc["title"], "title");
  if (doc.contains("description")) {
    spec.description = r.string_at(doc["description"], "description");
  }
  const std::string report = r.string_at(doc["report"], "report");
  bool known = false;
  for (ReportKind k :
       {ReportKind::table1, ReportKind::table2, ReportKind::figure, ReportKind::cases,
        ReportKind::edge, ReportKind::tradeoff, ReportKind::extremes}) {
    if (report == to_string(k)) {
      spec.report = k;
      known = true;
    }
  }
  if (!known) {
    r.fail("report", "unknown value '" + report +
                         "' (expected table1, table2, figure, cases, edge, tradeoff or extremes)");
  }
  if (doc.contains("reference")) {
    spec.reference = file.parent_path() / r.string_at(doc["reference"], "reference");
  }
  if ((spec.report == ReportKind::table1 || spec.report == ReportKind::table2) &&
      spec.reference.empty()) {
    r.fail("reference", "is required for a " + report + " report");
  }

  // What every case records: nothing beyond its verdict and final error unless listed.
  Observe observe;
  observe.error_over_time = observe.dt_stable = observe.crossings = false;
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

  json defaults = json::object();
  if (doc.contains("defaults")) {
    defaults = doc["defaults"];
    if (!defaults.is_object()) r.fail("defaults", "must be an object");
    r.only_known_keys(defaults, "defaults", kCaseKeys);
  }
  const json& cases = doc["cases"];
  if (!cases.is_array() || cases.empty()) r.fail("cases", "must be a non-empty array of cases");
  if (spec.report == ReportKind::figure && cases.size() != 1) {
    r.fail("cases", "a figure experiment has exactly one case");
  }

  std::map<std::string, std::size_t> seen;  // canonical parameters -> first case index
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::string base = "cases[" + std::to_string(i) + "]";
    const json& c = cases[i];
    if (!c.is_object()) r.fail(base, "must be an object");
    r.only_known_keys(c, base, kCaseKeys);
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
      r.set(p, cs, key, value, base + "." + key);
      source[key] = base + "." + key;
    }
    for (const char* key : {"method", "E", "A"}) {
      if (!source.count(key)) r.fail(base + "." + key, "is required (in the case or in defaults)");
    }
    if (spec.report == ReportKind::edge) {
      if (source.count("dt")) r.fail(source["dt"], "an edge experiment searches dt: remove it");
      p.dt = p.T;  // a placeholder that validates; the search sets dt
    } else if (p.stepping.policy == TimeStepPolicy::fixed && !source.count("dt")) {
      r.fail(base + ".dt", "is required with the fixed policy (in the case or in defaults)");
    }
    const auto issues = validate(p);
    if (!issues.empty()) {
      const auto& issue = issues.front();
      const auto it = source.find(issue.key);
      r.fail(it != source.end() ? it->second : base + "." + issue.key, issue.message);
    }
    if (const auto [it, inserted] = seen.emplace(canonical_parameters(p), i); !inserted) {
      r.fail(base, "repeats cases[" + std::to_string(it->second) + "]");
    }
    spec.cases.push_back(cs);
  }
  return spec;
}

}  // namespace mpmstab
