// Supporting experiments: a plain table of every case, the parameters that vary and the measured
// quantities the spec records.
#include <algorithm>
#include <sstream>

#include "csv.hpp"
#include "report_util.hpp"
#include "run_row.hpp"
#include "study.hpp"

namespace mpmstab::studies::cases {
namespace {

using ojson = nlohmann::ordered_json;

// Parameters shown as a column where the cases differ and stated once where they do not; method,
// E, A and dt always have a column.
const std::vector<std::string> kOptionalParams = {
    "T", "cells", "ppc", "bc", "position_update", "scene", "walls",
    // The transfer and the order of the update, and the form of the eq. (108) bound.
    "transfer", "flip_fraction", "xpic_order", "fmpm_order", "update", "body_force_time",
    "dt_stable_sigma", "dt_stable_vnorm"};

// What the cases find: their count and how they ended, which the heading and the index give.
struct Findings {
  std::size_t cases = 0;
  VerdictTally verdicts;
};

// The findings: the cases counted and their verdicts tallied.
Findings find(const std::vector<ojson>& rows) {
  return {rows.size(), verdict_tally(rows)};
}

// The parameter columns: method, E, A, dt, then every optional parameter that differs between
// the cases.
std::vector<std::string> varying_params(const std::vector<ojson>& rows) {
  std::vector<std::string> params = {"method", "E", "A", "dt"};
  for (const std::string& col : kOptionalParams)
    if (std::any_of(rows.begin(), rows.end(),
                    [&](const ojson& r) { return r[col] != rows.front()[col]; }))
      params.push_back(col);
  return params;
}

// "T = 1, cells = 100, ...": the optional parameters without a column, common to every case.
std::string common_params(const std::vector<ojson>& rows, const std::vector<std::string>& params) {
  std::string text;
  for (const std::string& col : kOptionalParams) {
    if (std::find(params.begin(), params.end(), col) != params.end()) continue;
    const ojson& v = rows.front()[col];
    if (v.is_null()) continue;  // not applicable to these runs (flip_fraction without a blend)
    text += std::string(text.empty() ? "" : ", ") + col + " = " +
            (v.is_string() ? v.get<std::string>() : shortest(v.get<double>()));
  }
  return text;
}

// The header of the table: the parameter columns, then the measured quantities the spec records.
std::string cases_header(const std::vector<std::string>& params, const Observe& observe) {
  std::ostringstream md;
  md << "|";
  for (const auto& p : params)
    md << " " << p << " |";
  md << " c dt/h | A/h | c T | verdict | max error |";
  if (observe.error_over_time) md << " max error over time | over time / A |";
  if (observe.dt_stable) md << " dt_stable min |";
  if (observe.crossings) md << " crossings |";
  md << " particle-steps |\n|";
  const std::size_t n_cols = params.size() + 6 + (observe.error_over_time ? 2 : 0) +
                             (observe.dt_stable ? 1 : 0) + (observe.crossings ? 1 : 0);
  md << rule_cells(n_cols) << "\n";
  return md.str();
}

// One case: its parameters and what it measured.
std::string case_row(const ojson& r, const std::vector<std::string>& params,
                     const Observe& observe) {
  std::ostringstream md;
  md << "|";
  for (const auto& p : params) {
    const ojson& v = r[p];
    md << " "
       << (v.is_string() ? v.get<std::string>()
           : v.is_null() ? std::string("–")
           : p == "dt"   ? param(v.get<double>())
                         : shortest(v.get<double>()))
       << " |";
  }
  auto coordinate = [&](const char* col) {
    return has_number(r, col) ? significant(r[col].get<double>(), 3) : std::string("–");
  };
  const RunRow row(r);
  md << " " << opt_sci(row.courant) << " | " << coordinate("A_over_h") << " | "
     << (row.wave_passes ? significant(*row.wave_passes, 3) : "–") << " | " << verdict(r) << " | "
     << opt_sci(r["max_error"]) << " |";
  if (observe.error_over_time)
    md << " " << opt_sci(row.error_over_time) << " | "
       << (row.error_over_A() ? ratio(*row.error_over_A()) : "–") << " |";
  if (observe.dt_stable) md << " " << opt_sci(r["dt_stable_min"]) << " |";
  if (observe.crossings)
    md << " " << (r["crossings"].is_null() ? std::string("–") : r["crossings"].dump()) << " |";
  md << " " << work(r) << " |\n";
  return md.str();
}

// "12 cases: 9 stable (7 accurate, 2 inaccurate), 1 meaningless, 2 unstable": the tally, with
// `meaningless` after the count of meaningless runs.
std::string outcomes_text(const Findings& f, const char* meaningless) {
  const VerdictTally& n = f.verdicts;
  std::ostringstream s;
  s << f.cases << " cases: " << n.stable << " stable (" << n.accurate << " accurate, "
    << n.inaccurate << " inaccurate";
  if (n.unmeasured > 0) s << ", " << n.unmeasured << " with no error over time recorded";
  s << "), " << n.meaningless << " meaningless" << meaningless << ", " << n.unstable << " unstable";
  if (n.too_short > 0) s << ", " << n.too_short << " too short for a verdict";
  if (n.under_a_wave_pass > 0)
    s << ", " << n.under_a_wave_pass << " under a wave pass (reached T below A in fewer than "
      << shortest(kMinWavePasses) << " wave pass c T / L: not counted as stable)";
  return s.str();
}

// The verdicts counted, the parameters common to every case, then one row per case.
std::string cases_markdown(const Spec& spec, const std::vector<ojson>& rows) {
  const auto params = varying_params(rows);
  const auto& observe = spec.cases.front().params.observe;
  std::ostringstream md;
  md << "## Results\n\n"
     << outcomes_text(find(rows), " (survived, but the error over time reached A)")
     << ". Common to all: " << common_params(rows, params) << ".\n\n"
     << cases_header(params, observe);
  for (const auto& r : rows)
    md << case_row(r, params, observe);
  return md.str();
}

std::string cases_index(const Spec& spec, const std::vector<ojson>& rows, const ojson&) {
  return "**What it shows.** " + outcomes_text(find(rows), "") + ". Full table: [" + spec.name +
         ".md](" + spec.name + ".md).\n\n";
}

const StudyRegistration kCases{{
    .name = "cases",
    .summary = "a plain table of every case (the experiments that support the comparison)",
    .report =
        [](const ReportContext& c) {
          return StudyReport{.markdown = cases_markdown(c.spec, c.rows)};
        },
    .index = cases_index,
}};

}  // namespace
}  // namespace mpmstab::studies::cases
