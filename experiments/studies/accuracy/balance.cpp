// The balance study: where the time error and the spatial error of a run balance, against the
// grid. For each method, scene and grid, the error over time e(C) at each Courant number C is
// fitted by e(C) = S + k C^p (S >= 0, the floor the error keeps as C goes to zero; k C^p, k > 0,
// p > 0, the time term), by least squares on the logarithms of the errors. The balancing C is
// where the fitted time term equals the floor, (S / k)^(1 / p), reported where it lies within
// the C the curve measured. The time term is resolved where its fitted value at the largest C
// measured is at least S / kResolved, negligible otherwise. FMPM(8) rows test one cause of a
// first-order time error, FLIP's lumped-mass re-projection; the rows with a half-step start test
// the other, a start from rest with a non-zero acceleration: where the half-step start leaves a
// negligible time term on a curve whose exact start has a resolved one, that time term and the
// balance it makes are a start-up effect.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>

#include "claims.hpp"
#include "csv.hpp"
#include "key.hpp"
#include "report_util.hpp"
#include "run_row.hpp"
#include "study.hpp"

namespace mpmstab::studies::balance {
namespace {

using ojson = nlohmann::ordered_json;

// The range of p, and the step of the grid it is first searched on.
constexpr double kOrderLow = 0.25;
constexpr double kOrderHigh = 4;
constexpr double kOrderStep = 0.025;
// For each p, v = ln(S / (k C_max^p)), the floor against the time term at the curve's largest C,
// is searched from ln((C_min / C_max)^p / kReach) (the floor a 1 / kReach of the time term at
// the smallest C) to ln(kReach) (kReach times the time term at the largest C), first on a grid
// of step kLogStep. Beyond those ends lie the fits with no floor and with no time term.
constexpr double kReach = 1e9;
constexpr double kLogStep = 0.1;
// Golden-section steps that refine each grid minimum (the bracket shrinks to 0.618^n of two
// grid steps: below the resolution of a double).
constexpr int kGoldenSteps = 80;
// A curve is fitted where it has at least this many points (three parameters, one to spare).
constexpr std::size_t kFitPoints = 4;
// The time term is resolved where k C_max^p >= S / kResolved, negligible otherwise.
constexpr double kResolved = 4;
// An order agrees with first or second order within this.
constexpr double kOrderTolerance = 0.5;
// The scene that starts with zero acceleration (the other starts from rest).
constexpr const char* kStillScene = "bar";

// What the least-squares fit found: a floor and a time term, no floor (S = 0, the pure power
// law), or no time term (k = 0, the errors are fitted best by a constant).
enum class FitForm { floor_and_term, no_floor, no_term };

struct Fit {
  FitForm form = FitForm::floor_and_term;
  double S = 0, k = 0;
  std::optional<double> p;  // none where k = 0
  double rms = 0;           // sqrt(mean over the points of (ln e - ln(S + k C^p))^2)
};

// The sum of squared log residuals of e = k (b^p + C^p) = S + k C^p over the points, as a
// function of p and the floor against the time term at C_max, with ln k at its least-squares
// value (the mean residual).
class LogResiduals {
 public:
  explicit LogResiduals(const std::vector<std::pair<double, double>>& points) {
    for (const auto& [C, e] : points) {
      u_.push_back(std::log(C));
      y_.push_back(std::log(e));
    }
    d_.resize(u_.size());
    u_max_ = *std::max_element(u_.begin(), u_.end());
  }

  double u_max() const { return u_max_; }

  // At p and v = ln(S / (k C_max^p)), so that S = k b^p with ln(b^p) = p ln C_max + v.
  double at(double p, double v, double* log_k = nullptr) {
    const double n = static_cast<double>(u_.size());
    double mean = 0;
    const double x = p * u_max_ + v;
    for (std::size_t i = 0; i < u_.size(); ++i) {
      // ln(b^p + C^p) = ln(e^x + e^z), without overflow.
      const double z = p * u_[i];
      d_[i] = y_[i] - (std::max(x, z) + std::log1p(std::exp(-std::abs(x - z))));
      mean += d_[i];
    }
    mean /= n;
    double sum = 0;
    for (const double d : d_)
      sum += (d - mean) * (d - mean);
    if (log_k) *log_k = mean;
    return sum;
  }

  // The power law e = k C^p (S = 0): p is the least-squares slope of ln e against ln C,
  // clamped to [kOrderLow, kOrderHigh] (the sum of squares is quadratic in p).
  double no_floor(double& p, double& log_k) const {
    const double n = static_cast<double>(u_.size());
    double mu = 0, my = 0;
    for (std::size_t i = 0; i < u_.size(); ++i) {
      mu += u_[i];
      my += y_[i];
    }
    mu /= n;
    my /= n;
    double suy = 0, suu = 0;
    for (std::size_t i = 0; i < u_.size(); ++i) {
      suy += (u_[i] - mu) * (y_[i] - my);
      suu += (u_[i] - mu) * (u_[i] - mu);
    }
    p = std::clamp(suu > 0 ? suy / suu : kOrderLow, kOrderLow, kOrderHigh);
    log_k = my - p * mu;
    double sum = 0;
    for (std::size_t i = 0; i < u_.size(); ++i) {
      const double r = y_[i] - log_k - p * u_[i];
      sum += r * r;
    }
    return sum;
  }

  // The constant e = S (k = 0).
  double no_term(double& log_S) const {
    const double n = static_cast<double>(y_.size());
    log_S = 0;
    for (const double y : y_)
      log_S += y;
    log_S /= n;
    double sum = 0;
    for (const double y : y_)
      sum += (y - log_S) * (y - log_S);
    return sum;
  }

 private:
  std::vector<double> u_, y_, d_;  // ln C, ln e, the residuals of the last evaluation
  double u_max_ = 0;               // ln C_max
};

// The minimum of f over [lo, hi] by golden-section search: (x, f(x)).
template <class F>
std::pair<double, double> golden(const F& f, double lo, double hi) {
  const double r = (std::sqrt(5.0) - 1) / 2;
  double x1 = hi - r * (hi - lo), x2 = lo + r * (hi - lo);
  double f1 = f(x1), f2 = f(x2);
  for (int step = 0; step < kGoldenSteps; ++step) {
    if (f1 <= f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - r * (hi - lo);
      f1 = f(x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + r * (hi - lo);
      f2 = f(x2);
    }
  }
  return f1 <= f2 ? std::pair{x1, f1} : std::pair{x2, f2};
}

// The minimum of f over [lo, hi]: the least of a grid of step `step` (both ends included),
// refined by golden-section search between its two neighbours (kept where it is lower).
template <class F>
std::pair<double, double> grid_then_golden(const F& f, double lo, double hi, double step) {
  const int n = std::max(1, static_cast<int>(std::ceil((hi - lo) / step)));
  const auto x_at = [&](int j) { return j == n ? hi : lo + j * step; };
  int best = 0;
  double best_f = f(x_at(0));
  for (int j = 1; j <= n; ++j) {
    const double v = f(x_at(j));
    if (v < best_f) {
      best = j;
      best_f = v;
    }
  }
  const auto refined = golden(f, x_at(std::max(0, best - 1)), x_at(std::min(n, best + 1)));
  return refined.second < best_f ? refined : std::pair{x_at(best), best_f};
}

// The least-squares fit of ln e = ln(S + k C^p) to the points (C, e), C descending and e
// positive.
Fit fit_curve(const std::vector<std::pair<double, double>>& points) {
  LogResiduals r(points);
  const double c_min = points.back().first, c_max = points.front().first;
  // For each p the best v; over p the best of those.
  const auto best_v = [&](double p) {
    const double lo = p * std::log(c_min / c_max) - std::log(kReach), hi = std::log(kReach);
    return grid_then_golden([&](double v) { return r.at(p, v); }, lo, hi, kLogStep);
  };
  const double p = grid_then_golden([&](double q) { return best_v(q).second; }, kOrderLow,
                                    kOrderHigh, kOrderStep)
                       .first;
  const double v = best_v(p).first;
  double log_k = 0;
  double best = r.at(p, v, &log_k);
  Fit fit{FitForm::floor_and_term, std::exp(log_k + p * r.u_max() + v), std::exp(log_k), p};
  // The two ends of the search over v: no floor (S = 0) and no time term (k = 0).
  double p0 = 0, log_k0 = 0;
  const double no_floor = r.no_floor(p0, log_k0);
  if (no_floor <= best) {
    best = no_floor;
    fit = {FitForm::no_floor, 0, std::exp(log_k0), p0};
  }
  double log_S = 0;
  const double no_term = r.no_term(log_S);
  if (no_term <= best) {
    best = no_term;
    fit = {FitForm::no_term, std::exp(log_S), 0, std::nullopt};
  }
  fit.rms = std::sqrt(best / static_cast<double>(points.size()));
  return fit;
}
struct Curve {
  std::string scene, method;
  int cells = 0;
  std::vector<const ojson*> rows;                 // its runs, those left out included
  std::vector<std::pair<double, double>> points;  // (C, error over time), C descending
  std::vector<double> left_out;   // the C of runs not stable, accurate and crossing-free
  bool complete = true;           // no run left out at a C below one that entered (report_util.hpp)
  std::optional<Fit> fit;         // where there are at least kFitPoints points
  std::optional<double> b;        // (S / k)^(1 / p), where the fit has a floor and a time term
  std::optional<double> balance;  // b, where within the measured C
  std::string balance_note;       // why there is none: "above C = 0.8", "none: S = 0"
  // k C_max^p / S: the fitted time term at the largest C measured against the floor (infinite
  // where S = 0, zero where k = 0).
  double time_share = 0;
  // The time term of an exact-start curve is a start-up effect: it is resolved, and the same
  // method, scene and grid with the half-step start has a negligible one. None where the exact
  // start's time term is not resolved or the curve has no fitted half-step twin.
  std::optional<bool> start_up;
  bool resolved() const { return fit && time_share >= 1 / kResolved; }
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

bool consistent_mass(const std::string& method) {
  return method.find("fmpm") != std::string::npos;
}

// The fit of a curve, its balancing C and its time share.
void fit_into(Curve& c) {
  const bool positive = std::all_of(c.points.begin(), c.points.end(),
                                    [](const auto& p) { return p.first > 0 && p.second > 0; });
  if (c.points.size() < kFitPoints || !positive) return;
  c.fit = fit_curve(c.points);
  const Fit& f = *c.fit;
  const double c_max = c.points.front().first, c_min = c.points.back().first;
  switch (f.form) {
    case FitForm::no_floor:
      c.balance_note = "none: S = " + shortest(f.S);
      c.time_share = std::numeric_limits<double>::infinity();
      return;
    case FitForm::no_term:
      c.balance_note = "none: k = " + shortest(f.k);
      c.time_share = 0;
      return;
    case FitForm::floor_and_term:
      break;
  }
  const double b = std::pow(f.S / f.k, 1 / *f.p);
  c.b = b;
  c.time_share = f.k * std::pow(c_max, *f.p) / f.S;
  if (b < c_min)
    c.balance_note = "below C = " + shortest(c_min);
  else if (b > c_max)
    c.balance_note = "above C = " + shortest(c_max);
  else
    c.balance = b;
}

std::map<CurveKey, Curve> curves(const std::vector<ojson>& rows) {
  std::map<CurveKey, Curve> out;
  for (const auto& r : rows) {
    const CurveKey key{text(r, "scene"), curve_label(r), r["cells"].get<int>()};
    Curve& c = out[key];
    std::tie(c.scene, c.method, c.cells) = key;
    c.rows.push_back(&r);
    if (!accurate_run(r) || !crossing_free(r)) {
      c.left_out.push_back(r["cfl_factor"].get<double>());
      continue;
    }
    c.points.emplace_back(r["cfl_factor"].get<double>(), *RunRow(r).error_over_time);
  }
  for (auto& [key, c] : out) {
    // A run left out above every C that entered is the stability limit, not a gap in the curve.
    for (const double C : c.left_out)
      for (const auto& p : c.points)
        if (C < p.first) c.complete = false;
    std::sort(c.points.begin(), c.points.end(),
              [](const auto& a, const auto& b) { return TotalLess()(b.first, a.first); });
    fit_into(c);
  }
  for (auto& [key, c] : out) {
    const auto twin = out.find({c.scene, c.method + kHalfStep, c.cells});
    if (!half_step(c.method) && c.resolved() && twin != out.end() && twin->second.fit)
      c.start_up = !twin->second.resolved();
  }
  return out;
}

// Per method and scene: the grids in order, and the slope of log(balancing C) against log(h)
// over the grids where it lies within the scan (at least three).
struct Trend {
  std::map<int, const Curve*> grids;  // by cells
  std::optional<double> slope;
  bool falls = false;  // the balancing C falls with every refinement where within the scan
  int bracketed = 0;
};

// How many curves (or methods and scenes) a claim is about, how many of them satisfy it, and
// where their runs lie: those it counts (on) and, for a claim that counts none, those it searched.
struct Count {
  int hits = 0, n = 0;
  Coverage on, searched;
  void add(bool hit) {
    ++n;
    hits += hit;
  }
  void add(bool hit, const Curve& c) {
    add(hit);
    cover(on, c);
  }
  static void cover(Coverage& runs, const Curve& c) {
    for (const ojson* r : c.rows)
      runs.add(*r);
  }
};

std::string scene_name(const std::string& scene) {
  return scene == "steffen" ? "neo-Hookean" : scene;
}

// What the study finds: every curve with its fit and balance, the trends with the grid, and the
// counts its claims and its index paragraph give.
struct Findings {
  std::map<CurveKey, Curve> curves;
  std::map<std::pair<std::string, std::string>, Trend> trends;  // by scene and method
  std::set<int> grids;                                          // the cells of every curve
  Count flip_first, fmpm_second, falls, start_up, half_second, still_none;
  std::vector<std::string> untwinned;  // resolved exact-start curves without a fitted twin
};

// The findings: every curve, fitted, and what the claims count of them.
Findings find(const std::vector<ojson>& rows) {
  Findings f;
  f.curves = curves(rows);
  for (const auto& [key, c] : f.curves) {
    f.trends[{c.scene, c.method}].grids[c.cells] = &c;
    f.grids.insert(c.cells);
    if (!c.fit) continue;
    if (c.scene == kStillScene) f.still_none.add(c.time_share < 1, c);
    const bool half = half_step(c.method), fmpm = !half && consistent_mass(c.method);
    Count& order = half ? f.half_second : fmpm ? f.fmpm_second : f.flip_first;
    Count::cover(order.searched, c);
    if (!c.resolved()) continue;
    order.add(std::abs(*c.fit->p - (half || fmpm ? 2 : 1)) <= kOrderTolerance, c);
    if (half) continue;
    // Every resolved exact-start curve: one without a fitted half-step twin counts against the
    // start-up claim, and is named.
    f.start_up.add(c.start_up.value_or(false), c);
    if (const auto twin = f.curves.find({c.scene, c.method + kHalfStep, c.cells});
        twin != f.curves.end())
      Count::cover(f.start_up.on, twin->second);
    if (!c.start_up)
      f.untwinned.push_back(c.method + " on the " + scene_name(c.scene) + " scene at " +
                            std::to_string(c.cells) + " cells");
  }
  for (auto& [key, t] : f.trends) {
    std::vector<std::pair<double, double>> xy;
    std::optional<double> previous;
    t.falls = true;
    for (const auto& [cells, c] : t.grids) {
      if (!c->balance) continue;
      ++t.bracketed;
      xy.emplace_back(1.0 / cells, *c->balance);
      if (previous && !(*c->balance < *previous)) t.falls = false;
      previous = c->balance;
    }
    t.slope = loglog_slope(xy);
    if (consistent_mass(key.second) || half_step(key.second) || t.bracketed < 2) continue;
    f.falls.add(t.falls);
    for (const auto& [cells, c] : t.grids)
      Count::cover(f.falls.on, *c);
  }
  return f;
}

// A claim about every curve (or method and scene) of a kind, "{hits} of {n} curves", with the
// value its statement names first (none where `value` is empty), measured on the curves it counts
// (on none: those it searched).
Claim every_curve(const char* id, const char* statement, const char* evidence, const char* hits,
                  const Count& count, const char* name = "", const std::string& value = "") {
  Claim c = claim(id, statement, evidence);
  if (!value.empty()) c.value(name, value);
  return c.every(hits, count.hits, "n", count.n).on(count.n > 0 ? count.on : count.searched);
}

std::vector<Claim> balance_claims(const Findings& f) {
  const std::string tol = shortest(kOrderTolerance);
  Claim start = every_curve(
      "balance-is-start-up-effect",
      "The balance is a start-up effect: on every method, scene and grid of this study where the "
      "exact start's fitted time term is resolved (which includes every curve whose balancing C "
      "lies within or "
      "under the scan), the half-step start leaves a negligible time term (its fitted k C^p under "
      "S / {resolved} at every measured C)",
      "{removed} of {n} curves; {untwinned} of them without a fitted half-step twin, counted as "
      "not removed{named}",
      "removed", f.start_up, "resolved", shortest(kResolved));
  start.count("untwinned", static_cast<long long>(f.untwinned.size()))
      .value("named", f.untwinned.empty() ? "" : ": " + list_of(f.untwinned));
  return {
      every_curve("flip-time-error-first-order",
                  "With FLIP, USL and the exact start the fitted time order p is first order in C "
                  "(within {tol}) on every method, scene and grid where the time term is resolved",
                  "{first} of {n} curves", "first", f.flip_first, "tol", tol),
      every_curve("consistent-mass-restores-second-order",
                  "With the consistent mass nearly restored (FMPM of order eight) and the exact "
                  "start the fitted time order p is second order in C (within {tol}) on every "
                  "scene and grid where the time term is resolved",
                  "{second} of {n} curves", "second", f.fmpm_second, "tol", tol),
      every_curve("balance-falls-with-h",
                  "With FLIP and USL the fitted balancing C falls with every refinement of the "
                  "grid, for every method and scene where it lies within the scan on two grids or "
                  "more",
                  "{falls} of {n} methods and scenes", "falls", f.falls),
      start,
      every_curve("half-step-start-second-order",
                  "With a half-step start the fitted time order p is second order in C (within "
                  "{tol}) wherever the time term is resolved",
                  "{second} of {n} curves", "second", f.half_second, "tol", tol),
      every_curve("no-balance-without-initial-acceleration",
                  "On the {scene} scene, which starts with zero acceleration, the fitted time term "
                  "stays under S at every measured C (no balancing C within or under the scan) for "
                  "every method, start and grid",
                  "{none} of {n} curves", "none", f.still_none, "scene", kStillScene)};
}

std::string balance_text(const Curve& c) {
  if (c.balance) return significant(*c.balance, 3);
  return c.balance_note.empty() ? "–" : c.balance_note;
}

// p, with `†` where it lies at an end of the range it is searched over.
std::string order_text(const Curve& c) {
  if (!c.fit || !c.fit->p) return "–";
  const double p = *c.fit->p;
  const double near = kOrderStep * 1e-6;
  return fixed(p, 2) + (p <= kOrderLow + near || p >= kOrderHigh - near ? " †" : "");
}

std::string time_term_text(const Curve& c) {
  return !c.fit ? "–" : c.resolved() ? "resolved" : "negligible";
}

std::string balance_table(const Findings& f) {
  std::ostringstream md;
  md << "| scene | method |";
  for (int n : f.grids)
    md << " " << n << " cells: balancing C (p) |";
  md << " slope of log(balancing C) against log(h) |\n|---|---|" << rule_cells(f.grids.size() + 1)
     << "\n";
  for (const auto& [key, t] : f.trends) {
    md << "| " << scene_name(key.first) << " | " << key.second << " |";
    for (int n : f.grids) {
      const auto it = t.grids.find(n);
      if (it == t.grids.end()) {
        md << " |";
        continue;
      }
      const Curve& c = *it->second;
      md << " " << balance_text(c) << " (" << order_text(c) << ")" << (c.complete ? "" : " ‡")
         << " |";
    }
    md << " " << opt_fixed(t.slope, 2) << " |\n";
  }
  return md.str();
}

std::string fits_table(const std::map<CurveKey, Curve>& all) {
  std::ostringstream md;
  md << "| scene | method | cells | S | k | p | RMS of ln residuals (ln e − ln fit) | balancing C "
        "| time term | k C_max^p / S |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [key, c] : all) {
    md << "| " << scene_name(c.scene) << " | " << c.method << " | " << c.cells << " | ";
    if (!c.fit) {
      md << "– | – | – | – | – | – | – |\n";
      continue;
    }
    const Fit& f = *c.fit;
    md << sci(f.S, 3) << " | " << sci(f.k, 3) << " | " << order_text(c) << " | " << sci(f.rms, 2)
       << " | " << balance_text(c) << (c.complete ? "" : " ‡") << " | " << time_term_text(c)
       << " | " << (std::isfinite(c.time_share) ? sci(c.time_share, 2) : std::string("–"))
       << " |\n";
  }
  return md.str();
}

std::string curves_table(const std::map<CurveKey, Curve>& all) {
  std::ostringstream md;
  md << "| scene | method | cells | error over time at each C (C: error) |\n"
        "|---|---|---|---|\n";
  for (const auto& [key, c] : all) {
    md << "| " << scene_name(c.scene) << " | " << c.method << " | " << c.cells << " | ";
    for (std::size_t k = 0; k < c.points.size(); ++k)
      md << (k ? "; " : "") << shortest(c.points[k].first) << ": " << sci(c.points[k].second);
    md << " |\n";
  }
  return md.str();
}

ojson curves_json(const std::map<CurveKey, Curve>& all) {
  ojson out = ojson::array();
  for (const auto& [key, c] : all) {
    const bool fitted = c.fit.has_value();
    out.push_back(
        {{"scene", c.scene},
         {"method", c.method},
         {"cells", c.cells},
         {"points", c.points.size()},
         {"S", fitted ? ojson(c.fit->S) : ojson(nullptr)},
         {"k", fitted ? ojson(c.fit->k) : ojson(nullptr)},
         {"p", fitted && c.fit->p ? ojson(*c.fit->p) : ojson(nullptr)},
         {"rms_log_residual", fitted ? ojson(c.fit->rms) : ojson(nullptr)},
         {"b", c.b ? ojson(*c.b) : ojson(nullptr)},
         {"balancing_courant", c.balance ? ojson(*c.balance) : ojson(nullptr)},
         {"balance_note", c.balance_note.empty() ? ojson(nullptr) : ojson(c.balance_note)},
         {"time_share",
          fitted && std::isfinite(c.time_share) ? ojson(c.time_share) : ojson(nullptr)},
         {"time_term", fitted ? ojson(time_term_text(c)) : ojson(nullptr)},
         {"start_up_effect", c.start_up ? ojson(*c.start_up) : ojson(nullptr)}});
  }
  return out;
}

StudyReport balance_report(const ReportContext& ctx) {
  const Findings f = find(ctx.rows);
  std::ostringstream md;
  md << "## Results\n\nPer method, scene and grid the error over time e at the Courant numbers C "
        "run is fitted by e(C) = S + k C^p: S is the floor the error keeps as C goes to zero (the "
        "spatial error), k C^p the time term. The fit is a nonlinear least-squares fit in log "
        "space: it minimises the sum over the measured C of (ln e − ln(S + k C^p))² over S "
        "non-negative, k positive and p from "
     << shortest(kOrderLow) << " to " << shortest(kOrderHigh)
     << ". With b the p-th root of S/k (the C at which k C^p = S) the model reads ln e = ln k + "
        "ln(b^p + C^p), in which ln k enters linearly and is solved for exactly. C_min and C_max "
        "are the smallest and largest C of the curve; p is searched on a grid of step "
     << shortest(kOrderStep)
     << " and, for each p, v = ln(S / (k C_max^p)), the floor against the time term at C_max, on "
        "a grid of step "
     << shortest(kLogStep) << " from ln((C_min / C_max)^p / " << value_text(kReach)
     << ") (the floor a " << value_text(1 / kReach) << " of the time term at C_min) to ln("
     << value_text(kReach)
     << "); each grid minimum is "
        "refined by "
     << kGoldenSteps
     << " steps of golden-section search. The two ends of that search, no floor (S zero, p the "
        "least-squares slope of ln e against ln C clamped to its range) and no time term (k zero, "
        "e constant), replace the fit where their sum of squares is not larger. A curve is fitted "
        "where at least "
     << kFitPoints
     << " of its runs enter. The *RMS of ln residuals* is the square root of the mean over the "
        "measured C of (ln e − ln(S + k C^p))², the typical relative misfit of the fit. The "
        "*balancing C* is b where it lies between C_min and C_max, \"below\" or \"above\" the scan "
        "where it lies outside, and \"none\" with the parameter that is zero where the fit puts no "
        "floor (S) or no time term (k). The time term is *resolved* where its fitted value at "
        "C_max, k C_max^p, is at least S / "
     << shortest(kResolved) << ", and *negligible* otherwise (then k C^p is under S / "
     << shortest(kResolved)
     << " at every measured C, since it rises with C); a fitted p is compared with first or "
        "second order only where the time term is resolved. The time term of a curve with the "
        "exact start, and with it its balance, is a *start-up effect* where it is resolved and the "
        "same method, scene and grid with the half-step start has a negligible time term; a curve "
        "that balances within or under the scan has a resolved time term.\n\nOnly runs that end "
        "stable and accurate and in which no particle crosses a cell enter; a run left out at the "
        "largest C is the stability limit (the curve starts below it), and `‡` marks a grid where "
        "one was left out below a C that entered. Each balancing C is that of one curve, one "
        "scene, method and grid, and the last column fits log of the balancing C against log(h) "
        "over the grids of one scene and method where it lies within the scan (at least three): no "
        "balancing C of one scene is applied to another scene in this report. A positive slope q "
        "means the balancing C falls as h^q and the balancing step dt = C h / c as h times h^q, so "
        "a C that balances on one grid leaves the time error above the spatial one on a finer "
        "grid.\n\n"
     << balance_table(f)
     << "\nTwo candidates for a first-order time term are tested: FLIP's lumped-mass "
        "re-projection, by the rows of FMPM of order eight (the consistent mass nearly restored), "
        "and a start from rest with a non-zero acceleration (the neo-Hookean scene starts at rest, "
        "the bar with its acceleration zero), by the rows with a half-step start (the particles' "
        "velocity starts half a step before the start, so that the velocity of the first position "
        "update lies half a step after it, as the leapfrog's staggered start has it). The claims "
        "above say which one moves the balance.\n"
     << "\n### The fit of each curve\n\n"
        "k C_max^p / S is the fitted time term at the largest measured C against the floor (– "
        "where S is zero); `†` marks a p at an end of the range it is searched over, where that "
        "range, not the data, stops the fit.\n\n"
     << fits_table(f.curves) << "\n### Each curve\n\n"
     << curves_table(f.curves);
  return StudyReport{.markdown = md.str(),
                     .json = {{"curves", curves_json(f.curves)}},
                     .claims = balance_claims(f)};
}
std::string balance_index(const Spec& spec, const std::vector<ojson>&, const ojson& published) {
  // The report's counts, from the curves it published (curves_json): a fitted curve has its S,
  // a balancing C within the scan is published where there is one.
  int fitted = 0, bracketed = 0;
  if (published.contains("curves")) {
    for (const auto& c : published["curves"]) {
      fitted += !c["S"].is_null();
      bracketed += !c["balancing_courant"].is_null();
    }
  }
  return "**What it shows.** The fit e(C) = S + k C^p of the error over time against the Courant "
         "number per method, scene and grid, and the C at which its time term equals its floor (" +
         std::to_string(bracketed) + " of " + std::to_string(fitted) +
         " fitted curves balance within the scan): [" + spec.name + ".md](" + spec.name +
         ".md).\n\n";
}

const StudyRegistration kBalance{{
    .name = "balance",
    .summary = "the Courant number where time and space errors balance, against the grid",
    .records = {.error_over_time = true, .crossings = true},
    .report = balance_report,
    .index = balance_index,
}};

}  // namespace
}  // namespace mpmstab::studies::balance
