// Supporting experiments: a plain table of every case, the parameters that vary and the measured
// quantities the spec records.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "csv.hpp"

#include "report_util.hpp"
#include "study.hpp"

namespace mpmstab {

namespace {

using ojson = nlohmann::ordered_json;
namespace fs = std::filesystem;

// A plain table of every case: the parameters that vary, then the measured quantities.

std::string cases_markdown(const Spec& spec, const std::vector<ojson>& rows) {
  // Parameter columns shown: always method, E, A, dt; the others only where cases differ.
  std::vector<std::string> params = {"method", "E", "A", "dt"};
  for (const char* col :
       {"T", "cells", "ppc", "bc", "position_update", "scene", "walls", "transfer", "flip_fraction",
        "update", "body_force_time", "dt_stable_sigma", "dt_stable_vnorm"}) {
    for (const auto& r : rows) {
      if (r[col] != rows.front()[col]) {
        params.push_back(col);
        break;
      }
    }
  }
  const auto& observe = spec.cases.front().params.observe;
  std::ostringstream md;
  int unstable = 0, meaningless = 0;
  for (const auto& r : rows) {
    unstable += r["stable"] == false;
    meaningless += r["meaningless"] == true;
  }
  md << "## Results\n\n"
     << rows.size() << " cases: " << rows.size() - unstable << " stable (" << meaningless
     << " meaningless: the error over time reached A), " << unstable << " unstable.";
  std::string fixed_params;
  for (const char* col :
       {"T", "cells", "ppc", "bc", "position_update", "scene", "walls", "transfer", "flip_fraction",
        "update", "body_force_time", "dt_stable_sigma", "dt_stable_vnorm"}) {
    if (std::find(params.begin(), params.end(), col) != params.end()) continue;
    const ojson& v = rows.front()[col];
    if (v.is_null()) continue;  // not applicable to these runs (flip_fraction without a blend)
    fixed_params += std::string(fixed_params.empty() ? "" : ", ") + col + " = " +
                    (v.is_string() ? v.get<std::string>() : shortest(v.get<double>()));
  }
  md << " Common to all: " << fixed_params << ".\n\n|";
  for (const auto& p : params)
    md << " " << p << " |";
  md << " c dt/h | verdict | max error |";
  if (observe.error_over_time) md << " max error over time | over time / A |";
  if (observe.dt_stable) md << " dt_stable min |";
  if (observe.crossings) md << " crossings |";
  md << " cost |\n|";
  const std::size_t n_cols = params.size() + 4 + (observe.error_over_time ? 2 : 0) +
                             (observe.dt_stable ? 1 : 0) + (observe.crossings ? 1 : 0);
  for (std::size_t k = 0; k < n_cols; ++k)
    md << "---|";
  md << "\n";
  for (const auto& r : rows) {
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
    md << " " << sci(r["courant"].get<double>()) << " | " << verdict(r) << " | "
       << opt_sci(r["max_error"]) << " |";
    if (observe.error_over_time) {
      md << " " << opt_sci(r["max_error_over_time"]) << " | "
         << (r["max_error_over_time"].is_number() && r["A"].get<double>() > 0
                 ? ratio(r["max_error_over_time"].get<double>() / r["A"].get<double>())
                 : "–")
         << " |";
    }
    if (observe.dt_stable) md << " " << opt_sci(r["dt_stable_min"]) << " |";
    if (observe.crossings) {
      md << " " << (r["crossings"].is_null() ? std::string("–") : r["crossings"].dump()) << " |";
    }
    md << " " << cost(r) << " |\n";
  }
  return md.str();
}

std::string cases_index(const Spec& spec, const std::vector<ojson>& rows) {
  int unstable = 0, meaningless = 0;
  for (const auto& r : rows) {
    unstable += r["stable"] == false;
    meaningless += r["meaningless"] == true;
  }
  std::ostringstream md;
  md << "**What it shows.** " << rows.size() << " cases, " << unstable << " unstable, "
     << meaningless << " meaningless; it supports the explanations in [comparison.md]"
     << "(comparison.md). Full table: [" << spec.name << ".md](" << spec.name << ".md).\n\n";
  return md.str();
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

}  // namespace mpmstab
