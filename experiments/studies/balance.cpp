// The balance study: where the time error and the spatial error of a run balance, against the
// grid. For each method, scene and grid, the error over time e(C) at each Courant number C; the
// plateau is e at the smallest C (the spatial error, with what time error is left there), the
// time part is e(C) less the plateau, the balancing C is where the time part equals the plateau
// (interpolated on log axes between the two C that bracket it), and the time order is the slope
// of log(time part) against log(C) over the C where the time part is at least the plateau /
// kVisible. Why a fixed C is not accurate on every grid: where the time order is below the
// spatial one, the balancing C falls as the grid is refined. FMPM(8) rows test one cause of a
// first-order time error, FLIP's lumped-mass re-projection.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>

#include "claims.hpp"
#include "csv.hpp"
#include "report_util.hpp"
#include "study.hpp"

namespace mpmstab {

namespace {

using ojson = nlohmann::ordered_json;

// A time part is fitted where it is at least the plateau / kVisible (smaller ones are the noise
// of the plateau's own time error).
constexpr double kVisible = 4;
// An order agrees with first or second order within this.
constexpr double kOrderTolerance = 0.5;

// ---------------------------------------------------------------------------------------------
// Findings

struct Curve {
  std::string scene, method;
  int cells = 0;
  std::vector<std::pair<double, double>> points;  // (C, error over time), C descending
  std::vector<double> left_out;   // the C of runs not stable, accurate and crossing-free
  bool complete = true;           // no run left out at a C below one that entered (report_util.hpp)
  double plateau = 0;             // the error at the smallest C
  std::optional<double> balance;  // the balancing C
  std::string balance_note;       // why there is none: "above C = 0.8", "below C = 0.05"
  std::optional<double> order;    // the time order
};

using CurveKey = std::tuple<std::string, std::string, int>;

constexpr const char* kHalfStep = ", half-step start";

// A curve's method: the method label, and the start where it is the half step.
std::string curve_label(const ojson& r) {
  return method_label(r) + (text(r, "start") == "half_step" ? kHalfStep : "");
}

bool half_step(const std::string& label) {
  return label.find(kHalfStep) != std::string::npos;
}

std::map<CurveKey, Curve> curves(const std::vector<ojson>& rows) {
  std::map<CurveKey, Curve> out;
  for (const auto& r : rows) {
    const CurveKey key{text(r, "scene"), curve_label(r), r["cells"].get<int>()};
    Curve& c = out[key];
    c.scene = std::get<0>(key);
    c.method = std::get<1>(key);
    c.cells = std::get<2>(key);
    if (!accurate_run(r) || !crossing_free(r)) {
      c.left_out.push_back(r["cfl_factor"].get<double>());
      continue;
    }
    c.points.emplace_back(r["cfl_factor"].get<double>(), r["max_error_over_time"].get<double>());
  }
  for (auto& [key, c] : out) {
    // A run left out above every C that entered is the stability limit, not a gap in the curve.
    for (const double C : c.left_out)
      for (const auto& p : c.points)
        if (C < p.first) c.complete = false;
    std::sort(c.points.begin(), c.points.end(),
              [](const auto& a, const auto& b) { return TotalLess()(b.first, a.first); });
    if (c.points.size() < 3) continue;
    c.plateau = c.points.back().second;
    // The time part at each C but the smallest.
    std::vector<std::pair<double, double>> time;
    for (std::size_t k = 0; k + 1 < c.points.size(); ++k)
      time.emplace_back(c.points[k].first, c.points[k].second - c.plateau);
    std::vector<std::pair<double, double>> visible;
    for (const auto& [C, t] : time)
      if (t >= c.plateau / kVisible) visible.emplace_back(C, t);
    c.order = loglog_slope(visible);
    // The balancing C: between the C whose time part is at least the plateau and the next.
    if (time.front().second < c.plateau) {
      c.balance_note = "above C = " + shortest(time.front().first);
    } else {
      for (std::size_t k = 0; k + 1 < time.size(); ++k) {
        const auto [C1, t1] = time[k];
        const auto [C2, t2] = time[k + 1];
        if (t1 >= c.plateau && t2 < c.plateau && t2 > 0) {
          const double s = std::log(c.plateau / t2) / std::log(t1 / t2);
          c.balance = std::exp(std::log(C2) + s * std::log(C1 / C2));
          break;
        }
      }
      if (!c.balance) c.balance_note = "below C = " + shortest(time.back().first);
    }
  }
  return out;
}

// Per method and scene: the grids in order, and the slope of log(balancing C) against log(h)
// over the grids where it is bracketed (at least three).
struct Trend {
  std::vector<const Curve*> grids;
  std::optional<double> slope;
  bool falls = false;  // the balancing C falls with every refinement where bracketed
  int bracketed = 0;
};

std::map<std::pair<std::string, std::string>, Trend> trends(const std::map<CurveKey, Curve>& all) {
  std::map<std::pair<std::string, std::string>, Trend> out;
  for (const auto& [key, c] : all)
    out[{c.scene, c.method}].grids.push_back(&c);
  for (auto& [key, t] : out) {
    std::vector<std::pair<double, double>> xy;
    std::optional<double> previous;
    t.falls = true;
    for (const Curve* c : t.grids) {
      if (!c->balance) continue;
      ++t.bracketed;
      xy.emplace_back(1.0 / c->cells, *c->balance);
      if (previous && !(*c->balance < *previous)) t.falls = false;
      previous = c->balance;
    }
    t.slope = loglog_slope(xy);
  }
  return out;
}

bool consistent_mass(const std::string& method) {
  return method.find("fmpm") != std::string::npos;
}

// ---------------------------------------------------------------------------------------------
// Claims

std::vector<Claim> balance_claims(const std::map<CurveKey, Curve>& all,
                                  const std::map<std::pair<std::string, std::string>, Trend>& tr) {
  int flip_n = 0, flip_first = 0, fmpm_n = 0, fmpm_second = 0, trend_n = 0, trend_falls = 0;
  int half_n = 0, half_raised = 0, half_order_n = 0, half_second = 0;
  for (const auto& [key, c] : all) {
    if (half_step(c.method)) {
      if (c.order) {
        ++half_order_n;
        half_second += std::abs(*c.order - 2) <= kOrderTolerance;
      }
      // Against the same method, scene and grid started exactly, where that one balances.
      const std::string exact = c.method.substr(0, c.method.find(kHalfStep));
      const auto it = all.find({c.scene, exact, c.cells});
      if (it == all.end() || !it->second.balance) continue;
      ++half_n;
      half_raised += !c.balance || *c.balance > *it->second.balance;
      continue;
    }
    if (!c.order) continue;
    if (consistent_mass(c.method)) {
      ++fmpm_n;
      fmpm_second += std::abs(*c.order - 2) <= kOrderTolerance;
    } else {
      ++flip_n;
      flip_first += std::abs(*c.order - 1) <= kOrderTolerance;
    }
  }
  for (const auto& [key, t] : tr) {
    if (consistent_mass(key.second) || half_step(key.second) || t.bracketed < 2) continue;
    ++trend_n;
    trend_falls += t.falls;
  }
  Claim first = claim("flip-time-error-first-order",
                      "With FLIP, USL and the exact start the time part of the error over time is "
                      "first order in C (within {tol}) on every method, scene and grid where it "
                      "is measured",
                      "{first} of {n} curves");
  first.value("tol", shortest(kOrderTolerance)).every("first", flip_first, "n", flip_n);
  Claim second = claim("consistent-mass-restores-second-order",
                       "With the consistent mass nearly restored (FMPM of order eight) the time "
                       "part is second order in C (within {tol}) on every scene and grid where it "
                       "is measured",
                       "{second} of {n} curves");
  second.value("tol", shortest(kOrderTolerance)).every("second", fmpm_second, "n", fmpm_n);
  Claim falls = claim("balance-falls-with-h",
                      "With FLIP and USL the balancing C falls with every refinement of the grid, "
                      "for every method and scene where it is bracketed on two grids or more",
                      "{falls} of {n} methods and scenes");
  falls.every("falls", trend_falls, "n", trend_n);
  Claim raised = claim("half-step-start-raises-balance",
                       "A half-step start raises the balancing C (or takes it above the scan) on "
                       "every method, scene and grid where the exact start balances inside it",
                       "{raised} of {n} curves");
  raised.every("raised", half_raised, "n", half_n);
  Claim half_order = claim("half-step-start-second-order",
                           "With a half-step start the time part is second order in C (within "
                           "{tol}) wherever it is measured",
                           "{second} of {n} curves");
  half_order.value("tol", shortest(kOrderTolerance))
      .every("second", half_second, "n", half_order_n);
  return {first, second, falls, raised, half_order};
}

// ---------------------------------------------------------------------------------------------
// Rendering

std::string scene_name(const std::string& scene) {
  return scene == "steffen" ? "neo-Hookean" : scene;
}

std::string balance_table(const std::map<std::pair<std::string, std::string>, Trend>& tr) {
  std::ostringstream md;
  std::vector<int> cells;
  for (const auto& [key, t] : tr)
    for (const Curve* c : t.grids)
      if (std::find(cells.begin(), cells.end(), c->cells) == cells.end()) cells.push_back(c->cells);
  std::sort(cells.begin(), cells.end());
  md << "| scene | method |";
  for (int n : cells)
    md << " " << n << " cells: balancing C (time order) |";
  md << " slope of log(balancing C) against log(h) |\n|---|---|";
  for (std::size_t k = 0; k <= cells.size(); ++k)
    md << "---|";
  md << "\n";
  for (const auto& [key, t] : tr) {
    md << "| " << scene_name(key.first) << " | " << key.second << " |";
    for (int n : cells) {
      const auto it = std::find_if(t.grids.begin(), t.grids.end(),
                                   [n](const Curve* c) { return c->cells == n; });
      if (it == t.grids.end()) {
        md << " |";
        continue;
      }
      const Curve& c = **it;
      md << " "
         << (c.balance                ? significant(*c.balance, 3)
             : c.balance_note.empty() ? "–"
                                      : c.balance_note)
         << " (" << (c.order ? fixed(*c.order, 2) : std::string("–")) << ")"
         << (c.complete ? "" : " ‡") << " |";
    }
    md << " " << (t.slope ? fixed(*t.slope, 2) : std::string("–")) << " |\n";
  }
  return md.str();
}

std::string curves_table(const std::map<CurveKey, Curve>& all) {
  std::ostringstream md;
  md << "| scene | method | cells | error over time at each C (C: error) | plateau |\n"
        "|---|---|---|---|---|\n";
  for (const auto& [key, c] : all) {
    md << "| " << scene_name(c.scene) << " | " << c.method << " | " << c.cells << " | ";
    for (std::size_t k = 0; k < c.points.size(); ++k)
      md << (k ? "; " : "") << shortest(c.points[k].first) << ": " << sci(c.points[k].second);
    md << " | " << (c.points.size() >= 3 ? sci(c.plateau) : std::string("–")) << " |\n";
  }
  return md.str();
}

ojson curves_json(const std::map<CurveKey, Curve>& all) {
  ojson out = ojson::array();
  for (const auto& [key, c] : all) {
    out.push_back({{"scene", c.scene},
                   {"method", c.method},
                   {"cells", c.cells},
                   {"balancing_courant", c.balance ? ojson(*c.balance) : ojson(nullptr)},
                   {"time_order", c.order ? ojson(*c.order) : ojson(nullptr)},
                   {"plateau", c.points.size() >= 3 ? ojson(c.plateau) : ojson(nullptr)}});
  }
  return out;
}

StudyReport balance_report(const ReportContext& ctx) {
  const auto all = curves(ctx.rows);
  const auto tr = trends(all);
  std::ostringstream md;
  md << "## Results\n\nPer method, scene and grid: the *plateau* is the error over time at the "
        "smallest C run; the *time part* at a C is its error over time less the plateau; the "
        "*balancing C* is where the time part equals the plateau, interpolated on log axes "
        "between the two C that bracket it (\"above\" or \"below\" the scan where none does); "
        "the *time order* is the least-squares slope of log(time part) against log(C) over the "
        "C whose time part is at least the plateau / "
     << shortest(kVisible)
     << " (at least three). Only runs that end stable and accurate and in which no particle "
        "crosses a cell enter; a run left out at the largest C is the stability limit (the curve "
        "starts below it), and `‡` marks a grid where one was left out below a C that entered. The "
        "last column fits log of "
        "the balancing C against log(h) over the grids where it is bracketed: a positive slope q "
        "means the balancing C falls as h^q and the balancing step dt = C h / c as h times h^q, "
        "so a C that balances on one grid leaves the time error above the spatial one on a "
        "finer grid.\n\n"
     << balance_table(tr)
     << "\nTwo known causes of a first-order time term are tested: FLIP's lumped-mass "
        "re-projection, by the rows of FMPM of order eight (the consistent mass nearly "
        "restored), and a start from rest with a non-zero acceleration (the neo-Hookean scene "
        "starts at rest, the bar with its acceleration zero), by the rows with a half-step "
        "start (the particles' velocity starts half a step before the start, so that the velocity "
        "of "
        "the first position update lies half a step after it, as the leapfrog's staggered start "
        "has it). The claims "
        "above say which one moves the balance.\n"
     << "\n### Each curve\n\n"
     << curves_table(all);
  return StudyReport{.markdown = md.str(),
                     .json = {{"curves", curves_json(all)}},
                     .claims = balance_claims(all, tr)};
}

std::string balance_index(const Spec& spec, const std::vector<ojson>& rows) {
  const auto all = curves(rows);
  int bracketed = 0;
  for (const auto& [key, c] : all)
    bracketed += c.balance.has_value();
  std::ostringstream md;
  md << "**What it shows.** The Courant number at which the time error equals the spatial one, "
        "per method, scene and grid ("
     << bracketed << " of " << all.size()
     << " curves bracket it), with the order of the time error: [" << spec.name << ".md]("
     << spec.name << ".md).\n\n";
  return md.str();
}

const StudyRegistration kBalance{{
    .name = "balance",
    .summary = "the Courant number where time and space errors balance, against the grid",
    .records = {.error_over_time = true, .crossings = true},
    .report = balance_report,
    .index = balance_index,
}};

}  // namespace

}  // namespace mpmstab
