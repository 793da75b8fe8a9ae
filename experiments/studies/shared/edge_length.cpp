#include "shared/edge_length.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>

#include "base/accuracy.hpp"
#include "csv.hpp"
#include "report_util.hpp"

namespace mpmstab {

using ojson = nlohmann::ordered_json;

bool survival_monotone(const ojson& r) {
  return !r.contains("monotone") || !r["monotone"].is_boolean() || r["monotone"].get<bool>();
}

std::string monotone_words(const ojson& r) {
  if (survival_monotone(r)) return "";
  std::string above = "–";
  if (has_number(r, "dt_survives_above") && has_number(r, "dt_cfl"))
    above = significant(r["dt_survives_above"].get<double>() / r["dt_cfl"].get<double>(), 3);
  return ", **not monotone**: survives again at up to c dt/h = " + above;
}

std::vector<double> edges_of(const ojson& r) {
  std::vector<double> dts;
  for (const char* col : {"dt_edge", "dt_accurate"})
    if (has_number(r, col)) add_unique(dts, r[col].get<double>());
  return dts;
}

std::vector<double> test_lengths(double cT) {
  std::vector<double> out;
  for (const double f : kLengthFactors) {
    const double length = std::min(f * cT, kLongPasses);
    if (length > cT && (out.empty() || length > out.back())) out.push_back(length);
  }
  return out;
}

std::vector<RunParams> length_runs(const RunParams& base, double dt) {
  std::vector<RunParams> out;
  for (const double length : test_lengths(wave_passes(base))) {
    RunParams p = base;
    p.stepping.policy = TimeStepPolicy::fixed;
    p.dt = dt;
    p.T = length / wave_speed(p);
    p.observe.error_over_time = true;
    out.push_back(p);
  }
  return out;
}

bool LongRun::accurate() const {
  return outcome == "stable" && error_over_A && *error_over_A < kAccurateFraction;
}

std::string length_role(double dt, std::size_t k) {
  return "length rerun " + std::to_string(k + 1) + " of dt " + shortest(dt);
}

std::vector<FollowUp> all_length_runs(const std::vector<ojson>& rows,
                                      const std::vector<CaseSpec>& cases,
                                      const std::vector<std::size_t>& case_of) {
  std::vector<FollowUp> runs;
  for (std::size_t i = 0; i < rows.size() && i < cases.size(); ++i) {
    const std::size_t of = case_of.empty() ? i : case_of.at(i);
    for (const double dt : edges_of(rows[i])) {
      std::vector<RunParams> lengths = length_runs(cases[i].params, dt);
      for (std::size_t k = 0; k < lengths.size(); ++k)
        runs.push_back({.of = of, .role = length_role(dt, k), .params = std::move(lengths[k])});
    }
  }
  return runs;
}

LengthRuns read_length_runs(const std::vector<ojson>& rows, const std::vector<ojson>& follow_up,
                            const std::vector<std::size_t>& case_of) {
  LengthRuns out;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ojson& r = rows[i];
    const std::size_t of = case_of.empty() ? i : case_of.at(i);
    for (const double dt : edges_of(r)) {
      const std::vector<double> lengths = test_lengths(*RunRow(r).wave_passes);
      for (std::size_t k = 0; k < lengths.size(); ++k) {
        const auto asked = follow_ups_of(follow_up, of, length_role(dt, k));
        if (asked.empty()) continue;
        const ojson& run = *asked.front();
        const RunRow rr(run);
        const bool survived = rr.survived();
        out[&r].push_back({.dt = dt,
                           .length = lengths[k],
                           .passes = survived || !rr.failure_time
                                         ? *rr.wave_passes
                                         : std::sqrt(run["E"].get<double>()) * *rr.failure_time,
                           .survived = survived,
                           .outcome = rr.outcome,
                           .error_over_A = rr.error_over_A()});
      }
    }
  }
  return out;
}

Lasting lasting(const LengthRuns& runs, const ojson& r, const char* dt_col,
                std::optional<double> bound) {
  Lasting out;
  if (!has_number(r, dt_col)) return out;
  const auto it = runs.find(&r);
  if (it == runs.end()) return out;
  const double dt = r[dt_col].get<double>();
  const bool survival = std::string_view(dt_col) == "dt_edge";
  for (const LongRun& l : it->second) {
    if (l.dt != dt) continue;
    out.tested = true;
    const bool bounded = !bound || (l.error_over_A && *l.error_over_A <= *bound);
    if (survival ? !(l.survived && bounded) : !l.accurate()) {
      out.holds = false;
      out.failing = &l;
      out.length = l.survived ? l.length : l.passes;
      return out;
    }
    out.holds = true;
    out.length = l.length;
    out.longest = &l;
  }
  return out;
}

std::string lasting_text(const LengthRuns& runs, const ojson& r, const char* dt_col,
                         std::optional<double> bound) {
  const Lasting l = lasting(runs, r, dt_col, bound);
  if (!l.tested) return "not tested for length";
  if (l.holds) {
    std::string s = "holds to c T = " + significant(l.length, 4);
    if (l.longest && l.longest->outcome == "meaningless") s += " (meaningless there)";
    return s;
  }
  const LongRun& run = *l.failing;
  if (!run.survived) return "**transient**: fails at c T = " + significant(run.passes, 3);
  if (std::string_view(dt_col) == "dt_edge")
    return "**transient**: unbounded at c T = " + significant(run.length, 4) + " (" +
           (run.error_over_A ? significant(*run.error_over_A, 2) + " A" : run.outcome) + ")";
  return "**transient**: not accurate at c T = " + significant(run.length, 4) + " (" +
         (run.outcome == "stable" && run.error_over_A ? significant(*run.error_over_A, 2) + " A"
                                                      : run.outcome) +
         ")";
}

void LengthTally::add(const Lasting& l) {
  if (!l.tested) return;
  ++tested;
  if (l.holds)
    ++held;
  else
    failed_at.push_back(l.length);
}

Claim length_claim(std::string id, std::string statement, std::string evidence,
                   const LengthTally& t) {
  Claim c = claim(std::move(id), std::move(statement), std::move(evidence));
  c.value("first", shortest(kLengthFactors[0]))
      .value("second", shortest(kLengthFactors[1]))
      .value("cap", shortest(kLongPasses))
      .every("held", t.held, "tested", t.tested);
  return c;
}

}  // namespace mpmstab
