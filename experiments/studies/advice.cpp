#include "advice.hpp"

#include <sstream>

#include "csv.hpp"
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
  return {fine, jittered};
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
  a.confirmed = !confirming.empty();
  for (const auto& c : confirming)
    a.confirmed = a.confirmed && within_limit(c, limit, rule) && meets_target(c, target, rule);
  return a;
}

std::string describe_rule(const AdviceRule& rule) {
  std::ostringstream s;
  s << "c dt/h at most the scheme's spectral limit / " << shortest(rule.limit_margin)
    << "; error over time (max over steps and particles) at most the target / "
    << shortest(rule.error_margin) << " in a stable run; the same two on a grid " << rule.refine
    << " times finer at the same c dt/h and on a layout jittered by " << shortest(rule.jitter)
    << " of the particle spacing";
  return s.str();
}

std::string describe_confirming(const ojson& row) {
  std::ostringstream s;
  s << row["cells"].get<int>() << " cells";
  if (has_number(row, "jitter") && row["jitter"].get<double>() > 0)
    s << ", jitter " << shortest(row["jitter"].get<double>());
  s << ": ";
  if (outcome(row) == "stable" && has_number(row, "max_error_over_time")) {
    s << "error over time " << sci(row["max_error_over_time"].get<double>());
  } else {
    s << verdict(row);
  }
  if (has_number(row, "courant")) s << ", c dt/h " << shortest(row["courant"].get<double>());
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
                  "cells; jitter {jitter})",
                  "{confirmed} of {recommended} recommended settings pass every part of the rule");
  c.value("target", sci(target, 1))
      .value("limit_margin", shortest(rule.limit_margin))
      .value("error_margin", shortest(rule.error_margin))
      .count("refine", rule.refine)
      .value("jitter", shortest(rule.jitter))
      .count("confirmed", confirmed)
      .count("recommended", static_cast<long long>(recommended.size()));
  c.holds = confirmed == static_cast<int>(recommended.size());
  return c;
}

}  // namespace mpmstab
