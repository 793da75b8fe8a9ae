// Convergence: the error at T against the grid spacing h (at a dt small enough that the time
// error does not show) and against the time step (C = c dt / h, on one grid), for every basis at
// several E, with the orders fitted by least squares on log-log axes. A run that did not end
// stable (unstable, or meaningless: its error over time reached A) has no error and leaves its
// point out of the fit; a fit needs at least three points.
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <tuple>

#include "csv.hpp"
#include "report_util.hpp"
#include "study.hpp"

namespace mpmstab {

namespace {

using ojson = nlohmann::ordered_json;

// The two refinements a case belongs to: a fixed policy refines h, the cfl policy refines dt.
std::string sweep_of(const ojson& r) {
  return r["policy"].get<std::string>() == "cfl" ? "dt" : "h";
}

// The variable of the sweep: h = 1 / cells, or dt = C h / c.
double variable(const ojson& r) {
  return sweep_of(r) == "h" ? 1.0 / r["cells"].get<double>()
                            : r["cfl_factor"].get<double>() * r["dt_cfl"].get<double>();
}

struct Point {
  double x = 0;                 // h or dt
  std::string label;            // its column: "h = 1/25" or "C = 0.4"
  std::optional<double> error;  // stable runs only
  std::string verdict;
};

// The fitted order over the points with an error (at least three).
std::optional<double> fitted_order(const std::vector<Point>& points) {
  std::vector<std::pair<double, double>> xy;
  for (const auto& p : points) {
    if (p.error) xy.emplace_back(p.x, *p.error);
  }
  return loglog_slope(xy);
}

// The rows grouped by (sweep, E, method), each group's points in the order of the spec.
using Key = std::tuple<std::string, double, std::string>;
std::map<Key, std::vector<Point>> groups(const std::vector<ojson>& rows) {
  std::map<Key, std::vector<Point>> g;
  for (const auto& r : rows) {
    Point p;
    p.x = variable(r);
    p.label = sweep_of(r) == "h" ? "h = 1/" + std::to_string(r["cells"].get<int>())
                                 : "C = " + shortest(r["cfl_factor"].get<double>());
    p.verdict = outcome(r);
    if (p.verdict == "stable" && r["max_error"].is_number()) p.error = r["max_error"].get<double>();
    g[{sweep_of(r), r["E"].get<double>(), method_label(r)}].push_back(p);
  }
  for (auto& [key, points] : g)
    std::sort(points.begin(), points.end(),
              [](const Point& a, const Point& b) { return a.x > b.x; });
  return g;
}

std::string order_text(const std::optional<double>& order) {
  return order ? fixed(*order, 2) : std::string("–");
}

std::string point_text(const Point& p) {
  if (p.error) return sci(*p.error, 2);
  return p.verdict.empty() ? std::string("–") : p.verdict;
}

std::string sweep_table(const std::map<Key, std::vector<Point>>& g, const std::string& sweep) {
  std::ostringstream md;
  bool header = false;
  for (const auto& [key, points] : g) {
    const auto& [s, E, method] = key;
    if (s != sweep) continue;
    if (!header) {
      md << "| E | method |";
      for (const auto& p : points)
        md << " " << p.label << " |";
      md << " fitted order |\n|---|---|";
      for (std::size_t k = 0; k < points.size(); ++k)
        md << "---|";
      md << "---|\n";
      header = true;
    }
    md << "| " << shortest(E) << " | " << method << " |";
    for (const auto& p : points)
      md << " " << point_text(p) << " |";
    md << " " << order_text(fitted_order(points)) << " |\n";
  }
  return md.str();
}

std::string convergence_markdown(const std::vector<ojson>& rows) {
  const auto g = groups(rows);
  const ojson& first = rows.front();
  std::ostringstream md;
  md << "## Error against h\n\nThe error at T (max over particles of |u_p - u(X_p, T)|) with the "
        "fixed step of each row of the spec, small enough that the time error does not show; "
        "the order is the least-squares slope of log(error) against log(h) over the stable "
        "runs (at least three; `–` otherwise). A = "
     << shortest(first["A"].get<double>()) << ", T = " << shortest(first["T"].get<double>()) << ", "
     << first["ppc"].get<int>() << " particles per cell.\n\n"
     << sweep_table(g, "h")
     << "\n## Error against dt\n\nThe cfl policy, dt = C h / c for each C of the spec, on one "
        "grid (each E has its own c, so its own dt for a given C). The order is the slope of "
        "log(error) against log(dt). Where the spatial error dominates, "
        "the error stops falling with dt and the fitted order is near zero: the time error is "
        "then below the grid's.\n\n"
     << sweep_table(g, "dt") << "\n";
  return md.str();
}

// <name>_data.csv: E, panel (per E), series (per method), h and error of each stable run of
// the h sweep.
std::string convergence_data(const std::vector<ojson>& rows, const std::string& header) {
  std::map<double, int> panel;
  std::map<std::string, int> series;
  for (const auto& r : rows) {
    if (sweep_of(r) != "h") continue;
    panel.emplace(r["E"].get<double>(), 0);
    series.emplace(method_label(r), 0);
  }
  int k = 0;
  for (auto& [E, p] : panel)
    p = k++;
  k = 0;
  for (auto& [m, s] : series)
    s = k++;
  std::ostringstream csv;
  csv << header << "E,panel,series,method,h,error\n";
  for (const auto& r : rows) {
    if (sweep_of(r) != "h" || outcome(r) != "stable" || !r["max_error"].is_number()) continue;
    const std::string method = method_label(r);
    csv << shortest(r["E"].get<double>()) << "," << panel[r["E"].get<double>()] << ","
        << series[method] << "," << method << "," << shortest(variable(r)) << ","
        << shortest(r["max_error"].get<double>()) << "\n";
  }
  return csv.str();
}

std::string convergence_subtitle(const Spec&, const ojson& doc) {
  int drawn = 0, left_out = 0;
  for (const auto& r : doc["cases"]) {
    if (sweep_of(r) != "h") continue;
    (outcome(r) == "stable" && r["max_error"].is_number() ? drawn : left_out) += 1;
  }
  return std::to_string(drawn) + " stable runs drawn, " + std::to_string(left_out) +
         " not stable left out";
}

// The index paragraph: the figure and the fitted orders in h, read from the rows.
std::string convergence_index(const Spec& spec, const std::vector<ojson>& rows) {
  std::ostringstream md;
  md << "![" << spec.title << "](" << spec.name << ".png)\n\n**What it shows.** Fitted order "
     << "of the error in h:";
  double last_E = -1;
  for (const auto& [key, points] : groups(rows)) {
    const auto& [sweep, E, method] = key;
    if (sweep != "h") continue;
    md << (E != last_E ? std::string(last_E < 0 ? " " : "; ") + "E = " + shortest(E) + ": " : ", ")
       << method << " " << order_text(fitted_order(points));
    last_E = E;
  }
  md << ". Errors, the orders in dt and where the grid's error hides the time error: [" << spec.name
     << ".md](" << spec.name << ".md).\n\n";
  return md.str();
}

const StudyRegistration kConvergence{{
    .name = "convergence",
    .summary = "error against h and dt for every basis, with fitted orders",
    .figure = true,
    .report =
        [](const ReportContext& c) {
          return StudyReport{.markdown = convergence_markdown(c.rows),
                             .data_csv = convergence_data(c.rows, c.csv_header)};
        },
    .index = convergence_index,
    .figure_subtitle = convergence_subtitle,
}};

}  // namespace

}  // namespace mpmstab
