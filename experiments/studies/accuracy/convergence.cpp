// Convergence: the error over time against the grid spacing h (at a dt small enough that the
// time error does not show) and the time error against the time step (the difference from a run
// at a much smaller step on the same grid, so that the spatial error cancels), for every basis at
// several E, with the orders fitted by least squares on log-log axes, the observed order of each
// refinement, a Richardson estimate of the limit, the published orders beside ours, and Uintah's
// own order-of-accuracy baseline beside the same measurement here. Orders are fitted only to
// norms over time (the largest error after any step, and the root mean square over the body and
// the run); the error at T is shown, never fitted. A run that did not end stable (unstable, or
// meaningless: its error over time reached A) has no error and leaves its point out of the fit;
// a fit needs at least three points.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <tuple>

#include "analysis/time_error.hpp"
#include "claims.hpp"
#include "csv.hpp"
#include "key.hpp"
#include "report_util.hpp"
#include "run_row.hpp"
#include "study.hpp"

namespace mpmstab {

namespace studies::convergence {
namespace {

using ojson = nlohmann::ordered_json;

// A moment t is special for the bar when its exact displacement sin(c pi t) is near zero there:
// an error measured only at t would then measure the phase, not the amplitude.
constexpr double kSpecialFactor = 0.1;
// The time error (time_error.hpp): samples every kTimeSampleCourant h / c, runs with each
// number of substeps per sample, against a reference with kTimeReferenceSubsteps.
constexpr double kTimeSampleCourant = 0.5;
const std::vector<int> kTimeSubsteps = {1, 2, 4, 8, 16};
constexpr int kTimeReferenceSubsteps = 128;
// Orders of one method at different E agree when they lie within this of each other; a
// published order is met when ours lies within this of it.
constexpr double kOrderAgreement = 0.5;
// The refinement is in its asymptotic range when the observed orders of its last two
// refinements differ by at most this.
constexpr double kAsymptoticSpread = 0.3;
// Symplectic Euler as MPM uses it (velocity first, then the position with the new velocity) is
// the leapfrog scheme with the velocity at half steps: second order in the positions, the order
// Steffen, Kirby and Berzins (2010) measured where the time error dominates.
constexpr double kPublishedTimeOrder = 2;

// The order in h that theory allows the error of any basis here: the particle quadrature of the
// internal force is second order at best (Steffen, Kirby and Berzins 2008), whatever the degree
// of the grid's basis.
constexpr double kTheoryMaxOrder = 2;

// The published order in h of each basis for a smooth small-amplitude problem (docs/theory.md,
// "Published orders"); nullopt where none is published for this kind of problem.
struct PublishedOrder {
  std::optional<double> order;
  std::string source;
};
PublishedOrder published_order(const std::string& method) {
  if (method == "gimp" || method == "cpgimp")
    return {2.0,
            "Steffen, Wallstedt, Guilkey, Kirby and Berzins (2008); Wallstedt and Guilkey "
            "(2008): GIMP converges at second order in space while particles do not "
            "separate"};
  if (method == "bspline2")
    return {2.0,
            "Steffen, Kirby and Berzins (2008): the quadratic B-spline removes the "
            "grid-crossing error and converges at second order"};
  if (method == "mpm")
    return {std::nullopt,
            "Steffen, Kirby and Berzins (2008): the grid-crossing error of the linear basis "
            "hampers convergence once particles cross cells; no rate; Uintah's baseline below"};
  return {std::nullopt, "none published for this problem"};
}

// The three refinements a case belongs to: the bar with a fixed step refines h, the bar with
// the cfl policy refines dt, the steffen scene is the measurement beside Uintah's baseline.
std::string sweep_of(const ojson& r) {
  if (r["scene"].get<std::string>() == "steffen") return "peer";
  return r["policy"].get<std::string>() == "cfl" ? "dt" : "h";
}

// The variable of the sweep: h = 1 / cells, or dt = C h / c.
double variable(const ojson& r) {
  return sweep_of(r) == "dt" ? r["cfl_factor"].get<double>() * r["dt_cfl"].get<double>()
                             : 1.0 / r["cells"].get<double>();
}

// One point of a refinement. The norm fitted is chosen by the table (Norm).
struct Point {
  double x = 0;                      // h or dt
  std::string label;                 // its column: "h = 1/25" or "C = 0.4"
  std::optional<double> over_time;   // max over steps and particles (stable runs only)
  std::optional<double> l2_time;     // RMS over the body and the run (stable runs only)
  std::optional<double> error_at_T;  // the error at T: shown, never fitted
  std::string verdict;
  bool fit = false;  // in the regime an order is fitted in (report_util.hpp, accurate_run)
};

enum class Norm { over_time, l2_time, at_T };
std::optional<double> value_of(const Point& p, Norm n) {
  return n == Norm::over_time ? p.over_time : n == Norm::l2_time ? p.l2_time : p.error_at_T;
}

// The fitted order: the slope of log(error) against log(x) over the points with an error in the
// regime orders are fitted in (at least three).
std::optional<double> fitted_order(const std::vector<Point>& points, Norm n) {
  std::vector<std::pair<double, double>> xy;
  for (const auto& p : points) {
    if (const auto e = value_of(p, n); e && p.fit) xy.emplace_back(p.x, *e);
  }
  return loglog_slope(xy);
}

// The rows grouped by (sweep, E, method), each group's points from the coarsest to the finest.
using GroupKey = std::tuple<std::string, Key, std::string>;
std::map<GroupKey, std::vector<Point>> groups(const std::vector<ojson>& rows) {
  std::map<GroupKey, std::vector<Point>> g;
  for (const auto& r : rows) {
    Point p;
    p.x = variable(r);
    p.label = sweep_of(r) == "dt" ? "C = " + shortest(r["cfl_factor"].get<double>())
                                  : "h = 1/" + std::to_string(r["cells"].get<int>());
    p.verdict = outcome(r);
    // An order in dt asks the run to be accurate; an order in h also that no particle crossed.
    p.fit = accurate_run(r) && (sweep_of(r) == "dt" || crossing_free(r));
    if (p.verdict == "stable") {
      p.over_time = RunRow(r).error_over_time;
      if (has_number(r, "error_l2_time")) p.l2_time = r["error_l2_time"].get<double>();
      if (has_number(r, "max_error")) p.error_at_T = r["max_error"].get<double>();
    }
    g[{sweep_of(r), Key(r["E"].get<double>(), "E"), method_label(r)}].push_back(p);
  }
  for (auto& [key, points] : g)
    std::sort(points.begin(), points.end(),
              [](const Point& a, const Point& b) { return TotalLess()(b.x, a.x); });
  return g;
}

std::string order_text(const std::optional<double>& order) {
  return order ? fixed(*order, 2) : std::string("–");
}

// The observed order between two successive points, log(e1 / e2) / log(x1 / x2); none where
// either lies outside the regime orders are fitted in.
std::optional<double> step_order(const Point& coarse, const Point& fine, Norm n) {
  if (!coarse.fit || !fine.fit) return std::nullopt;
  const auto a = value_of(coarse, n), b = value_of(fine, n);
  if (!a || !b || *a <= 0 || *b <= 0) return std::nullopt;
  return std::log(*a / *b) / std::log(coarse.x / fine.x);
}

// The observed order of the last refinement in the regime orders are fitted in.
std::optional<double> last_order(const std::vector<std::optional<double>>& q) {
  for (auto it = q.rbegin(); it != q.rend(); ++it)
    if (*it) return *it;
  return std::nullopt;
}

// The observed orders of every refinement, coarsest first.
std::vector<std::optional<double>> step_orders(const std::vector<Point>& points, Norm n) {
  std::vector<std::optional<double>> q;
  for (std::size_t k = 1; k < points.size(); ++k)
    q.push_back(step_order(points[k - 1], points[k], n));
  return q;
}

// A point's cell: the error and, from the second point on, the ratio to the point before it and
// the observed order: "3.2e-5 (3.9, 1.98)"; a point outside the regime orders are fitted in is
// marked "3.2e-5 †" and has no observed order.
std::string point_text(const std::vector<Point>& points, std::size_t k, Norm n) {
  const Point& p = points[k];
  const auto e = value_of(p, n);
  if (!e) return p.verdict.empty() || p.verdict == "stable" ? std::string("–") : p.verdict;
  std::string s = sci(*e, 2) + (p.fit ? "" : " †");
  if (k > 0) {
    const auto before = value_of(points[k - 1], n);
    if (const auto o = step_order(points[k - 1], p, n); o && before)
      s += " (" + fixed(*before / *e, 2) + ", " + fixed(*o, 2) + ")";
  }
  return s;
}

// Richardson's estimate of the error's limit from the three finest points in the regime orders
// are fitted in, of a geometric refinement: with the observed order q of the last two differences,
// e_inf = e3 - (e2 - e3) / (r^q - 1), r the refinement factor. Near zero when the error converges
// to zero; a floor (a time error, the crossings) shows as a limit well above it. nullopt without
// three stable points or without a monotone trend.
std::optional<double> richardson_limit(const std::vector<Point>& all, Norm n) {
  std::vector<Point> points;  // the points in the regime orders are fitted in
  for (const auto& p : all)
    if (p.fit) points.push_back(p);
  if (points.size() < 3) return std::nullopt;
  const Point &a = points[points.size() - 3], &b = points[points.size() - 2], &c = points.back();
  const auto ea = value_of(a, n), eb = value_of(b, n), ec = value_of(c, n);
  if (!ea || !eb || !ec) return std::nullopt;
  const double d1 = *ea - *eb, d2 = *eb - *ec;
  if (!(d1 > 0 && d2 > 0 && d1 > d2)) return std::nullopt;
  const double ratio_x = b.x / c.x;
  const double q = std::log(d1 / d2) / std::log(ratio_x);
  return *ec - d2 / (std::pow(ratio_x, q) - 1);
}

std::string sweep_table(const std::map<GroupKey, std::vector<Point>>& g, const std::string& sweep,
                        Norm n) {
  std::ostringstream md;
  bool header = false;
  for (const auto& [key, points] : g) {
    const auto& [s, E, method] = key;
    if (s != sweep) continue;
    if (!header) {
      md << "| E | method |";
      for (const auto& p : points)
        md << " " << p.label << " |";
      md << " fitted order | Richardson limit | error at T, finest grid (not fitted) |\n|---|---|";
      for (std::size_t k = 0; k < points.size(); ++k)
        md << "---|";
      md << "---|---|---|\n";
      header = true;
    }
    md << "| " << shortest(E) << " | " << method << " |";
    for (std::size_t k = 0; k < points.size(); ++k)
      md << " " << point_text(points, k, n) << " |";
    const auto limit = richardson_limit(points, n);
    md << " " << order_text(fitted_order(points, n)) << " | " << (limit ? sci(*limit, 2) : "–")
       << " | " << (points.back().error_at_T ? sci(*points.back().error_at_T, 2) : "–") << " |\n";
  }
  return md.str();
}

std::string special_check(const std::vector<ojson>& rows) {
  std::map<Key, double> factor;  // E -> |sin(c pi T)|
  for (const auto& r : rows) {
    if (sweep_of(r) == "peer") continue;
    factor[Key(r["E"].get<double>(), "E")] = std::abs(
        std::sin(std::sqrt(r["E"].get<double>()) * std::acos(-1.0) * r["T"].get<double>()));
  }
  std::vector<std::string> special, fine;
  for (const auto& [E, f] : factor)
    (f < kSpecialFactor ? special : fine)
        .push_back("E = " + shortest(E) + " (" + fixed(f, 2) + ")");
  std::ostringstream md;
  md << "**The instant T.** |sin(c pi T)|, the exact displacement at T over its amplitude: "
     << list_of(fine) << (fine.empty() ? "" : ", away from zero");
  if (!special.empty()) {
    md << (fine.empty() ? "" : "; ") << list_of(special) << " below " << shortest(kSpecialFactor)
       << ", where the error at T measures the phase, not the displacement";
  }
  md << ". Every order is fitted to a norm over the whole run all the same, which no instant can "
        "make small.";
  return md.str();
}

// The orders of each method across E, for the agreement claim and its reading.
struct MethodOrders {
  std::map<Key, double> order;                              // E -> fitted order (over time)
  std::map<Key, std::vector<std::optional<double>>> steps;  // E -> observed orders
};
std::map<std::string, MethodOrders> orders_by_method(
    const std::map<GroupKey, std::vector<Point>>& g) {
  std::map<std::string, MethodOrders> m;
  for (const auto& [key, points] : g) {
    const auto& [sweep, E, method] = key;
    if (sweep != "h") continue;
    if (const auto o = fitted_order(points, Norm::over_time)) m[method].order[E] = *o;
    m[method].steps[E] = step_orders(points, Norm::over_time);
  }
  return m;
}

double spread(const std::map<Key, double>& orders) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& [E, o] : orders) {
    lo = std::min(lo, o);
    hi = std::max(hi, o);
  }
  return orders.empty() ? 0 : hi - lo;
}

// Whether the last two observed orders in the regime agree (the asymptotic range is reached).
bool asymptotic(const std::vector<std::optional<double>>& all) {
  std::vector<double> q;
  for (const auto& o : all)
    if (o) q.push_back(*o);
  if (q.size() < 2) return false;
  return std::abs(q[q.size() - 1] - q[q.size() - 2]) <= kAsymptoticSpread;
}

// Where the orders of a method disagree across E: the evidence per E.
std::string agreement_reading(const std::map<std::string, MethodOrders>& m,
                              const std::vector<ojson>& rows) {
  std::map<Key, double> wave_passes;
  for (const auto& r : rows)
    if (sweep_of(r) == "h") wave_passes[Key(r["E"].get<double>(), "E")] = *RunRow(r).wave_passes;
  std::ostringstream md;
  md << "**Orders across E.** E only rescales time: at the same T a larger E is a longer run in "
        "wave passes c T (";
  std::vector<std::string> passes;
  for (const auto& [E, cT] : wave_passes)
    passes.push_back("E = " + shortest(E) + ": c T = " + fixed(cT, 1));
  md << list_of(passes) << "), over which the error accumulates differently. ";
  std::vector<std::string> agree, differ;
  for (const auto& [method, o] : m) {
    if (o.order.size() < 2) continue;
    if (spread(o.order) <= kOrderAgreement) {
      agree.push_back(method);
      continue;
    }
    std::string s = method + ": fitted ";
    std::vector<std::string> per_E;
    for (const auto& [E, order] : o.order) {
      const auto& q = o.steps.at(E);
      std::string each = fixed(order, 2) + " at E = " + shortest(E) + " (observed ";
      std::vector<std::string> qs;
      for (const auto& v : q)
        qs.push_back(v ? fixed(*v, 2) : std::string("–"));
      each += list_of(qs) + (asymptotic(q) ? ", asymptotic" : ", not yet asymptotic") + ")";
      per_E.push_back(each);
    }
    // The last refinement's order at each E: where these agree, the fitted orders differ only
    // through the coarse grids.
    std::map<Key, double> last_orders;  // E -> the last refinement's order
    for (const auto& [E, q] : o.steps)
      if (const auto last = last_order(q)) last_orders[E] = *last;
    const double last_spread = spread(last_orders);
    std::string last = "; the last refinements' orders spread by " +
                       (last_orders.empty() ? std::string("–") : fixed(last_spread, 2));
    if (!last_orders.empty())
      last += last_spread <= kOrderAgreement
                  ? ", within the tolerance: the difference is the coarse grids'"
                  : ", beyond the tolerance: the difference persists to the finest grid here, "
                    "where only the run length c T differs between the E";
    differ.push_back(s + list_of(per_E) + last);
  }
  md << "The fitted orders of " << list_of(agree) << " agree across E within "
     << shortest(kOrderAgreement) << ". ";
  if (!differ.empty()) {
    md << "They do not for " << differ.size()
       << " methods; beside each E, the observed order of each refinement (coarsest first) and "
          "whether the last two agree within "
       << shortest(kAsymptoticSpread)
       << " (asymptotic; where they do not, that fitted order is pre-asymptotic), and how far "
          "the orders of the last refinement spread across E: "
       << list_of(differ) << ".";
  }
  return md.str();
}

// The order of the time error each update order should have: USL is the leapfrog scheme
// (second order; the bar starts with zero acceleration, so its first half step is consistent);
// USF updates the stress with the velocity of the start of the step and MUSL with the velocity
// re-mapped after it, each an O(dt) inconsistency in the strain: first order.
double expected_time_order(const std::string& update) {
  return update == "usl" ? kPublishedTimeOrder : 1.0;
}

// The time error of each (E, method) of the dt sweep, computed from its first case's parameters;
// for MPM and GIMP with FLIP, also with the other update orders.
struct TimeErrorRow {
  double E = 0;
  std::string method;  // the label, with its update order
  std::string update;
  TimeErrorStudy study;
  bool consistent_mass = false;  // the FMPM(kConsistentOrder) twin of a FLIP row
  bool linear = false;           // a twin at kLinearAmplitudeFraction of the amplitude
};

// FLIP re-projects the particle velocities through the lumped mass every step: the grid velocity
// it stores then grows by Q a dt (Q = M_L^-1 M, the consistent over the lumped mass) while the
// positions move with a dt, an O((kh)^2 dt) inconsistency per step (docs/theory.md, "Orders of
// convergence"). FMPM of this order restores the consistent mass; its twin of the FLIP row at the
// smallest E isolates that term.
constexpr int kConsistentOrder = 8;
// The twins run at the study's amplitude and at this fraction of it, where the particles barely
// move across the grid (the linear limit the re-projection argument is about).
constexpr double kLinearAmplitudeFraction = 0.01;

std::vector<TimeErrorRow> time_error_rows(const Spec& spec, const std::vector<ojson>& rows) {
  std::vector<TimeErrorRow> out;
  std::map<std::pair<Key, std::string>, bool> seen;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (sweep_of(rows[i]) != "dt") continue;
    const auto key = std::make_pair(Key(rows[i]["E"].get<double>(), "E"), method_label(rows[i]));
    if (seen[key]) continue;
    seen[key] = true;
    const RunParams& base = spec.cases[i].params;
    std::vector<UpdateOrder> updates = {base.update};
    if (base.transfer == Transfer::flip && base.update == UpdateOrder::usl &&
        (base.method == Method::mpm || base.method == Method::gimp))
      updates = {UpdateOrder::usl, UpdateOrder::usf, UpdateOrder::musl};
    for (const UpdateOrder u : updates) {
      RunParams p = base;
      p.update = u;
      const std::string update(to_string(u));
      out.push_back({key.first, key.second + (u == base.update ? "" : "/" + update), update,
                     time_errors(p, kTimeSampleCourant, kTimeSubsteps, kTimeReferenceSubsteps)});
    }
  }
  // The consistent-mass twins: MPM and GIMP with FLIP and USL at the smallest E of the sweep.
  double smallest_E = std::numeric_limits<double>::infinity();
  for (const auto& row : out)
    smallest_E = std::min(smallest_E, row.E);
  std::vector<TimeErrorRow> twins;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (sweep_of(rows[i]) != "dt" || rows[i]["E"].get<double>() != smallest_E) continue;
    const RunParams& base = spec.cases[i].params;
    if (base.transfer != Transfer::flip || base.update != UpdateOrder::usl ||
        (base.method != Method::mpm && base.method != Method::gimp))
      continue;
    const std::string label =
        std::string(to_string(base.method)) + "/fmpm(" + std::to_string(kConsistentOrder) + ")";
    if (std::any_of(twins.begin(), twins.end(),
                    [&](const TimeErrorRow& r) { return r.method.rfind(label, 0) == 0; }))
      continue;
    for (const double fraction : {1.0, kLinearAmplitudeFraction}) {
      RunParams p = base;
      p.transfer = Transfer::fmpm;
      p.fmpm_order = kConsistentOrder;
      p.A = base.A * fraction;
      TimeErrorRow row{smallest_E, label + (fraction == 1.0 ? "" : ", A = " + param(p.A)), "usl",
                       time_errors(p, kTimeSampleCourant, kTimeSubsteps, kTimeReferenceSubsteps)};
      row.consistent_mass = true;
      row.linear = fraction != 1.0;
      twins.push_back(std::move(row));
    }
    // The control: FLIP itself at the smaller amplitude.
    RunParams p = base;
    p.A = base.A * kLinearAmplitudeFraction;
    TimeErrorRow control{smallest_E, std::string(to_string(base.method)) + ", A = " + param(p.A),
                         "usl",
                         time_errors(p, kTimeSampleCourant, kTimeSubsteps, kTimeReferenceSubsteps)};
    control.linear = true;
    twins.push_back(std::move(control));
  }
  out.insert(out.end(), twins.begin(), twins.end());
  return out;
}

std::optional<double> time_order(const TimeErrorStudy& s) {
  std::vector<std::pair<double, double>> xy;
  for (const auto& p : s.points)
    if (p.max_difference && *p.max_difference > 0) xy.emplace_back(p.courant, *p.max_difference);
  return loglog_slope(xy);
}

// What the USL rows show: the observed order of the first halving and of the last, over rows.
std::string usl_reading(const std::vector<TimeErrorRow>& t) {
  double first_lo = std::numeric_limits<double>::infinity(), first_hi = -first_lo;
  double last_lo = first_lo, last_hi = -first_lo;
  int n = 0;
  for (const auto& row : t) {
    if (row.update != "usl" || row.consistent_mass || row.linear) continue;
    const auto& pts = row.study.points;
    if (pts.size() < 3) continue;
    auto q = [&](std::size_t k) -> std::optional<double> {
      if (!pts[k - 1].max_difference || !pts[k].max_difference || *pts[k].max_difference <= 0)
        return std::nullopt;
      return std::log2(*pts[k - 1].max_difference / *pts[k].max_difference);
    };
    const auto a = q(1), b = q(pts.size() - 1);
    if (!a || !b) continue;
    ++n;
    first_lo = std::min(first_lo, *a);
    first_hi = std::max(first_hi, *a);
    last_lo = std::min(last_lo, *b);
    last_hi = std::max(last_hi, *b);
  }
  if (n == 0) return "";
  std::ostringstream md;
  md << "**Reading.** With USL the observed order of the first halving (from C = "
     << shortest(kTimeSampleCourant) << ") is " << fixed(first_lo, 2) << " to "
     << fixed(first_hi, 2) << " and that of the last " << fixed(last_lo, 2) << " to "
     << fixed(last_hi, 2) << ", over " << n
     << " rows: the second-order term of the leapfrog reading shows only at the largest steps, "
        "and below them a first-order term takes over, with a constant far below USF's (compare "
        "the rows at the same C). Its source is FLIP's re-projection of the particle velocities "
        "through the lumped mass (docs/theory.md, \"Orders of convergence\"): the stored grid "
        "velocity grows by the consistent over the lumped mass times a dt while the positions "
        "move with a dt. The twins with FMPM("
     << kConsistentOrder << "), whose series restores the consistent mass, isolate it: ";
  std::vector<std::string> twins;
  for (const auto& row : t) {
    if (!row.consistent_mass && !row.linear) continue;
    twins.push_back(row.method + " at E = " + shortest(row.E) + " falls at " +
                    order_text(time_order(row.study)));
  }
  md << list_of(twins)
     << " (without FMPM, the FLIP rows at the smaller amplitude are the control). At the smaller "
        "amplitude, where the particles barely move across the grid, the FMPM twins fall at the "
        "leapfrog order and FLIP does not; at the study's amplitude a second first-order term, "
        "which grows with the amplitude, remains (largest for linear MPM, whose particles' "
        "crossings move its forces).\n\n";
  return md.str();
}

std::string time_error_table(const std::vector<TimeErrorRow>& t) {
  if (t.empty()) return "";
  std::ostringstream md;
  md << "| E | method |";
  for (const auto& p : t.front().study.points)
    md << " C = " << shortest(p.courant) << " |";
  md << " fitted order | expected | particle-steps |\n|---|---|";
  for (std::size_t k = 0; k < t.front().study.points.size(); ++k)
    md << "---|";
  md << "---|---|---|\n";
  for (const auto& row : t) {
    md << "| " << shortest(row.E) << " | " << row.method << " |";
    long long work = row.study.reference_particle_steps;
    double before = 0;  // the difference at the step twice as large; 0: none
    for (const auto& p : row.study.points) {
      work += p.particle_steps;
      if (!p.max_difference) {
        md << " " << (p.stable ? "–" : "unstable") << " |";
        before = 0;
        continue;
      }
      const double d = *p.max_difference;
      md << " " << sci(d, 2);
      if (before > 0 && d > 0)
        md << " (" << fixed(before / d, 2) << ", " << fixed(std::log2(before / d), 2) << ")";
      md << " |";
      before = d;
    }
    md << " " << order_text(time_order(row.study)) << " | "
       << shortest(expected_time_order(row.update)) << " | " << sci(double(work), 2) << " |\n";
  }
  return md.str();
}

// Uintah's baseline (the spec's reference) and its fitted orders in h (the negative slope
// against the number of nodes).
struct Baseline {
  std::vector<double> nodes, l2, max;
  std::optional<double> order_l2, order_max;
};
Baseline read_baseline(const std::filesystem::path& file) {
  Baseline b;
  const CsvTable t = read_csv(file);
  std::vector<std::pair<double, double>> l2, mx;
  for (const auto& row : t.rows) {
    const double nn = std::stod(row.at("NN"));
    b.nodes.push_back(nn);
    b.l2.push_back(std::stod(row.at("L2norm")));
    b.max.push_back(std::stod(row.at("maxError")));
    l2.emplace_back(1.0 / nn, b.l2.back());
    mx.emplace_back(1.0 / nn, b.max.back());
  }
  b.order_l2 = loglog_slope(l2);
  b.order_max = loglog_slope(mx);
  return b;
}

std::string peer_section(const Spec& spec, const std::map<GroupKey, std::vector<Point>>& g,
                         const Baseline& b, const std::vector<ojson>& rows) {
  std::ostringstream md;
  const ojson* first = nullptr;
  for (const auto& r : rows)
    if (sweep_of(r) == "peer") first = &r;
  if (!first) return "";
  md << "## Beside Uintah's own order-of-accuracy baseline\n\n"
     << "Uintah's 1D MPM code keeps an order-of-accuracy baseline for its manufactured solution (["
     << spec.reference.filename().string() << "](../reference/peers/"
     << spec.reference.filename().string()
     << "), from the Uintah repository: the file, its setting and its commit are described "
        "there). Its errors are measured at the final time, one wave transit: ";
  std::vector<std::string> pairs;
  for (std::size_t k = 0; k < b.nodes.size(); ++k)
    pairs.push_back(shortest(b.nodes[k]) + " nodes: max " + sci(b.max[k], 2) + ", L2 " +
                    sci(b.l2[k], 2));
  md << list_of(pairs) << "; fitted order in h " << order_text(b.order_max) << " (max) and "
     << order_text(b.order_l2) << " (L2).\n\n"
     << "The same measurement here: the neo-Hookean manufactured solution (scene steffen), linear "
        "MPM, "
     << (*first)["ppc"].get<int>() << " particles per cell, the cfl policy at C = "
     << shortest((*first)["cfl_factor"].get<double>())
     << ", one wave transit (c T = " << shortest(*RunRow(*first).wave_passes)
     << "), A / L = " << shortest((*first)["A"].get<double>())
     << " (the baseline's A over its bar's length L), on our unit bar with walls at both ends. "
        "The setting differs in what the scene declares, and each difference is named: Uintah's "
        "bar ends inside a larger domain (the nodes beyond it empty), ours fills the grid; its "
        "E only rescales time (as ours); its CFL step adds |v_p| to c, which at this amplitude "
        "moves dt by less than the amplitude's strain; its L2 norm is the root mean square over "
        "the particles at the final time.\n\n";
  for (const auto& [key, points] : g) {
    const auto& [sweep, E, method] = key;
    if (sweep != "peer") continue;
    md << "| norm |";
    for (const auto& p : points)
      md << " " << p.label << " |";
    md << " fitted order |\n|---|";
    for (std::size_t k = 0; k < points.size(); ++k)
      md << "---|";
    md << "---|\n";
    for (const auto& [name, n] : {std::pair{"error at T (the baseline's norm)", Norm::at_T},
                                  std::pair{"error over time", Norm::over_time},
                                  std::pair{"L2 over time", Norm::l2_time}}) {
      md << "| " << name << " |";
      for (std::size_t k = 0; k < points.size(); ++k)
        md << " " << point_text(points, k, n) << " |";
      md << " " << order_text(fitted_order(points, n)) << " |\n";
    }
  }
  const auto ours_T = [&]() -> std::optional<double> {
    for (const auto& [key, points] : g)
      if (std::get<0>(key) == "peer") return fitted_order(points, Norm::at_T);
    return std::nullopt;
  }();
  md << "\n**Reading.** In the baseline's norm our order is " << order_text(ours_T)
     << " and the baseline's " << order_text(b.order_max)
     << ". Of the differences named above, E and the |v_p| in its step do not move an order (E "
        "only rescales time; |v_p| / c is at most pi A / L = "
     << sci(std::acos(-1.0) * (*first)["A"].get<double>(), 2)
     << " here); what is left is the bar's end: ours meets a wall on a node, Uintah's ends "
        "inside the grid beside empty nodes, where the boundary node holds a part of a cell's "
        "mass. A first-order error at such an end would give the baseline's order. The "
        "experiment that would decide it is the same bar, with its manufactured solution, ending "
        "inside a larger grid; the bar scene fills its grid (its body may not be placed), and "
        "the scenes that do end beside empty cells solve other problems, so no run here "
        "decides it: the difference is stated, not explained by a run.\n\n";
  return md.str();
}

std::optional<double> peer_order(const std::map<GroupKey, std::vector<Point>>& g, Norm n) {
  for (const auto& [key, points] : g)
    if (std::get<0>(key) == "peer") return fitted_order(points, n);
  return std::nullopt;
}

// The fitted orders above what theory allows, and the evidence for each: the observed order of the
// last refinement, which is what the order tends to once the coarse grids stop weighing.
struct AboveTheory {
  std::string method;
  double E = 0;
  double fitted = 0;
  std::optional<double> last;
};
std::vector<AboveTheory> above_theory(const std::map<std::string, MethodOrders>& m) {
  std::vector<AboveTheory> out;
  for (const auto& [method, o] : m)
    for (const auto& [E, order] : o.order) {
      if (order <= kTheoryMaxOrder + kOrderAgreement) continue;
      const auto& q = o.steps.at(E);
      out.push_back({method, E, order, last_order(q)});
    }
  return out;
}

std::string above_theory_reading(const std::vector<AboveTheory>& a) {
  std::ostringstream md;
  md << "**Orders above the theory's.** The particle quadrature limits the order in h to "
     << shortest(kTheoryMaxOrder) << " (Steffen, Kirby and Berzins (2008)). ";
  if (a.empty()) {
    md << "No fitted order exceeds it by more than " << shortest(kOrderAgreement) << ".";
    return md.str();
  }
  std::vector<std::string> items;
  for (const auto& x : a)
    items.push_back(x.method + " at E = " + shortest(x.E) + " (fitted " + fixed(x.fitted, 2) +
                    ", last refinement " + (x.last ? fixed(*x.last, 2) : std::string("–")) + ")");
  md << a.size() << " fitted orders exceed it by more than " << shortest(kOrderAgreement) << ": "
     << list_of(items) << ". ";
  // Which of them fall back to the theory's order (within kOrderAgreement) at the last
  // refinement: for those the fit is weighted by a coarse-grid regime that does not persist.
  std::vector<std::string> fall, stay;
  for (const auto& x : a)
    (x.last && *x.last <= kTheoryMaxOrder + kOrderAgreement ? fall : stay)
        .push_back(x.method + " at E = " + shortest(x.E));
  if (!fall.empty())
    md << "At the last refinement " << list_of(fall) << " " << (fall.size() == 1 ? "falls" : "fall")
       << " to within " << shortest(kOrderAgreement)
       << " of it: there the fitted order is weighted by coarse grids whose order does not "
          "persist, and the order to expect on finer grids is the last refinement's. ";
  if (!stay.empty())
    md << list_of(stay) << " " << (stay.size() == 1 ? "stays" : "stay") << " above it at the "
       << "last refinement: the grids run do not show where "
       << (stay.size() == 1 ? "its" : "their") << " order settles. ";
  md << "What makes the coarse grids converge faster is not isolated here.";
  return md.str();
}

std::string published_table(const std::map<std::string, MethodOrders>& m) {
  std::ostringstream md;
  md << "| method | published order in h | source | ours (error over time), per E |\n"
        "|---|---|---|---|\n";
  for (const auto& [method, o] : m) {
    const PublishedOrder pub = published_order(method);
    std::vector<std::string> ours;
    for (const auto& [E, order] : o.order)
      ours.push_back(fixed(order, 2) + " (E = " + shortest(E) + ")");
    md << "| " << method << " | " << (pub.order ? shortest(*pub.order) : "–") << " | " << pub.source
       << " | " << list_of(ours) << " |\n";
  }
  return md.str();
}

Claim orders_agree_claim(const std::map<std::string, MethodOrders>& m) {
  int agree = 0, total = 0;
  for (const auto& [method, o] : m) {
    if (o.order.size() < 2) continue;
    ++total;
    agree += spread(o.order) <= kOrderAgreement;
  }
  Claim c = claim("orders-agree-across-E",
                  "The fitted orders in h of each method agree across E within {tolerance}",
                  "{agree} of {total} methods");
  c.number("tolerance", kOrderAgreement).every("agree", agree, "total", total);
  return c;
}

Claim published_orders_claim(const std::map<std::string, MethodOrders>& m) {
  int met = 0, total = 0;
  for (const auto& [method, o] : m) {
    const auto pub = published_order(method).order;
    if (!pub) continue;
    for (const auto& [E, order] : o.order) {
      ++total;
      met += std::abs(order - *pub) <= kOrderAgreement;
    }
  }
  Claim c = claim("published-spatial-orders",
                  "Where an order in h is published for the basis, ours lies within "
                  "{tolerance} of it at every E",
                  "{met} of {total} (method, E) pairs");
  c.number("tolerance", kOrderAgreement).every("met", met, "total", total);
  return c;
}

// USL (leapfrog) or USF and MUSL: the time order of every method and E against the published one.
Claim time_order_claim(const std::vector<TimeErrorRow>& t, bool leapfrog) {
  int met = 0, total = 0;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& row : t) {
    if ((row.update == "usl") != leapfrog || row.consistent_mass || row.linear) continue;
    const auto o = time_order(row.study);
    if (!o) continue;
    ++total;
    met += std::abs(*o - expected_time_order(row.update)) <= kOrderAgreement;
    lo = std::min(lo, *o);
    hi = std::max(hi, *o);
  }
  Claim c = leapfrog
                ? claim("time-order-usl",
                        "With USL the time error (the difference from a run at a much smaller "
                        "step on the same grid) falls at the published order {expected} for "
                        "every method and E",
                        "{met} of {total} within {tolerance}; fitted orders {lo} to {hi}")
                : claim("time-order-usf-musl",
                        "With USF and MUSL the time error falls at first order ({expected}) for "
                        "MPM and GIMP at every E",
                        "{met} of {total} within {tolerance}; fitted orders {lo} to {hi}");
  c.number("expected", leapfrog ? kPublishedTimeOrder : 1.0)
      .number("tolerance", kOrderAgreement)
      .every("met", met, "total", total)
      .value("lo", total ? fixed(lo, 2) : "–")
      .value("hi", total ? fixed(hi, 2) : "–");
  return c;
}

Claim consistent_mass_claim(const std::vector<TimeErrorRow>& t) {
  int met = 0, total = 0;
  std::vector<std::string> orders;
  for (const auto& row : t) {
    if (!row.consistent_mass || !row.linear) continue;
    const auto o = time_order(row.study);
    if (!o) continue;
    ++total;
    met += std::abs(*o - kPublishedTimeOrder) <= kOrderAgreement;
    orders.push_back(row.method + " " + fixed(*o, 2));
  }
  Claim c = claim("time-order-consistent-mass",
                  "With the consistent mass restored (FMPM of order {order}) and at an "
                  "amplitude {fraction} of the study's, USL's time error falls at the leapfrog "
                  "order {expected}: the first-order term of FLIP in the linear limit is its "
                  "lumped-mass re-projection",
                  "{met} of {total} within {tolerance} ({orders})");
  c.count("order", kConsistentOrder)
      .number("fraction", kLinearAmplitudeFraction)
      .number("expected", kPublishedTimeOrder)
      .number("tolerance", kOrderAgreement)
      .every("met", met, "total", total)
      .value("orders", list_of(orders));
  return c;
}

Claim within_theory_claim(const std::map<std::string, MethodOrders>& m) {
  const auto a = above_theory(m);
  int explained = 0;
  for (const auto& x : a)
    explained += x.last && *x.last <= kTheoryMaxOrder + kOrderAgreement;
  Claim c = claim("orders-within-theory",
                  "Every fitted order in h above the theory's {theory} (by more than "
                  "{tolerance}) is pre-asymptotic: its last refinement falls at most at "
                  "{theory} + {tolerance}",
                  "{explained} of {above} fitted orders above it");
  c.number("theory", kTheoryMaxOrder)
      .number("tolerance", kOrderAgreement)
      .every("explained", explained, "above", static_cast<long long>(a.size()));
  return c;
}

Claim uintah_baseline_claim(const std::map<GroupKey, std::vector<Point>>& g, const Baseline& b) {
  const auto ours = peer_order(g, Norm::at_T);
  Claim c = claim("uintah-baseline-order",
                  "Linear MPM's order in h on the manufactured solution agrees with Uintah's own "
                  "baseline within {tolerance} (the error at the final time, as the baseline "
                  "measures it)",
                  "ours {ours}, the baseline's {theirs}");
  c.number("tolerance", kOrderAgreement)
      .value("ours", order_text(ours))
      .value("theirs", order_text(b.order_max));
  c.holds = ours && b.order_max && std::abs(*ours - *b.order_max) <= kOrderAgreement;
  return c;
}

std::vector<Claim> convergence_claims(const std::map<std::string, MethodOrders>& m,
                                      const std::vector<TimeErrorRow>& t,
                                      const std::map<GroupKey, std::vector<Point>>& g,
                                      const Baseline& b) {
  return {orders_agree_claim(m),      published_orders_claim(m), time_order_claim(t, true),
          time_order_claim(t, false), consistent_mass_claim(t),  within_theory_claim(m),
          uintah_baseline_claim(g, b)};
}

std::string convergence_data(const std::vector<ojson>& rows, const std::string& header);

StudyReport convergence_report(const ReportContext& ctx) {
  const auto& rows = ctx.rows;
  const auto g = groups(rows);
  const auto m = orders_by_method(g);
  const auto t = time_error_rows(ctx.spec, rows);
  const Baseline b = read_baseline(ctx.spec.reference);
  const ojson* first = nullptr;
  for (const auto& r : rows)
    if (sweep_of(r) == "h") {
      first = &r;
      break;
    }
  std::ostringstream md;
  md << "## Error against h\n\n" << special_check(rows) << "\n\n";
  if (first) {
    md << "A = " << shortest((*first)["A"].get<double>())
       << ", T = " << shortest((*first)["T"].get<double>()) << ", " << (*first)["ppc"].get<int>()
       << " particles per cell, the fixed step of each row of the spec, small enough that the "
          "time error does not show (the time error section below measures it). ";
  }
  md << "Each cell gives the error and, in brackets, the ratio to the grid before it and the "
        "observed order (the log of the ratio over the log of the h ratio), so that the "
        "asymptotic range shows. The fitted order is the least-squares slope of log(error) "
        "against log(h); "
     << order_regime_text()
     << " (`†`: outside it; `–`: fewer than three points in it). The Richardson "
        "limit extrapolates the error from the three finest grids (near zero when it converges "
        "to zero, a floor otherwise). The error at T is shown for the finest grid and fitted to "
        "nothing.\n\n### The error over time (max over steps and particles of |u_p - u(X_p, "
        "t)|)\n\n"
     << sweep_table(g, "h", Norm::over_time)
     << "\n### The L2 error over time (root mean square over the body and the run)\n\n"
     << sweep_table(g, "h", Norm::l2_time) << "\n"
     << agreement_reading(m, rows) << "\n\n"
     << above_theory_reading(above_theory(m)) << "\n\n"
     << "### Published orders beside ours\n\nThe sources are listed in docs/theory.md "
        "(\"Published orders\"). The claim below compares where a number is published.\n\n"
     << published_table(m)
     << "\n## The time error against dt\n\nOn one grid, every run is compared with a reference "
        "run at a step "
     << kTimeReferenceSubsteps / kTimeSubsteps.back()
     << " times smaller than the smallest, through the same sample instants (every "
     << shortest(kTimeSampleCourant)
     << " h / c, each cut into equal substeps; core/analysis/time_error.hpp): the largest "
        "difference of "
        "a particle position at any sample instant. The spatial error is common to both runs "
        "and cancels, so this is the error the time step makes, measured where it dominates by "
        "construction. Symplectic Euler as MPM steps it with USL (the velocity first, then the "
        "position with the new velocity) is the leapfrog scheme with the velocity at half steps: "
        "second order, the order Steffen, Kirby and Berzins (2010) measured where the time error "
        "dominates. USF updates the stress with the velocity of the start of the step and MUSL "
        "with the velocity re-mapped after it: first order. MPM and GIMP run with each update "
        "order. Each cell: the difference and, in brackets, the ratio to the step twice as "
        "large and its order.\n\n"
     << time_error_table(t) << "\n"
     << usl_reading(t)
     << "\n### The error against the exact solution at each C\n\nThe cfl runs of the spec on the "
        "same grid, against the exact solution (the error over time, so the grid's error shows): "
        "where it stops falling with dt, the time error is below the grid's. A run whose error "
        "over time is not accurate is marked `†` and left out of the fitted order.\n\n"
     << sweep_table(g, "dt", Norm::over_time) << "\n"
     << peer_section(ctx.spec, g, b, rows);
  StudyReport report;
  report.markdown = md.str();
  report.data_csv = convergence_data(rows, ctx.csv_header);
  report.claims = convergence_claims(m, t, g, b);
  return report;
}

// <name>_data.csv: E, panel (per E), series (per method), h and error of each stable run of
// the h sweep.
std::string convergence_data(const std::vector<ojson>& rows, const std::string& header) {
  std::map<Key, int> panel;
  std::map<std::string, int> series;
  for (const auto& r : rows) {
    if (sweep_of(r) != "h") continue;
    panel.emplace(Key(r["E"].get<double>(), "E"), 0);
    series.emplace(method_label(r), 0);
  }
  int k = 0;
  for (auto& [E, p] : panel)
    p = k++;
  k = 0;
  for (auto& [m, s] : series)
    s = k++;
  std::ostringstream csv;
  csv << header << "E,panel,series,method,h,error_over_time\n";
  for (const auto& r : rows) {
    const RunRow run(r);
    if (sweep_of(r) != "h" || run.outcome != "stable" || !run.error_over_time) continue;
    const std::string method = method_label(r);
    csv << shortest(r["E"].get<double>()) << "," << panel[Key(r["E"].get<double>(), "E")] << ","
        << series[method] << "," << method << "," << shortest(variable(r)) << ","
        << shortest(*run.error_over_time) << "\n";
  }
  return csv.str();
}

// The runs drawn: those that reached T below A, the stable ones apart from those under a wave
// pass (drawn, never called stable, no order fitted on them: VerdictTally, run_row.hpp).
std::string convergence_subtitle(const Spec&, const ojson& doc) {
  VerdictTally drawn;
  std::vector<double> short_cT;
  int left_out = 0;
  for (const auto& row : doc["cases"]) {
    const RunRow r(row);
    if (sweep_of(row) != "h") continue;
    if (r.outcome != "stable" || !r.error_over_time) {
      ++left_out;
      continue;
    }
    drawn.add(r);
    if (r.under_a_wave_pass()) short_cT.push_back(*r.wave_passes);
  }
  std::string s = std::to_string(drawn.stable) + " stable runs drawn";
  if (drawn.under_a_wave_pass > 0)
    s += ", " + std::to_string(drawn.under_a_wave_pass) + " under a wave pass (c T " +
         span(short_cT, 2) + ": not stable, no order fitted) drawn beside them";
  return s + ", " + std::to_string(left_out) + " not stable left out";
}

// The wave passes c T of the h sweep's runs at E that ran under a wave pass (none where none did):
// no order is fitted on them.
std::optional<double> under_a_pass_at(const std::vector<ojson>& rows, double E) {
  for (const auto& row : rows) {
    const RunRow r(row);
    if (sweep_of(row) == "h" && row["E"].get<double>() == E && r.under_a_wave_pass())
      return r.wave_passes;
  }
  return std::nullopt;
}

// The index paragraph: the figure and the fitted orders in h, read from the rows. An E whose
// runs are under a wave pass has none fitted, and says why.
std::string convergence_index(const Spec& spec, const std::vector<ojson>& rows) {
  std::ostringstream md;
  md << "![" << spec.title << "](" << spec.name << ".png)\n\n**What it shows.** Fitted order "
     << "of the error over time in h:";
  std::map<Key, std::vector<std::string>> by_E;
  std::map<Key, bool> any_fitted;
  for (const auto& [key, points] : groups(rows)) {
    const auto& [sweep, E, method] = key;
    if (sweep != "h") continue;
    const auto order = fitted_order(points, Norm::over_time);
    by_E[E].push_back(method + " " + order_text(order));
    any_fitted[E] = any_fitted[E] || order.has_value();
  }
  bool first = true;
  for (const auto& [E, orders] : by_E) {
    md << (first ? " " : "; ") << "E = " << shortest(E) << ": ";
    first = false;
    const auto short_cT = under_a_pass_at(rows, E);
    if (!any_fitted[E] && short_cT) {
      md << "none fitted (its runs cover c T = " << shortest(*short_cT) << " < "
         << shortest(kMinWavePasses) << " wave pass: not stable)";
      continue;
    }
    for (std::size_t k = 0; k < orders.size(); ++k)
      md << (k ? ", " : "") << orders[k];
  }
  md << ". The L2 norm over time, the observed order of each refinement, the time error against "
        "dt, the published orders and Uintah's baseline: ["
     << spec.name << ".md](" << spec.name << ".md).\n\n";
  return md.str();
}

const StudyRegistration kConvergence{{
    .name = "convergence",
    .summary = "error over time against h and time error against dt for every basis, with "
               "fitted and published orders",
    .needs_reference = true,
    .figure = true,
    .report = convergence_report,
    .index = convergence_index,
    .figure_subtitle = convergence_subtitle,
}};

}  // namespace
}  // namespace studies::convergence

}  // namespace mpmstab
