#include "advice.hpp"

#include <algorithm>
#include <sstream>
#include <string_view>

#include "csv.hpp"
#include "key.hpp"
#include "report_util.hpp"

namespace mpmstab {

using ojson = nlohmann::ordered_json;

bool within_limit(const ojson& row, double uniform_limit, const AdviceRule& rule) {
  if (!has_number(row, "courant")) return false;
  const double limit =
      has_number(row, "courant_spectral") ? row["courant_spectral"].get<double>() : uniform_limit;
  return limit > 0 && row["courant"].get<double>() <= limit / rule.limit_margin;
}

bool meets_target(const ojson& row, double target, const AdviceRule& rule) {
  return outcome(row) == "stable" && has_number(row, "max_error_over_time") &&
         row["max_error_over_time"].get<double>() <= target / rule.error_margin;
}

bool candidate(const ojson& row, double target, const AdviceRule& rule) {
  return has_number(row, "courant_spectral") &&
         within_limit(row, row["courant_spectral"].get<double>(), rule) &&
         meets_target(row, target, rule);
}

std::vector<RunParams> confirming_runs(const RunParams& p, const AdviceRule& rule) {
  RunParams fine = p;
  fine.cells = p.cells * rule.refine;
  if (fine.stepping.policy == TimeStepPolicy::fixed) fine.dt = p.dt / rule.refine;
  fine.observe.error_over_time = true;
  RunParams jittered = p;
  jittered.layout.jitter = rule.jitter;
  jittered.observe.error_over_time = true;
  RunParams small = p;
  small.A = p.A / rule.amplitude_factor;
  small.observe.error_over_time = true;
  RunParams longer = p;
  longer.T = p.T * rule.length_factor;
  longer.observe.error_over_time = true;
  return {fine, jittered, small, longer};
}

Advice judge(const ojson& row, double target, const std::vector<ojson>& confirming,
             const AdviceRule& rule) {
  Advice a;
  a.row = &row;
  a.confirming = confirming;
  const double limit =
      has_number(row, "courant_spectral") ? row["courant_spectral"].get<double>() : 0;
  a.limit_ok = within_limit(row, limit, rule);
  a.error_ok = meets_target(row, target, rule);
  a.confirmed = confirming.size() == kConfirmingRuns;
  const double A = row["A"].get<double>();
  for (const auto& c : confirming) {
    const double scaled = target * c["A"].get<double>() / A;  // the same relative accuracy
    a.confirmed = a.confirmed && within_limit(c, limit, rule) && meets_target(c, scaled, rule);
  }
  return a;
}

std::string describe_rule(const AdviceRule& rule) {
  std::ostringstream s;
  s << "c dt/h at most the scheme's spectral limit / " << shortest(rule.limit_margin)
    << "; error over time (max over steps and particles) at most the target / "
    << shortest(rule.error_margin) << " in a stable run; the same two on a grid " << rule.refine
    << " times finer at the same c dt/h, on a layout jittered by " << shortest(rule.jitter)
    << " of the particle spacing, at an amplitude " << shortest(rule.amplitude_factor)
    << " times smaller (the target scaled with it) and on a run " << shortest(rule.length_factor)
    << " times as long";
  return s.str();
}

std::string describe_confirming(const ojson& row, const ojson& setting) {
  std::ostringstream s;
  auto differs = [&](const char* key) {
    return row.contains(key) && setting.contains(key) && row[key] != setting[key];
  };
  if (differs("cells")) s << row["cells"].get<int>() << " cells";
  if (differs("jitter")) s << "jitter " << shortest(row["jitter"].get<double>());
  if (differs("A")) s << "A = " << value_text(row["A"].get<double>());
  if (differs("T")) s << "T = " << value_text(row["T"].get<double>());
  s << ": ";
  if (outcome(row) == "stable" && has_number(row, "max_error_over_time")) {
    s << "error over time " << sci(row["max_error_over_time"].get<double>());
  } else {
    s << verdict(row);
  }
  if (has_number(row, "courant")) s << ", c dt/h " << shortest(row["courant"].get<double>());
  return s.str();
}

std::string describe_confirming(const Advice& a) {
  std::string s;
  for (const auto& c : a.confirming)
    s += (s.empty() ? "" : "; ") + describe_confirming(c, *a.row);
  return s;
}

namespace {

// The step parameter of a setting's policy: dt (fixed), cfl_factor (cfl) or safety.
const char* step_key(const ojson& row) {
  const std::string policy = row["policy"].get<std::string>();
  return policy == "fixed" ? "dt" : policy == "cfl" ? "cfl_factor" : "safety";
}

const char* step_symbol(const char* key) {
  return std::string_view(key) == "dt" ? "dt" : std::string_view(key) == "cfl_factor" ? "C" : "s";
}

// The runs of `scan` that are the setting but for its step parameter, and larger in it, in
// increasing order of it.
std::vector<const ojson*> larger_steps(const ojson& setting, const std::vector<ojson>& scan) {
  const char* key = step_key(setting);
  ojson same = setting_case(setting);
  same.erase(key);
  const double v = setting[key].get<double>();
  std::vector<const ojson*> out;
  for (const auto& r : scan) {
    if (!has_number(r, key) || r[key].get<double>() <= v) continue;
    ojson other = setting_case(r);
    other.erase(key);
    if (other == same) out.push_back(&r);
  }
  std::stable_sort(out.begin(), out.end(), [key](const ojson* a, const ojson* b) {
    return TotalLess()((*a)[key].get<double>(), (*b)[key].get<double>());
  });
  return out;
}

const ojson* first_failing(const std::vector<const ojson*>& larger) {
  for (const ojson* r : larger)
    if (outcome(*r) == "unstable" || outcome(*r) == "meaningless") return r;
  return nullptr;
}

}  // namespace

std::optional<double> margin_ratio(const ojson& setting, const std::vector<ojson>& scan) {
  const char* key = step_key(setting);
  const ojson* bad = first_failing(larger_steps(setting, scan));
  if (!bad) return std::nullopt;
  return (*bad)[key].get<double>() / setting[key].get<double>();
}

std::string margin_text(const ojson& setting, const std::vector<ojson>& scan) {
  const char* key = step_key(setting);
  const double v = setting[key].get<double>();
  const auto larger = larger_steps(setting, scan);
  if (larger.empty()) return "no larger step was run";
  const ojson* bad = first_failing(larger);
  std::ostringstream s;
  if (!bad) {
    const double top = (*larger.back())[key].get<double>();
    s << "no larger step of the scan fails (run up to " << step_symbol(key) << " = "
      << value_text(top) << ", " << ratio(top / v) << "x)";
    return s.str();
  }
  const double b = (*bad)[key].get<double>();
  s << "the first failing step of the scan: " << step_symbol(key) << " = " << value_text(b) << " ("
    << ratio(b / v) << "x), " << outcome(*bad);
  return s.str();
}

ojson setting_case(const ojson& row) {
  ojson c = ojson::object();
  for (const auto& name : parameter_names()) {
    if (row.contains(name) && !row[name].is_null()) c[name] = row[name];
  }
  return c;
}

ojson recommended_json(const Advice& a, double target) {
  const ojson& r = *a.row;
  return {{"target", target},
          {"case", setting_case(r)},
          {"courant", r["courant"]},
          {"courant_spectral", r["courant_spectral"]},
          {"max_error_over_time", r["max_error_over_time"]}};
}

Claim recommendations_claim(const std::vector<Advice>& recommended, double target,
                            const AdviceRule& rule) {
  int confirmed = 0;
  for (const auto& a : recommended)
    confirmed += a.recommended();
  Claim c = claim("recommended-" + sci(target, 1),
                  "Every setting recommended for an error of {target} keeps c dt/h at most its "
                  "spectral limit / {limit_margin} and its error over time at most the target / "
                  "{error_margin}, in its own run and in its confirming runs ({refine}x the "
                  "cells; jitter {jitter}; A / {amplitude}, the target likewise; {length}x T)",
                  "{confirmed} of {recommended} recommended settings pass every part of the rule");
  c.value("target", sci(target, 1))
      .value("limit_margin", shortest(rule.limit_margin))
      .value("error_margin", shortest(rule.error_margin))
      .count("refine", rule.refine)
      .value("jitter", shortest(rule.jitter))
      .value("amplitude", shortest(rule.amplitude_factor))
      .value("length", shortest(rule.length_factor))
      .count("confirmed", confirmed)
      .count("recommended", static_cast<long long>(recommended.size()));
  c.over(static_cast<long long>(recommended.size()));
  c.holds = confirmed == static_cast<int>(recommended.size());
  return c;
}

}  // namespace mpmstab
