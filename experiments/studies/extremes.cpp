// The extremes: verdicts over extreme parameters, and per method where and why it fails.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "csv.hpp"
#include "report.hpp"
#include "report_util.hpp"
#include "scenes.hpp"

#include "study.hpp"

namespace mpmstab {

namespace {

using ojson = nlohmann::ordered_json;

// The extremes: where and why each method fails.

// 0 stable, 1 stable but meaningless, 2 unstable.
int verdict_code(const ojson& r) {
  if (r["stable"] != true) return 2;
  return r["meaningless"] == true ? 1 : 0;
}

// A stable run's measured quantities must all be finite numbers (JSON has no NaN: a NaN would
// have been written as null).
bool stable_output_is_finite(const ojson& r) {
  for (const char* key : {"max_error", "max_error_over_time", "dt_stable_min", "dt_min", "dt_max",
                          "courant", "wall_seconds"}) {
    if (!r[key].is_number() || !std::isfinite(r[key].get<double>())) return false;
  }
  return r["crossings"].is_number();
}

std::string extremes_markdown(const Spec& spec, const std::vector<ojson>& rows) {
  int stable = 0, meaningless = 0, bad_output = 0;
  double slowest = 0;
  std::string slowest_case;
  std::map<std::string, int> reasons;
  for (const auto& r : rows) {
    const int v = verdict_code(r);
    stable += v == 0;
    meaningless += v == 1;
    if (v == 2) ++reasons[r["failure_reason"].get<std::string>()];
    if (v < 2 && !stable_output_is_finite(r)) ++bad_output;
    if (r["wall_seconds"].get<double>() > slowest) {
      slowest = r["wall_seconds"].get<double>();
      slowest_case = r["method"].get<std::string>() + " E=" + shortest(r["E"].get<double>()) +
                     " A=" + shortest(r["A"].get<double>()) +
                     " dt=" + param(r["dt"].get<double>()) + " cells=" + r["cells"].dump() +
                     " ppc=" + r["ppc"].dump();
    }
  }
  std::ostringstream md;
  md << "## Results\n\n**Summary.** " << rows.size()
     << " cases, every one with a verdict: " << stable << " stable, " << meaningless
     << " stable but meaningless (the error over time "
     << "reached A), " << rows.size() - stable - meaningless << " unstable (";
  bool first = true;
  for (const auto& [reason, n] : reasons) {
    md << (first ? "" : ", ") << reason << " " << n;
    first = false;
  }
  md << "). Stable outputs holding a NaN or an infinity: " << bad_output
     << ". The slowest case took " << seconds(slowest) << " (" << slowest_case << ").\n\n"
     << "![" << spec.title << "](" << spec.name << ".png)\n\nVector version: [" << spec.name
     << ".svg](" << spec.name << ".svg); data: [" << spec.name << "_data.csv](" << spec.name
     << "_data.csv).\n\n";

  // Where and why, per method: by Courant number and by amplitude in cells.
  struct Band {
    const char* name;
    double lo, hi;
  };
  const std::vector<Band> courant_bands = {{"c dt/h < 0.5", 0, 0.5},
                                           {"0.5 <= c dt/h < 1", 0.5, 1},
                                           {"1 <= c dt/h < 10", 1, 10},
                                           {"c dt/h >= 10", 10, 1e300}};
  const std::vector<Band> amplitude_bands = {{"A/h < 1e-3", 0, 1e-3},
                                             {"1e-3 <= A/h < 0.1", 1e-3, 0.1},
                                             {"0.1 <= A/h < 1", 0.1, 1},
                                             {"A/h >= 1 (particles cross cells)", 1, 1e300}};
  auto table = [&](const std::string& method, const std::vector<Band>& bands, bool by_courant) {
    md << "| " << (by_courant ? "Courant number" : "amplitude in cells")
       << " | runs | stable | "
          "meaningless | unstable: reasons |\n|---|---|---|---|---|\n";
    for (const auto& b : bands) {
      int n = 0, s = 0, m = 0;
      std::map<std::string, int> why;
      for (const auto& r : rows) {
        if (r["method"] != method) continue;
        const double x = by_courant ? r["courant"].get<double>()
                                    : r["A"].get<double>() * r["cells"].get<double>();
        if (x < b.lo || x >= b.hi) continue;
        ++n;
        const int v = verdict_code(r);
        s += v == 0;
        m += v == 1;
        if (v == 2) ++why[r["failure_reason"].get<std::string>()];
      }
      md << "| " << b.name << " | " << n << " | " << s << " | " << m << " | ";
      bool f = true;
      for (const auto& [reason, k] : why) {
        md << (f ? "" : ", ") << reason << " " << k;
        f = false;
      }
      md << (why.empty() ? "none" : "") << " |\n";
    }
    md << "\n";
  };
  for (const char* method : {"gimp", "mpm"}) {
    md << "### " << method << "\n\n";
    table(method, courant_bands, true);
    table(method, amplitude_bands, false);
  }
  // The reading, computed: what happens at and above Courant 1, and what the failures below
  // it have in common.
  md << "Reading (computed from the rows): ";
  for (const char* method : {"gimp", "mpm"}) {
    int above = 0, above_failed = 0, below_failed = 0, below_failed_crossing = 0;
    std::int64_t longest_survivor = 0;
    for (const auto& r : rows) {
      if (r["method"] != method) continue;
      const bool failed = r["stable"] != true;
      if (r["courant"].get<double>() >= 1) {
        ++above;
        above_failed += failed;
        if (!failed) longest_survivor = std::max(longest_survivor, r["steps"].get<std::int64_t>());
      } else if (failed) {
        ++below_failed;
        below_failed_crossing += r["A"].get<double>() * r["cells"].get<double>() >= 1;
      }
    }
    md << method << ": " << above_failed << " of " << above
       << " runs at c dt/h >= 1 fail; the ones that survive ran " << longest_survivor
       << " steps at most (T is short there), too few for the instability to grow. Below "
          "Courant 1, "
       << below_failed << " runs fail, " << below_failed_crossing << " of them with A/h >= 1, "
       << "where particles cross cells. ";
  }
  md << "\n\n";
  md << "### Every case\n\n| method | bc | E | A | dt | T | cells | ppc | c dt/h | verdict | "
        "max error over time | cost |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    md << "| " << r["method"].get<std::string>() << " | " << r["bc"].get<std::string>() << " | "
       << shortest(r["E"].get<double>()) << " | " << shortest(r["A"].get<double>()) << " | "
       << param(r["dt"].get<double>()) << " | " << param(r["T"].get<double>()) << " | "
       << r["cells"].dump() << " | " << r["ppc"].dump() << " | " << sci(r["courant"].get<double>())
       << " | " << verdict(r) << " | " << opt_sci(r["max_error_over_time"]) << " | " << cost(r)
       << " |\n";
  }
  return md.str();
}

std::string extremes_data_csv(const std::vector<ojson>& rows, const std::string& header_lines) {
  std::ostringstream csv;
  csv << header_lines
      << "# method: 0 mpm, 1 gimp; verdict: 0 stable, 1 meaningless, 2 unstable\n"
         "method,courant,A_over_h,verdict\n";
  for (const auto& r : rows) {
    csv << (r["method"] == "gimp" ? 1 : 0) << ',' << shortest(r["courant"].get<double>()) << ','
        << shortest(r["A"].get<double>() * r["cells"].get<double>()) << ',' << verdict_code(r)
        << '\n';
  }
  return csv.str();
}

std::string extremes_index(const Spec& spec, const std::vector<ojson>& rows) {
  int unstable = 0;
  for (const auto& r : rows)
    unstable += r["stable"] == false;
  std::ostringstream md;
  md << "![" << spec.title << "](" << spec.name << ".png)\n\n**What it shows.** " << rows.size()
     << " cases at the extremes, each with a verdict (" << unstable
     << " unstable); per method, where and why it fails: [" << spec.name << ".md](" << spec.name
     << ".md).\n\n";
  return md.str();
}

const StudyRegistration kExtremes{{
    .name = "extremes",
    .summary = "verdicts over extreme parameters: where and why each method fails",
    .records = {.error_over_time = true, .dt_stable = true, .crossings = true},
    .figure = true,
    .report =
        [](const ReportContext& c) {
          return StudyReport{.markdown = extremes_markdown(c.spec, c.rows),
                             .data_csv = extremes_data_csv(c.rows, c.csv_header)};
        },
    .index = extremes_index,
    .figure_subtitle = [](const Spec& spec,
                          const ojson& doc) { return first_scene_subtitle(spec.name, doc); },
}};

}  // namespace

}  // namespace mpmstab
