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
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <tuple>
#include <utility>

#include "analysis/time_error.hpp"
#include "claims.hpp"
#include "csv.hpp"
#include "key.hpp"
#include "report_util.hpp"
#include "run_row.hpp"
#include "study.hpp"

namespace mpmstab::studies::convergence {
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

// FLIP re-projects the particle velocities through the lumped mass every step: the grid velocity
// it stores then grows by Q a dt (Q = M_L^-1 M, the consistent over the lumped mass) while the
// positions move with a dt, an O((kh)^2 dt) inconsistency per step (docs/theory.md, "Orders of
// convergence"). FMPM of this order restores the consistent mass; its twin of the FLIP row at the
// smallest E isolates that term.
constexpr int kConsistentOrder = 8;
// The twins run at the study's amplitude and at this fraction of it, where the particles barely
// move across the grid (the linear limit the re-projection argument is about).
constexpr double kLinearAmplitudeFraction = 0.01;

// The published order in h of each basis for a smooth small-amplitude problem (docs/theory.md,
// "Published orders"); nullopt where none is published for this kind of problem.
struct PublishedOrder {
  std::optional<double> order;
  std::string source;
};
PublishedOrder published_order(const std::string& method) {
  if (method == "gimp" || method == "cpgimp")
    return {2.0,
            "Steffen, Wallstedt, Guilkey, Kirby and Berzins (2008); Wallstedt and Guilkey (2008): "
            "GIMP converges at second order in space while particles do not "
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
  std::optional<double> order;   // fitted (find)
};
std::vector<TimeErrorRow> time_error_rows(const Spec& spec, const std::vector<ojson>& rows) {
  std::vector<TimeErrorRow> out;
  std::map<std::pair<Key, std::string>, bool> seen;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (sweep_of(rows[i]) != "dt") continue;
    const auto key = std::make_pair(Key(rows[i]["E"].get<double>(), "E"), method_label(rows[i]));
    if (std::exchange(seen[key], true)) continue;
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
    // The twin at both amplitudes, then the control: FLIP itself at the smaller amplitude.
    using Twin = std::pair<bool, double>;  // (FMPM, the fraction of the amplitude)
    for (const auto& [fmpm, fraction] : {Twin{true, 1.0}, Twin{true, kLinearAmplitudeFraction},
                                         Twin{false, kLinearAmplitudeFraction}}) {
      RunParams p = base;
      p.A = base.A * fraction;
      if (fmpm) {
        p.transfer = Transfer::fmpm;
        p.fmpm_order = kConsistentOrder;
      }
      const std::string name = fmpm ? label : std::string(to_string(base.method));
      twins.push_back({smallest_E, name + (fraction == 1.0 ? "" : ", A = " + param(p.A)), "usl",
                       time_errors(p, kTimeSampleCourant, kTimeSubsteps, kTimeReferenceSubsteps),
                       fmpm, fraction != 1.0});
    }
  }
  out.insert(out.end(), twins.begin(), twins.end());
  return out;
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
  for (const auto& p : points)
    if (const auto e = value_of(p, n); e && p.fit) xy.emplace_back(p.x, *e);
  return loglog_slope(xy);
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

// A refinement (one sweep, E and method): its points from the coarsest to the finest and, in
// each norm, its fitted order, the observed order of each refinement (steps[k - 1]: from point
// k - 1 to point k) and Richardson's limit.
struct Orders {
  std::optional<double> fitted, limit;
  std::vector<std::optional<double>> steps;
};
struct Refinement {
  std::vector<Point> points;
  std::array<Orders, 3> norms;
  const Orders& operator[](Norm n) const { return norms[static_cast<std::size_t>(n)]; }
};
using Refinements = std::map<std::pair<Key, std::string>, Refinement>;  // by E and method

// The rows grouped by sweep (h, dt and peer), then by E and method.
std::tuple<Refinements, Refinements, Refinements> refinements(const std::vector<ojson>& rows) {
  std::map<std::string, Refinements> g;
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
    g[sweep_of(r)][{Key(r["E"].get<double>(), "E"), method_label(r)}].points.push_back(p);
  }
  for (auto& [sweep, by] : g)
    for (auto& [key, ref] : by) {
      auto& points = ref.points;
      std::sort(points.begin(), points.end(),
                [](const Point& a, const Point& b) { return TotalLess()(b.x, a.x); });
      for (const Norm n : {Norm::over_time, Norm::l2_time, Norm::at_T}) {
        Orders& o = ref.norms[static_cast<std::size_t>(n)];
        o.fitted = fitted_order(points, n);
        o.limit = richardson_limit(points, n);
        for (std::size_t k = 1; k < points.size(); ++k)
          o.steps.push_back(step_order(points[k - 1], points[k], n));
      }
    }
  return {std::move(g["h"]), std::move(g["dt"]), std::move(g["peer"])};
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

// The orders in h (error over time) of one method across E: fitted and observed, and whether
// they agree across E.
struct MethodOrders {
  std::map<Key, double> order;                              // E -> fitted order
  std::map<Key, std::vector<std::optional<double>>> steps;  // E -> observed orders
  std::map<Key, bool> asymptotic;  // E -> the last two observed orders agree
  bool compared = false;           // fitted at two E or more
  bool agree = false;              // ... within kOrderAgreement
  // The spread across E of the last refinement's observed orders, where any, and whether it lies
  // within kOrderAgreement (the fitted orders then differ only through the coarse grids).
  std::optional<double> last_spread;
  bool last_agree = false;
};
std::map<std::string, MethodOrders> orders_by_method(const Refinements& h) {
  std::map<std::string, MethodOrders> m;
  for (const auto& [key, ref] : h) {
    const auto& [E, method] = key;
    MethodOrders& o = m[method];
    const Orders& over_time = ref[Norm::over_time];
    if (over_time.fitted) o.order[E] = *over_time.fitted;
    o.steps[E] = over_time.steps;
    o.asymptotic[E] = asymptotic(over_time.steps);
  }
  for (auto& [method, o] : m) {
    o.compared = o.order.size() >= 2;
    o.agree = o.compared && spread(o.order) <= kOrderAgreement;
    std::map<Key, double> last_orders;  // E -> the last refinement's order
    for (const auto& [E, q] : o.steps)
      if (const auto last = last_order(q)) last_orders[E] = *last;
    if (!last_orders.empty()) o.last_spread = spread(last_orders);
    o.last_agree = o.last_spread && *o.last_spread <= kOrderAgreement;
  }
  return m;
}

// A fitted order above what theory allows, and the evidence: the observed order of the last
// refinement, which is what the order tends to once the coarse grids stop weighing.
struct AboveTheory {
  std::string method;
  double E = 0;
  double fitted = 0;
  std::optional<double> last;
  bool falls = false;  // the last refinement's order lies within kOrderAgreement of the theory's
};

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

// How many of a set (methods, pairs, rows) satisfy a claim, with the range of a value over them.
struct Count {
  int met = 0, total = 0;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  void add(bool hit, double v = 0) {
    ++total;
    met += hit;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
};

// The fitted orders in h at one E (the index's), and the c T of its runs where under a wave pass.
struct OrdersAtE {
  std::vector<std::pair<std::string, std::optional<double>>> by_method;
  bool any_fitted = false;
  std::optional<double> under_a_pass;
};

// What the study finds: every refinement with its orders, each method's across E, the time error
// with its orders, Uintah's baseline beside our measurement, and what the figure draws.
struct Findings {
  Refinements h, dt, peer;                                // the sweeps
  const ojson* first_h = nullptr;                         // the first row of the h sweep
  const ojson* peer_row = nullptr;                        // the last row of the peer measurement
  std::vector<std::pair<Key, double>> special, ordinary;  // E -> |sin(c pi T)|, below or not
  std::map<Key, double> wave_passes;                      // of the h sweep, per E
  std::map<std::string, MethodOrders> methods;
  Count agree, published;  // methods whose orders agree across E; (method, E) pairs published
  std::vector<AboveTheory> above;
  int explained = 0;  // of `above`, those that fall back at the last refinement
  std::vector<TimeErrorRow> time;
  Count usl, usf_musl, consistent;    // time orders met, each with the range of the orders
  Count first_halving, last_halving;  // USL's observed orders of the first and last halving
  std::vector<std::pair<std::string, double>> consistent_orders;  // method -> time order
  Baseline baseline;
  std::optional<double> peer_at_T;  // our order in the baseline's norm
  bool peer_agrees = false;
  std::map<Key, OrdersAtE> index;
  VerdictTally drawn;  // the figure: the stable runs of the h sweep
  std::vector<const ojson*> drawn_rows;
  std::vector<double> short_cT;
  int left_out = 0;
};

// The time order of every row, and what the claims and the reading count: the sweep's rows against
// their update order's expected order, the consistent-mass twins in the linear limit against 2.
void time_orders(std::vector<TimeErrorRow> t, Findings& f) {
  for (auto& row : t) {
    std::vector<std::pair<double, double>> xy;  // the fitted order of the largest difference
    for (const auto& p : row.study.points)
      if (p.max_difference && *p.max_difference > 0) xy.emplace_back(p.courant, *p.max_difference);
    row.order = loglog_slope(xy);
    if (row.consistent_mass && row.linear && row.order) {
      f.consistent.add(std::abs(*row.order - kPublishedTimeOrder) <= kOrderAgreement, *row.order);
      f.consistent_orders.emplace_back(row.method, *row.order);
    }
    if (row.consistent_mass || row.linear) continue;
    if (row.order)
      (row.update == "usl" ? f.usl : f.usf_musl)
          .add(std::abs(*row.order - expected_time_order(row.update)) <= kOrderAgreement,
               *row.order);
    const auto& pts = row.study.points;
    if (row.update != "usl" || pts.size() < 3) continue;
    auto q = [&](std::size_t k) -> std::optional<double> {
      if (!pts[k - 1].max_difference || !pts[k].max_difference || *pts[k].max_difference <= 0)
        return std::nullopt;
      return std::log2(*pts[k - 1].max_difference / *pts[k].max_difference);
    };
    const auto a = q(1), b = q(pts.size() - 1);
    if (!a || !b) continue;
    f.first_halving.add(true, *a);
    f.last_halving.add(true, *b);
  }
  f.time = std::move(t);
}

// The findings from the rows and, in the report, the time error runs (time_error_rows).
Findings find(const Spec& spec, const std::vector<ojson>& rows, std::vector<TimeErrorRow> t = {}) {
  Findings f;
  std::tie(f.h, f.dt, f.peer) = refinements(rows);
  std::map<Key, double> factor;  // E -> |sin(c pi T)|
  for (const auto& row : rows) {
    const RunRow r(row);
    const std::string sweep = sweep_of(row);
    const Key E(row["E"].get<double>(), "E");
    if (sweep == "peer") f.peer_row = &row;
    if (sweep != "peer")
      factor[E] =
          std::abs(std::sin(std::sqrt(E.value()) * std::acos(-1.0) * row["T"].get<double>()));
    if (sweep != "h") continue;
    if (!f.first_h) f.first_h = &row;
    f.wave_passes[E] = *r.wave_passes;
    if (r.under_a_wave_pass() && !f.index[E].under_a_pass) f.index[E].under_a_pass = r.wave_passes;
    if (r.outcome != "stable" || !r.error_over_time) {
      ++f.left_out;
      continue;
    }
    f.drawn.add(r);
    f.drawn_rows.push_back(&row);
    if (r.under_a_wave_pass()) f.short_cT.push_back(*r.wave_passes);
  }
  for (const auto& [E, x] : factor)
    (x < kSpecialFactor ? f.special : f.ordinary).emplace_back(E, x);
  // The orders in h of each method across E, against the theory's and the published ones.
  f.methods = orders_by_method(f.h);
  for (const auto& [method, o] : f.methods) {
    if (o.compared) f.agree.add(o.agree);
    const auto pub = published_order(method).order;
    for (const auto& [E, order] : o.order) {
      if (pub) f.published.add(std::abs(order - *pub) <= kOrderAgreement);
      if (order <= kTheoryMaxOrder + kOrderAgreement) continue;
      const auto last = last_order(o.steps.at(E));
      f.above.push_back(
          {method, E, order, last, last && *last <= kTheoryMaxOrder + kOrderAgreement});
      f.explained += f.above.back().falls;
    }
  }
  for (const auto& [key, ref] : f.h) {
    OrdersAtE& at = f.index[key.first];
    at.by_method.emplace_back(key.second, ref[Norm::over_time].fitted);
    at.any_fitted = at.any_fitted || ref[Norm::over_time].fitted.has_value();
  }
  time_orders(std::move(t), f);
  f.baseline = read_baseline(spec.reference);
  if (!f.peer.empty()) f.peer_at_T = f.peer.begin()->second[Norm::at_T].fitted;
  f.peer_agrees = f.peer_at_T && f.baseline.order_max &&
                  std::abs(*f.peer_at_T - *f.baseline.order_max) <= kOrderAgreement;
  return f;
}

std::string order_text(const std::optional<double>& order) {
  return order ? fixed(*order, 2) : std::string("–");
}

// USL (leapfrog) or USF and MUSL: the time order of every method and E against the published one.
Claim time_order_claim(const Count& n, bool leapfrog) {
  Claim c = leapfrog
                ? claim("time-order-usl",
                        "With USL the time error (the difference from a run at a much smaller step "
                        "on the same grid) falls at the published order {expected} for "
                        "every method and E",
                        "{met} of {total} within {tolerance}; fitted orders {lo} to {hi}")
                : claim("time-order-usf-musl",
                        "With USF and MUSL the time error falls at first order ({expected}) for "
                        "MPM and GIMP at every E",
                        "{met} of {total} within {tolerance}; fitted orders {lo} to {hi}");
  c.number("expected", leapfrog ? kPublishedTimeOrder : 1.0)
      .number("tolerance", kOrderAgreement)
      .every("met", n.met, "total", n.total)
      .value("lo", n.total ? fixed(n.lo, 2) : "–")
      .value("hi", n.total ? fixed(n.hi, 2) : "–");
  return c;
}

Claim consistent_mass_claim(const Findings& f) {
  std::vector<std::string> orders;
  for (const auto& [method, order] : f.consistent_orders)
    orders.push_back(method + " " + fixed(order, 2));
  Claim c = claim("time-order-consistent-mass",
                  "With the consistent mass restored (FMPM of order {order}) and at an amplitude "
                  "{fraction} of the study's, USL's time error falls at the leapfrog order "
                  "{expected}: the first-order term of FLIP in the linear limit is its "
                  "lumped-mass re-projection",
                  "{met} of {total} within {tolerance} ({orders})");
  c.count("order", kConsistentOrder)
      .number("fraction", kLinearAmplitudeFraction)
      .number("expected", kPublishedTimeOrder)
      .number("tolerance", kOrderAgreement)
      .every("met", f.consistent.met, "total", f.consistent.total)
      .value("orders", list_of(orders));
  return c;
}

std::vector<Claim> convergence_claims(const Findings& f) {
  Claim agree = claim("orders-agree-across-E",
                      "The fitted orders in h of each method agree across E within {tolerance}",
                      "{agree} of {total} methods");
  agree.number("tolerance", kOrderAgreement).every("agree", f.agree.met, "total", f.agree.total);
  Claim published = claim("published-spatial-orders",
                          "Where an order in h is published for the basis, ours lies within "
                          "{tolerance} of it at every E",
                          "{met} of {total} (method, E) pairs");
  published.number("tolerance", kOrderAgreement)
      .every("met", f.published.met, "total", f.published.total);
  Claim theory = claim("orders-within-theory",
                       "Every fitted order in h above the theory's {theory} (by more than "
                       "{tolerance}) is pre-asymptotic: its last refinement falls at most at "
                       "{theory} + {tolerance}",
                       "{explained} of {above} fitted orders above it");
  theory.number("theory", kTheoryMaxOrder)
      .number("tolerance", kOrderAgreement)
      .every("explained", f.explained, "above", static_cast<long long>(f.above.size()));
  Claim uintah = claim("uintah-baseline-order",
                       "Linear MPM's order in h on the manufactured solution agrees with Uintah's "
                       "own baseline within {tolerance} (the error at the final time, as the "
                       "baseline measures it)",
                       "ours {ours}, the baseline's {theirs}");
  uintah.number("tolerance", kOrderAgreement)
      .value("ours", order_text(f.peer_at_T))
      .value("theirs", order_text(f.baseline.order_max));
  uintah.holds = f.peer_agrees;
  return {agree,
          published,
          time_order_claim(f.usl, true),
          time_order_claim(f.usf_musl, false),
          consistent_mass_claim(f),
          theory,
          uintah};
}

// A point's cell: the error and, from the second point on, the ratio to the point before it and
// the observed order: "3.2e-5 (3.9, 1.98)"; a point outside the regime orders are fitted in is
// marked "3.2e-5 †" and has no observed order.
std::string point_text(const Refinement& ref, std::size_t k, Norm n) {
  const Point& p = ref.points[k];
  const auto e = value_of(p, n);
  if (!e) return p.verdict.empty() || p.verdict == "stable" ? std::string("–") : p.verdict;
  std::string s = sci(*e, 2) + (p.fit ? "" : " †");
  if (k > 0) {
    const auto before = value_of(ref.points[k - 1], n);
    if (const auto o = ref[n].steps[k - 1]; o && before)
      s += " (" + fixed(*before / *e, 2) + ", " + fixed(*o, 2) + ")";
  }
  return s;
}

// The head of a table of refinements: `first` columns, one per point, then `last` columns.
std::string refinement_head(const char* first, const Refinement& ref, const char* last,
                            const char* rule) {
  std::ostringstream md;
  md << first;
  for (const auto& p : ref.points)
    md << " " << p.label << " |";
  md << last << rule;
  for (std::size_t k = 0; k < ref.points.size(); ++k)
    md << "---|";
  return md.str();
}

std::string sweep_table(const Refinements& sweep, Norm n) {
  std::ostringstream md;
  for (const auto& [key, ref] : sweep) {
    if (key == sweep.begin()->first)
      md << refinement_head("| E | method |", ref,
                            " fitted order | Richardson limit | error at T, finest grid (not "
                            "fitted) |\n",
                            "|---|---|")
         << "---|---|---|\n";
    md << "| " << shortest(key.first) << " | " << key.second << " |";
    for (std::size_t k = 0; k < ref.points.size(); ++k)
      md << " " << point_text(ref, k, n) << " |";
    const auto& at_T = ref.points.back().error_at_T;
    md << " " << order_text(ref[n].fitted) << " | " << (ref[n].limit ? sci(*ref[n].limit, 2) : "–")
       << " | " << (at_T ? sci(*at_T, 2) : "–") << " |\n";
  }
  return md.str();
}

std::string special_check(const Findings& f) {
  const auto items = [](const std::vector<std::pair<Key, double>>& factors) {
    std::vector<std::string> out;
    for (const auto& [E, x] : factors)
      out.push_back("E = " + shortest(E) + " (" + fixed(x, 2) + ")");
    return out;
  };
  std::ostringstream md;
  md << "**The instant T.** |sin(c pi T)|, the exact displacement at T over its amplitude: "
     << list_of(items(f.ordinary)) << (f.ordinary.empty() ? "" : ", away from zero");
  if (!f.special.empty())
    md << (f.ordinary.empty() ? "" : "; ") << list_of(items(f.special)) << " below "
       << shortest(kSpecialFactor) << ", where the error at T measures the phase, not the "
       << "displacement";
  md << ". Every order is fitted to a norm over the whole run all the same, which no instant can "
        "make small.";
  return md.str();
}

// A method whose orders disagree across E: the evidence per E.
std::string disagreement(const std::string& method, const MethodOrders& o) {
  std::vector<std::string> per_E;
  for (const auto& [E, order] : o.order) {
    std::vector<std::string> qs;
    for (const auto& v : o.steps.at(E))
      qs.push_back(v ? fixed(*v, 2) : std::string("–"));
    per_E.push_back(fixed(order, 2) + " at E = " + shortest(E) + " (observed " + list_of(qs) +
                    (o.asymptotic.at(E) ? ", asymptotic" : ", not yet asymptotic") + ")");
  }
  // The last refinement's order at each E: where these agree, the fitted orders differ only
  // through the coarse grids.
  std::string last = "; the last refinements' orders spread by " +
                     (o.last_spread ? fixed(*o.last_spread, 2) : std::string("–"));
  if (o.last_spread)
    last += o.last_agree ? ", within the tolerance: the difference is the coarse grids'"
                         : ", beyond the tolerance: the difference persists to the finest grid "
                           "here, where only the run length c T differs between the E";
  return method + ": fitted " + list_of(per_E) + last;
}

// Where the orders of a method disagree across E: the evidence per E.
std::string agreement_reading(const Findings& f) {
  std::ostringstream md;
  md << "**Orders across E.** E only rescales time: at the same T a larger E is a longer run in "
        "wave passes c T (";
  std::vector<std::string> passes;
  for (const auto& [E, cT] : f.wave_passes)
    passes.push_back("E = " + shortest(E) + ": c T = " + fixed(cT, 1));
  md << list_of(passes) << "), over which the error accumulates differently. ";
  std::vector<std::string> agree, differ;
  for (const auto& [method, o] : f.methods) {
    if (o.agree) agree.push_back(method);
    if (o.compared && !o.agree) differ.push_back(disagreement(method, o));
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

std::string above_theory_reading(const Findings& f) {
  std::ostringstream md;
  md << "**Orders above the theory's.** The particle quadrature limits the order in h to "
     << shortest(kTheoryMaxOrder) << " (Steffen, Kirby and Berzins (2008)). ";
  if (f.above.empty()) {
    md << "No fitted order exceeds it by more than " << shortest(kOrderAgreement) << ".";
    return md.str();
  }
  std::vector<std::string> items;
  for (const auto& x : f.above)
    items.push_back(x.method + " at E = " + shortest(x.E) + " (fitted " + fixed(x.fitted, 2) +
                    ", last refinement " + (x.last ? fixed(*x.last, 2) : std::string("–")) + ")");
  md << f.above.size() << " fitted orders exceed it by more than " << shortest(kOrderAgreement)
     << ": " << list_of(items) << ". ";
  // Which of them fall back to the theory's order (within kOrderAgreement) at the last
  // refinement: for those the fit is weighted by a coarse-grid regime that does not persist.
  std::vector<std::string> fall, stay;
  for (const auto& x : f.above)
    (x.falls ? fall : stay).push_back(x.method + " at E = " + shortest(x.E));
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

std::string published_table(const Findings& f) {
  std::ostringstream md;
  md << "| method | published order in h | source | ours (error over time), per E |\n"
        "|---|---|---|---|\n";
  for (const auto& [method, o] : f.methods) {
    const PublishedOrder pub = published_order(method);
    std::vector<std::string> ours;
    for (const auto& [E, order] : o.order)
      ours.push_back(fixed(order, 2) + " (E = " + shortest(E) + ")");
    md << "| " << method << " | " << (pub.order ? shortest(*pub.order) : "–") << " | " << pub.source
       << " | " << list_of(ours) << " |\n";
  }
  return md.str();
}

// What the USL rows show: the observed order of the first halving and of the last, over rows.
std::string usl_reading(const Findings& f) {
  if (f.first_halving.total == 0) return "";
  std::ostringstream md;
  md << "**Reading.** With USL the observed order of the first halving (from C = "
     << shortest(kTimeSampleCourant) << ") is " << fixed(f.first_halving.lo, 2) << " to "
     << fixed(f.first_halving.hi, 2) << " and that of the last " << fixed(f.last_halving.lo, 2)
     << " to " << fixed(f.last_halving.hi, 2) << ", over " << f.first_halving.total
     << " rows: the second-order term of the leapfrog reading shows only at the largest steps, "
        "and below them a first-order term takes over, with a constant far below USF's (compare "
        "the rows at the same C). Its source is FLIP's re-projection of the particle velocities "
        "through the lumped mass (docs/theory.md, \"Orders of convergence\"): the stored grid "
        "velocity grows by the consistent over the lumped mass times a dt while the positions move "
        "with a dt. The twins with FMPM("
     << kConsistentOrder << "), whose series restores the consistent mass, isolate it: ";
  std::vector<std::string> twins;
  for (const auto& row : f.time)
    if (row.consistent_mass || row.linear)
      twins.push_back(row.method + " at E = " + shortest(row.E) + " falls at " +
                      order_text(row.order));
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
    md << " " << order_text(row.order) << " | " << shortest(expected_time_order(row.update))
       << " | " << sci(double(work), 2) << " |\n";
  }
  return md.str();
}

std::string peer_section(const Spec& spec, const Findings& f) {
  if (!f.peer_row) return "";
  const ojson& first = *f.peer_row;
  const Baseline& b = f.baseline;
  std::ostringstream md;
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
     << first["ppc"].get<int>()
     << " particles per cell, the cfl policy at C = " << shortest(first["cfl_factor"].get<double>())
     << ", one wave transit (c T = " << shortest(*RunRow(first).wave_passes)
     << "), A / L = " << shortest(first["A"].get<double>())
     << " (the baseline's A over its bar's length L), on our unit bar with walls at both ends. "
        "The setting differs in what the scene declares, and each difference is named: Uintah's "
        "bar ends inside a larger domain (the nodes beyond it empty), ours fills the grid; its E "
        "only rescales time (as ours); its CFL step adds |v_p| to c, which at this amplitude moves "
        "dt by less than the amplitude's strain; its L2 norm is the root mean square over the "
        "particles at the final time.\n\n";
  for (const auto& [key, ref] : f.peer) {
    md << refinement_head("| norm |", ref, " fitted order |\n", "|---|") << "---|\n";
    for (const auto& [name, n] : {std::pair{"error at T (the baseline's norm)", Norm::at_T},
                                  std::pair{"error over time", Norm::over_time},
                                  std::pair{"L2 over time", Norm::l2_time}}) {
      md << "| " << name << " |";
      for (std::size_t k = 0; k < ref.points.size(); ++k)
        md << " " << point_text(ref, k, n) << " |";
      md << " " << order_text(ref[n].fitted) << " |\n";
    }
  }
  md << "\n**Reading.** In the baseline's norm our order is " << order_text(f.peer_at_T)
     << " and the baseline's " << order_text(b.order_max)
     << ". Of the differences named above, E and the |v_p| in its step do not move an order (E "
        "only rescales time; |v_p| / c is at most pi A / L = "
     << sci(std::acos(-1.0) * first["A"].get<double>(), 2)
     << " here); what is left is the bar's end: ours meets a wall on a node, Uintah's ends "
        "inside the grid beside empty nodes, where the boundary node holds a part of a cell's "
        "mass. A first-order error at such an end would give the baseline's order. The experiment "
        "that would decide it is the same bar, with its manufactured solution, ending inside a "
        "larger grid; the bar scene fills its grid (its body may not be placed), and the scenes "
        "that do end beside empty cells solve other problems, so no run here decides it: the "
        "difference is stated, not explained by a run.\n\n";
  return md.str();
}

// The index paragraph: the figure and the fitted orders in h. An E whose runs are under a wave
// pass has none fitted, and says why.
std::string convergence_index(const Spec& spec, const std::vector<ojson>& rows) {
  const Findings f = find(spec, rows);
  std::ostringstream md;
  md << "![" << spec.title << "](" << spec.name << ".png)\n\n**What it shows.** Fitted order "
     << "of the error over time in h:";
  for (const auto& [E, at] : f.index) {
    md << (E == f.index.begin()->first ? " " : "; ") << "E = " << shortest(E) << ": ";
    if (!at.any_fitted && at.under_a_pass) {
      md << "none fitted (its runs cover c T = " << shortest(*at.under_a_pass) << " < "
         << shortest(kMinWavePasses) << " wave pass: not stable)";
      continue;
    }
    for (std::size_t k = 0; k < at.by_method.size(); ++k)
      md << (k ? ", " : "") << at.by_method[k].first << " " << order_text(at.by_method[k].second);
  }
  md << ". The L2 norm over time, the observed order of each refinement, the time error against "
        "dt, the published orders and Uintah's baseline: ["
     << spec.name << ".md](" << spec.name << ".md).\n\n";
  return md.str();
}

// <name>_data.csv: E, panel (per E), series (per method), h and error of each run drawn.
std::string convergence_data(const Findings& f, const std::string& header) {
  std::map<Key, int> panel;
  std::map<std::string, int> series;
  for (const auto& [E, at] : f.index)
    panel.emplace(E, static_cast<int>(panel.size()));
  for (const auto& [method, o] : f.methods)
    series.emplace(method, static_cast<int>(series.size()));
  std::ostringstream csv;
  csv << header << "E,panel,series,method,h,error_over_time\n";
  for (const ojson* r : f.drawn_rows) {
    const std::string method = method_label(*r);
    const double E = (*r)["E"].get<double>();
    csv << shortest(E) << "," << panel[Key(E, "E")] << "," << series[method] << "," << method << ","
        << shortest(variable(*r)) << "," << shortest(*RunRow(*r).error_over_time) << "\n";
  }
  return csv.str();
}

// The runs drawn: those that reached T below A, the stable ones apart from those under a wave
// pass (drawn, never called stable, no order fitted on them: VerdictTally, run_row.hpp).
std::string convergence_subtitle(const Spec& spec, const ojson& doc) {
  const std::vector<ojson> rows(doc["cases"].begin(), doc["cases"].end());
  const Findings f = find(spec, rows);
  std::string s = std::to_string(f.drawn.stable) + " stable runs drawn";
  if (f.drawn.under_a_wave_pass > 0)
    s += ", " + std::to_string(f.drawn.under_a_wave_pass) + " under a wave pass (c T " +
         span(f.short_cT, 2) + ": not stable, no order fitted) drawn beside them";
  return s + ", " + std::to_string(f.left_out) + " not stable left out";
}

// The report: the findings once (with the time error runs), and from them the claims, the text
// and the figure's data.
StudyReport convergence_report(const ReportContext& ctx) {
  const Findings f = find(ctx.spec, ctx.rows, time_error_rows(ctx.spec, ctx.rows));
  std::ostringstream md;
  md << "## Error against h\n\n" << special_check(f) << "\n\n";
  if (f.first_h) {
    const ojson& first = *f.first_h;
    md << "A = " << shortest(first["A"].get<double>())
       << ", T = " << shortest(first["T"].get<double>()) << ", " << first["ppc"].get<int>()
       << " particles per cell, the fixed step of each row of the spec, small enough that the "
          "time error does not show (the time error section below measures it). ";
  }
  md << "Each cell gives the error and, in brackets, the ratio to the grid before it and the "
        "observed order (the log of the ratio over the log of the h ratio), so that the asymptotic "
        "range shows. The fitted order is the least-squares slope of log(error) against log(h); "
     << order_regime_text()
     << " (`†`: outside it; `–`: fewer than three points in it). The Richardson "
        "limit extrapolates the error from the three finest grids (near zero when it converges to "
        "zero, a floor otherwise). The error at T is shown for the finest grid and fitted to "
        "nothing.\n\n### The error over time (max over steps and particles of |u_p - u(X_p, "
        "t)|)\n\n"
     << sweep_table(f.h, Norm::over_time)
     << "\n### The L2 error over time (root mean square over the body and the run)\n\n"
     << sweep_table(f.h, Norm::l2_time) << "\n"
     << agreement_reading(f) << "\n\n"
     << above_theory_reading(f) << "\n\n"
     << "### Published orders beside ours\n\nThe sources are listed in docs/theory.md "
        "(\"Published orders\"). The claim below compares where a number is published.\n\n"
     << published_table(f)
     << "\n## The time error against dt\n\nOn one grid, every run is compared with a reference "
        "run at a step "
     << kTimeReferenceSubsteps / kTimeSubsteps.back()
     << " times smaller than the smallest, through the same sample instants (every "
     << shortest(kTimeSampleCourant)
     << " h / c, each cut into equal substeps; core/analysis/time_error.hpp): the largest "
        "difference of a particle position at any sample instant. The spatial error is common to "
        "both runs and cancels, so this is the error the time step makes, measured where it "
        "dominates by construction. Symplectic Euler as MPM steps it with USL (the velocity first, "
        "then the position with the new velocity) is the leapfrog scheme with the velocity at half "
        "steps: second order, the order Steffen, Kirby and Berzins (2010) measured where the time "
        "error dominates. USF updates the stress with the velocity of the start of the step and "
        "MUSL with the velocity re-mapped after it: first order. MPM and GIMP run with each update "
        "order. Each cell: the difference and, in brackets, the ratio to the step twice as large "
        "and its order.\n\n"
     << time_error_table(f.time) << "\n"
     << usl_reading(f)
     << "\n### The error against the exact solution at each C\n\nThe cfl runs of the spec on the "
        "same grid, against the exact solution (the error over time, so the grid's error shows): "
        "where it stops falling with dt, the time error is below the grid's. A run whose error "
        "over time is not accurate is marked `†` and left out of the fitted order.\n\n"
     << sweep_table(f.dt, Norm::over_time) << "\n"
     << peer_section(ctx.spec, f);
  return StudyReport{.markdown = md.str(),
                     .data_csv = convergence_data(f, ctx.csv_header),
                     .claims = convergence_claims(f)};
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
}  // namespace mpmstab::studies::convergence
