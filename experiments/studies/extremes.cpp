// The extremes: verdicts over extreme parameters (Courant numbers from far below 1 to far above
// it, amplitudes from a tiny fraction of a cell to many cells), and per method where and why it
// fails.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <sstream>
#include <tuple>

#include "csv.hpp"
#include "report.hpp"
#include "report_util.hpp"
#include "scenes.hpp"
#include "study.hpp"

namespace mpmstab {

namespace {

using ojson = nlohmann::ordered_json;

// 0 stable, 1 stable but meaningless, 2 unstable.
int verdict_code(const ojson& r) {
  const std::string o = outcome(r);
  return o == "unstable" ? 2 : o == "meaningless" ? 1 : 0;
}

// A stable run's measured quantities must all be finite numbers (JSON has no NaN: a NaN would
// have been written as null).
bool stable_output_is_finite(const ojson& r) {
  for (const char* key : {"max_error", "max_error_over_time", "dt_stable_min", "dt_min", "dt_max",
                          "dt_mean", "courant"}) {
    if (!r[key].is_number() || !std::isfinite(r[key].get<double>())) return false;
  }
  return r["crossings"].is_number();
}

// Failure reasons with their counts: "left_domain 1, nonpositive_F 73".
std::string reason_counts(const std::map<std::string, int>& reasons) {
  std::ostringstream s;
  bool first = true;
  for (const auto& [reason, n] : reasons) {
    s << (first ? "" : ", ") << reason << " " << n;
    first = false;
  }
  return s.str();
}

// The case with the most work (particle-steps, deterministic): its work and its parameters.
struct Slowest {
  double work = 0;
  std::string name;
};

Slowest slowest_case(const std::vector<ojson>& rows) {
  Slowest slowest;
  for (const auto& r : rows) {
    if (particle_steps(r) > slowest.work) {
      slowest.work = particle_steps(r);
      slowest.name = method_label(r) + " E=" + shortest(r["E"].get<double>()) +
                     " A=" + shortest(r["A"].get<double>()) +
                     " dt=" + param(r["dt"].get<double>()) + " cells=" + r["cells"].dump() +
                     " ppc=" + r["ppc"].dump();
    }
  }
  return slowest;
}

// The opening: how many cases reached each verdict and why the unstable ones failed, whether
// any stable output holds a NaN or an infinity, the slowest case, and the figure.
std::string extremes_summary(const Spec& spec, const std::vector<ojson>& rows) {
  int stable = 0, meaningless = 0, bad_output = 0;
  std::map<std::string, int> reasons;
  for (const auto& r : rows) {
    const int v = verdict_code(r);
    stable += v == 0;
    meaningless += v == 1;
    if (v == 2) ++reasons[r["failure_reason"].get<std::string>()];
    if (v < 2 && !stable_output_is_finite(r)) ++bad_output;
  }
  const Slowest slowest = slowest_case(rows);
  std::ostringstream md;
  md << "## Results\n\n**Summary.** " << rows.size()
     << " cases, every one with a verdict: " << stable << " stable, " << meaningless
     << " meaningless (survived, but the error over time reached A), "
     << rows.size() - stable - meaningless << " unstable (" << reason_counts(reasons)
     << "). Stable outputs holding a NaN or an infinity: " << bad_output
     << ". The largest case took " << sci(slowest.work) << " particle-steps (" << slowest.name
     << ").\n\n"
     << "![" << spec.title << "](" << spec.name << ".png)\n\nVector version: [" << spec.name
     << ".svg](" << spec.name << ".svg); data: [" << spec.name << "_data.csv](" << spec.name
     << "_data.csv).\n\n";
  return md.str();
}

// A band of Courant numbers c dt/h or of amplitudes in cells A/h: lo <= x < hi.
struct Band {
  const char* name;
  double lo, hi;
};
const std::vector<Band> kCourantBands = {{"c dt/h < 0.5", 0, 0.5},
                                         {"0.5 <= c dt/h < 1", 0.5, 1},
                                         {"1 <= c dt/h < 10", 1, 10},
                                         {"c dt/h >= 10", 10, 1e300}};
const std::vector<Band> kAmplitudeBands = {{"A/h < 1e-3", 0, 1e-3},
                                           {"1e-3 <= A/h < 0.1", 1e-3, 0.1},
                                           {"0.1 <= A/h < 1", 0.1, 1},
                                           {"A/h >= 1 (particles cross cells)", 1, 1e300}};

// Where one method fails: per band of the Courant number (`by_courant`) or of the amplitude in
// cells, how many runs fall in it, their verdicts and the reasons of the failures.
std::string band_table(const std::vector<ojson>& rows, const std::string& method,
                       const std::vector<Band>& bands, bool by_courant) {
  std::ostringstream md;
  md << "| " << (by_courant ? "Courant number" : "amplitude in cells")
     << " | runs | stable | meaningless | unstable: reasons |\n|---|---|---|---|---|\n";
  for (const auto& b : bands) {
    int n = 0, s = 0, m = 0;
    std::map<std::string, int> why;
    for (const auto& r : rows) {
      if (method_label(r) != method) continue;
      const double x =
          by_courant ? r["courant"].get<double>() : r["A"].get<double>() * r["cells"].get<double>();
      if (x < b.lo || x >= b.hi) continue;
      ++n;
      const int v = verdict_code(r);
      s += v == 0;
      m += v == 1;
      if (v == 2) ++why[r["failure_reason"].get<std::string>()];
    }
    md << "| " << b.name << " | " << n << " | " << s << " | " << m << " | " << reason_counts(why)
       << (why.empty() ? "none" : "") << " |\n";
  }
  md << "\n";
  return md.str();
}

// The reading for one method, computed from the rows: how many runs at and above Courant 1
// fail and how long the survivors ran, and how many of the failures below Courant 1 have
// particles crossing cells.
std::string method_reading(const std::vector<ojson>& rows, const std::string& method) {
  int above = 0, above_failed = 0, below_failed = 0, below_failed_crossing = 0;
  std::int64_t longest_survivor = 0;
  for (const auto& r : rows) {
    if (method_label(r) != method) continue;
    const bool failed = outcome(r) == "unstable";
    if (r["courant"].get<double>() >= 1) {
      ++above;
      above_failed += failed;
      if (!failed) longest_survivor = std::max(longest_survivor, r["steps"].get<std::int64_t>());
    } else if (failed) {
      ++below_failed;
      below_failed_crossing += r["A"].get<double>() * r["cells"].get<double>() >= 1;
    }
  }
  std::ostringstream md;
  md << method << ": " << above_failed << " of " << above
     << " runs at c dt/h >= 1 fail; the longest survivor there ran " << longest_survivor
     << " steps (a survivor above Courant 1 is stable only if its basis's edge lies above "
        "it: edge.md). Below Courant 1, "
     << below_failed << " runs fail, " << below_failed_crossing << " of them with A/h >= 1, "
     << "where particles cross cells. ";
  return md.str();
}

// Every case: its parameters, Courant number, verdict, error over time and cost.
std::string every_case_table(const std::vector<ojson>& rows) {
  std::ostringstream md;
  md << "### Every case\n\n| method | bc | E | A | dt | T | cells | ppc | c dt/h | verdict | "
        "max error over time | particle-steps "
        "|\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    md << "| " << method_label(r) << " | " << r["bc"].get<std::string>() << " | "
       << shortest(r["E"].get<double>()) << " | " << shortest(r["A"].get<double>()) << " | "
       << param(r["dt"].get<double>()) << " | " << param(r["T"].get<double>()) << " | "
       << r["cells"].dump() << " | " << r["ppc"].dump() << " | " << opt_sci(r["courant"]) << " | "
       << verdict(r) << " | " << opt_sci(r["max_error_over_time"]) << " | " << work(r) << " |\n";
  }
  return md.str();
}

// The methods of the rows (method_label: the basis, then a transfer other than FLIP), the
// paper's first, then the other bases in a fixed order, then the rest as they first appear.
std::vector<std::string> methods_of(const std::vector<ojson>& rows) {
  std::vector<std::string> present;
  for (const char* m : {"gimp", "mpm", "cpgimp", "cpdi", "bspline2", "bspline3"}) {
    for (const auto& r : rows) {
      if (method_label(r) == m) {
        present.emplace_back(m);
        break;
      }
    }
  }
  for (const auto& r : rows) {
    const std::string m = method_label(r);
    if (std::find(present.begin(), present.end(), m) == present.end()) present.push_back(m);
  }
  return present;
}

// The report: the summary, per method its band tables, the reading and every case.
std::string extremes_markdown(const Spec& spec, const std::vector<ojson>& rows) {
  std::ostringstream md;
  md << extremes_summary(spec, rows);
  const std::vector<std::string> methods = methods_of(rows);
  for (const std::string& method : methods) {
    md << "### " << method << "\n\n"
       << band_table(rows, method, kCourantBands, true)
       << band_table(rows, method, kAmplitudeBands, false);
  }
  md << "Reading (computed from the rows): ";
  for (const std::string& method : methods)
    md << method_reading(rows, method);
  md << "\n\n" << every_case_table(rows);
  return md.str();
}

// The cases drawn at one spot of the figure: a method, a Courant number, an amplitude in cells
// and a verdict. Many cases share a spot (they differ in E, T, cells or ppc): they are drawn once,
// with their count.
using Spot = std::tuple<int, std::string, std::string, int>;

std::map<Spot, int> spots(const std::vector<ojson>& rows) {
  const std::vector<std::string> methods = methods_of(rows);
  std::map<Spot, int> n;
  for (const auto& r : rows) {
    const auto m = std::find(methods.begin(), methods.end(), method_label(r));
    ++n[{int(m - methods.begin()), param(r["courant"].get<double>()),
         param(r["A"].get<double>() * r["cells"].get<double>()), verdict_code(r)}];
  }
  return n;
}

std::string extremes_data_csv(const std::vector<ojson>& rows, const std::string& header_lines) {
  std::ostringstream csv;
  csv << header_lines
      << "# one row per spot: method (its panel, 0..), Courant number, amplitude in cells, "
         "verdict (0 stable, 1 meaningless, 2 unstable), the number of cases there and the "
         "method's name\n"
         "method,courant,A_over_h,verdict,cases,name\n";
  const std::vector<std::string> methods = methods_of(rows);
  for (const auto& [spot, count] : spots(rows)) {
    const auto& [method, courant, a_over_h, verdict] = spot;
    csv << method << ',' << courant << ',' << a_over_h << ',' << verdict << ',' << count << ','
        << methods[static_cast<std::size_t>(method)] << '\n';
  }
  return csv.str();
}

// What the figure draws: every case, at fewer spots than cases.
std::string extremes_subtitle(const Spec&, const ojson& doc) {
  const std::vector<ojson> rows(doc["cases"].begin(), doc["cases"].end());
  std::string s = std::to_string(rows.size());
  s += " cases at ";
  s += std::to_string(spots(rows).size());
  s += " spots; the verdicts of one spot side by side, the marker growing with its number of "
       "cases (printed when more than 1)";
  return s;
}

std::string extremes_index(const Spec& spec, const std::vector<ojson>& rows) {
  int unstable = 0;
  for (const auto& r : rows)
    unstable += outcome(r) == "unstable";
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
    .figure_subtitle = extremes_subtitle,
}};

}  // namespace

}  // namespace mpmstab
