// Helpers shared by the report writers: number formatting, prose lists and ranges, fits. The row
// vocabulary (a run's outcome, verdict, accuracy, labels and cost) is run_row.hpp, included here.
#pragma once

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "run/edge.hpp"
#include "run_row.hpp"
#include "spec.hpp"

namespace mpmstab {

// "5.1e-5": `digits` significant digits, compact exponent.
std::string sci(double v, int digits = 2);
std::string fixed(double v, int decimals);
// "0.25 ms", "3.96 s", "56 s".
std::string seconds(double s);
// A ratio to two significant digits: "11", "7.6", "0.13", "1.2e+02".
std::string ratio(double r);
// A parameter: three significant digits without trailing zeros ("1e-5", "2.5e-3").
std::string param(double v);
// v to `digits` significant digits, printf's %g: "0.03162".
std::string significant(double v, int digits);
// significant(v, digits), with more digits (up to 6) where fewer would print v on a threshold it
// is not on, or on its other side: a value set beside a verdict judged against a threshold reads
// on the side it was judged ("0.0997 A, accurate", not "0.1 A, accurate"; "3.01x", not "3x").
std::string beside_thresholds(double v, std::initializer_list<double> thresholds, int digits = 2);
// The cells of a Markdown table's rule row: "---|" `n` times.
std::string rule_cells(std::size_t n);
// Appends x to v unless v holds it already (v keeps the order values first appear in).
template <class T>
void add_unique(std::vector<T>& v, const std::type_identity_t<T>& x) {
  if (std::find(v.begin(), v.end(), x) == v.end()) v.push_back(x);
}
// Items joined as prose: "a", "a and b", "a, b and c" ("" when empty).
std::string list_of(const std::vector<std::string>& items);
// A value of a parameter as prose prints it: shortest() from 0.01 to 1e5 ("0.05", "10000"),
// param() outside ("1e-4").
std::string value_text(double v);
// The distinct values of v, ascending, in value_text(): "4", "4 and 64", "4, 64 and 1000"; "–"
// when v is empty.
std::string listing(std::vector<double> v);
// The numbers in `column` of the rows that hold one there, in row order.
std::vector<double> numbers(const std::vector<nlohmann::ordered_json>& rows, const char* column);
// listing(numbers(rows, column)).
std::string listing(const std::vector<nlohmann::ordered_json>& rows, const char* column);
// The range of v in value_text(): "1e-4 to 0.05", or one value when all are equal; "–" when empty.
std::string span(const std::vector<double>& v);
// The range of v, each end to `digits` significant digits: "0.387 to 0.432".
std::string span(const std::vector<double>& v, int digits);
// The edge search of `o` in words, every number from `o`: "a log-spaced scan of dt, 2 per octave,
// from 0.0625 to 4 times h/c, then bisection until the smallest failing dt is within 2% of the
// largest surviving one".
std::string edge_search_text(const EdgeOptions& o);
// A percentage of a fraction: "2%", "0.5%".
std::string percent(double fraction);
// The codes of a data file's column, each name after its index: "0 usl, 1 usf, 2 musl" (from
// `first` on).
std::string codes(const std::vector<std::string>& names, int first = 0);
// A JSON number in sci(), or "–" for null.
std::string opt_sci(const nlohmann::ordered_json& v);
// A value in sci(), or "–" for none (a RunRow's optional columns).
std::string opt_sci(const std::optional<double>& v);
// A value with `decimals` decimals, or "–".
std::string opt_fixed(std::optional<double> v, int decimals = 3);
// A string column of a row ("" where it is missing or not a string).
std::string text(const nlohmann::ordered_json& row, const char* column);
// The row has a number in `column` (not null, not missing).
bool has_number(const nlohmann::ordered_json& row, const char* column);
// The number in `column`, 0 where it is missing or not a number.
double number_or_zero(const nlohmann::ordered_json& row, const char* column);
// The runs a report made itself (cached_run.hpp's RunAccount), as timings.json records them under
// "report_runs" in an experiment's entry (write_reports) and a tier's (make reproduce): how many,
// their particle-steps and CPU seconds. report_runs_of: zero where the entry records none, and
// `recorded` false where it has no such field (a tier run measured before they were counted).
struct ReportRuns {
  bool recorded = false;
  std::size_t runs = 0;
  double particle_steps = 0, seconds = 0;
};
ReportRuns report_runs_of(const nlohmann::ordered_json& entry);
nlohmann::ordered_json report_runs_json(std::int64_t runs, double particle_steps, double seconds);
// The method of a flat record as the trade study names it: the basis, then the transfer (with
// its order or FLIP share) where it is not FLIP and the update order where it is not USL: "gimp",
// "gimp/xpic(2)", "bspline3/usf". Rows without those columns are named by their basis.
std::string method_label(const nlohmann::ordered_json& row);
// method_label with the particles per cell where not 2 and the layout where not uniform:
// "gimp/usf (ppc 4)", "mpm (shift 0.45)", "gimp (jitter 0.5)".
std::string scheme_label(const nlohmann::ordered_json& row);
// The one cost metric of every report that compares costs (tradeoff, methods, edge), in words,
// linking performance.md from a report in the same folder: particle-steps, and the measured time
// of one particle-step per method.
std::string cost_metric_text();
// The q-quantile of v (0 <= q <= 1, linear between order statistics); v must not be empty.
double quantile(std::vector<double> v, double q);
// Least-squares slope of log(y) against log(x) over the points with x, y > 0: a fitted order.
// nullopt with fewer than three such points.
std::optional<double> loglog_slope(const std::vector<std::pair<double, double>>& points);
// The regime orders are fitted in (docs/theory.md, "Orders of convergence"): a run that is
// accurate_run() (run_row.hpp: stable over at least a wave pass, error over time below
// kAccurateFraction A), and, for an order in h, in which no particle crossed a cell: its recorded
// crossings are zero, or, where they are not recorded, A / h is below 1 / (2 ppc) (the particles
// nearest a cell boundary start a quarter cell from it at 2 per cell). A point outside it is shown
// and never fitted.
bool crossing_free(const nlohmann::ordered_json& row);
// "the order is fitted only over grids where no particle crosses a cell and the error over
// time is below 0.1 A": the regime in words, for the reports that fit orders.
std::string order_regime_text();
// Relative link from a report folder to a file.
std::string link(const std::filesystem::path& from_dir, const std::filesystem::path& target);

}  // namespace mpmstab
