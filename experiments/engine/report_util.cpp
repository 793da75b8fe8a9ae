#include "report_util.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "base/accuracy.hpp"
#include "compare.hpp"
#include "csv.hpp"
#include "key.hpp"

namespace mpmstab {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

// The number formats are fmt's, which follow printf's ("%.*f", "%.*g", "%.*e") digit for digit.
std::string fixed(double v, int decimals) {
  return fmt::format("{:.{}f}", v, decimals);
}

std::string seconds(double s) {
  if (s < 1) return fixed(s * 1e3, s < 0.01 ? 2 : 0) + " ms";
  return s < 10 ? fixed(s, 2) + " s" : fixed(s, 0) + " s";
}

// A ratio to two significant digits: "11", "7.6", "0.13", "1.2e+02".
std::string ratio(double r) {
  return fmt::format("{:.2g}", r);
}

// A parameter: its value to 3 significant digits without trailing zeros ("1e-5", "2.5e-3").
std::string param(double v) {
  std::string s = sci(v, 3);
  const auto e = s.find('e');
  std::string mantissa = s.substr(0, e), rest = e == std::string::npos ? "" : s.substr(e);
  if (mantissa.find('.') != std::string::npos) {
    mantissa.erase(mantissa.find_last_not_of('0') + 1);
    if (mantissa.back() == '.') mantissa.pop_back();
  }
  return mantissa + rest;
}

std::string list_of(const std::vector<std::string>& items) {
  std::string s;
  for (std::size_t k = 0; k < items.size(); ++k) {
    if (k > 0) s += k + 1 == items.size() ? " and " : ", ";
    s += items[k];
  }
  return s;
}

std::string listing(std::vector<double> v) {
  std::sort(v.begin(), v.end(), TotalLess());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  if (v.empty()) return "–";
  std::vector<std::string> items;
  for (double x : v)
    items.push_back(value_text(x));
  return list_of(items);
}

std::string significant(double v, int digits) {
  return fmt::format("{:.{}g}", v, digits);
}

std::string beside_thresholds(double v, std::initializer_list<double> thresholds, int digits) {
  constexpr int kMostDigits = 6;
  auto side = [](double x, double t) { return (x > t) - (x < t); };
  for (int d = digits;; ++d) {
    const std::string s = significant(v, d);
    const double shown = std::stod(s);
    bool same_side = true;
    for (const double t : thresholds)
      same_side = same_side && side(shown, t) == side(v, t);
    if (same_side || d >= kMostDigits) return s;
  }
}

std::string value_text(double v) {
  const double a = std::abs(v);
  return a == 0 || (a >= 1e-2 && a < 1e5) ? shortest(v) : param(v);
}

std::vector<double> numbers(const std::vector<ojson>& rows, const char* column) {
  std::vector<double> v;
  for (const auto& r : rows)
    if (has_number(r, column)) v.push_back(r[column].get<double>());
  return v;
}

std::string listing(const std::vector<ojson>& rows, const char* column) {
  return listing(numbers(rows, column));
}

std::string span(const std::vector<double>& v) {
  if (v.empty()) return "–";
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end(), TotalLess());
  return *lo == *hi ? value_text(*lo) : value_text(*lo) + " to " + value_text(*hi);
}

std::string span(const std::vector<double>& v, int digits) {
  std::vector<double> r;
  for (double x : v)
    r.push_back(std::stod(significant(x, digits)));
  return span(r);
}

std::string edge_search_text(const EdgeOptions& o) {
  return "a log-spaced scan of dt, " + std::to_string(o.per_octave) + " per octave, from " +
         shortest(o.scan_low) + " to " + shortest(o.scan_high) + " times h/c (at most T / " +
         std::to_string(kMinStepsToJudge) +
         ": a run of fewer steps gets no verdict), then bisection until the lowest failing dt is "
         "within " +
         percent(o.tolerance) + " of the largest surviving one, then " +
         std::to_string(o.below_points) + " dts from " + shortest(o.below_span) +
         " times the edge up to it; a failure there moves the edge below it, and the search "
         "bisects and scans below the new edge again. Each edge is the lowest failure found";
}

std::string percent(double fraction) {
  return shortest(100 * fraction) + "%";
}

std::string codes(const std::vector<std::string>& names, int first) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i)
    out += (i ? ", " : "") + std::to_string(first + int(i)) + " " + names[i];
  return out;
}

std::string rule_cells(std::size_t n) {
  std::string s;
  for (std::size_t k = 0; k < n; ++k)
    s += "---|";
  return s;
}

std::string opt_fixed(std::optional<double> v, int decimals) {
  return v ? fixed(*v, decimals) : "–";
}

std::string opt_sci(const ojson& v) {
  return v.is_number() ? sci(v.get<double>()) : "–";
}

std::string opt_sci(const std::optional<double>& v) {
  return v ? sci(*v) : "–";
}

std::string text(const ojson& row, const char* column) {
  const auto it = row.find(column);
  return it != row.end() && it->is_string() ? it->get<std::string>() : std::string();
}

bool has_number(const ojson& r, const char* column) {
  return r.contains(column) && r[column].is_number();
}

double number_or_zero(const ojson& row, const char* column) {
  const auto it = row.find(column);
  return it != row.end() && it->is_number() ? it->get<double>() : 0.0;
}

ReportRuns report_runs_of(const ojson& entry) {
  if (!entry.is_object() || !entry.contains("report_runs") || !entry["report_runs"].is_object())
    return {};
  const ojson& j = entry["report_runs"];
  return {true, static_cast<std::size_t>(std::llround(number_or_zero(j, "runs"))),
          number_or_zero(j, "particle_steps"), number_or_zero(j, "cpu_seconds")};
}

ojson report_runs_json(std::int64_t runs, double particle_steps, double seconds) {
  return {{"runs", runs}, {"particle_steps", particle_steps}, {"cpu_seconds", seconds}};
}

std::string cost_metric_text() {
  return "**Cost.** Every cost here is in particle-steps (particles x steps, of every run a "
         "result needs): deterministic, the same on any machine. What one particle-step of each "
         "method costs in time is measured, with Google Benchmark, in [performance.md]"
         "(performance.md#the-step-kernel) (ns per particle-step per basis, transfer and update "
         "order): particle-steps times that is the time on the measured machine.";
}

bool crossing_free(const ojson& r) {
  if (has_number(r, "crossings")) return r["crossings"].get<double>() == 0;
  if (!has_number(r, "A_over_h") || !has_number(r, "ppc")) return false;
  return r["A_over_h"].get<double>() < 1.0 / (2 * r["ppc"].get<double>());
}

std::string order_regime_text() {
  return "an order is fitted only over points in the regime it describes: runs that end stable "
         "over at least " +
         shortest(kMinWavePasses) + " wave pass c T / L and accurate (error over time below " +
         shortest(kAccurateFraction) +
         " A) and, for an order in h, in which no particle crosses a cell (no crossing recorded; "
         "where crossings are not recorded, A / h below 1 / (2 ppc)); a point outside it is "
         "shown and marked, never fitted, and at least three points are needed";
}

std::optional<double> loglog_slope(const std::vector<std::pair<double, double>>& points) {
  std::vector<std::pair<double, double>> xy;
  for (const auto& [x, y] : points) {
    if (x > 0 && y > 0) xy.emplace_back(std::log(x), std::log(y));
  }
  if (xy.size() < 3) return std::nullopt;
  double mx = 0, my = 0;
  for (const auto& [x, y] : xy) {
    mx += x;
    my += y;
  }
  mx /= double(xy.size());
  my /= double(xy.size());
  double sxy = 0, sxx = 0;
  for (const auto& [x, y] : xy) {
    sxy += (x - mx) * (y - my);
    sxx += (x - mx) * (x - mx);
  }
  return sxx > 0 ? std::optional<double>(sxy / sxx) : std::nullopt;
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end(), TotalLess());
  const double pos = q * double(v.size() - 1);
  const std::size_t i = static_cast<std::size_t>(pos);
  return i + 1 < v.size() ? v[i] + (pos - double(i)) * (v[i + 1] - v[i]) : v.back();
}

std::string link(const fs::path& from_dir, const fs::path& target) {
  return fs::relative(target, from_dir).generic_string();
}

std::string sci(double v, int digits) {
  if (v == 0) return "0";
  if (!std::isfinite(v)) return std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf");
  // 5.1e-05 -> 5.1e-5, 1.0e+04 -> 1.0e4
  const std::string s = fmt::format("{:.{}e}", v, digits - 1);
  const auto e = s.find('e');
  std::string mantissa = s.substr(0, e);
  std::string exponent = s.substr(e + 1);
  const bool negative = exponent[0] == '-';
  exponent = exponent.substr(1);
  exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
  if (exponent == "0") return mantissa;
  return mantissa + "e" + (negative ? "-" : "") + exponent;
}

}  // namespace mpmstab
