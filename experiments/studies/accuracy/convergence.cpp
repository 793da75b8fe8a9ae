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
#include <set>
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
// convergence"). FMPM of this order restores the consistent mass; its twins of the FLIP rows of
// MPM and GIMP at every E test that term.
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
// for MPM and GIMP with FLIP and USL, also with the other update orders and the consistent-mass
// twins: FMPM(kConsistentOrder) at the study's amplitude and at kLinearAmplitudeFraction of it,
// and the control, FLIP itself at the smaller amplitude.
struct TimeErrorRow {
  double E = 0;
  std::string method;  // the label, with its update order
  std::string update;
  TimeErrorStudy study;
  bool flip = false;             // the transfer is FLIP
  bool consistent_mass = false;  // the FMPM(kConsistentOrder) twin of a FLIP row
  bool linear = false;           // a twin at kLinearAmplitudeFraction of the amplitude
  ojson run;                     // its case's row at the amplitude it ran (what it covers)
  std::optional<double> order;   // fitted (find)
};
std::vector<TimeErrorRow> time_error_rows(const Spec& spec, const std::vector<ojson>& rows) {
  std::vector<TimeErrorRow> out, twins;
  std::map<std::pair<Key, std::string>, bool> seen;
  const auto row = [&](std::size_t i, const RunParams& p, const std::string& label, bool fmpm,
                       bool linear) {
    ojson run = rows[i];
    run["A"] = p.A;
    return TimeErrorRow{rows[i]["E"].get<double>(),
                        label,
                        std::string(to_string(p.update)),
                        time_errors(p, kTimeSampleCourant, kTimeSubsteps, kTimeReferenceSubsteps),
                        p.transfer == Transfer::flip,
                        fmpm,
                        linear,
                        run,
                        std::nullopt};
  };
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (sweep_of(rows[i]) != "dt") continue;
    const auto key = std::make_pair(Key(rows[i]["E"].get<double>(), "E"), method_label(rows[i]));
    if (std::exchange(seen[key], true)) continue;
    const RunParams& base = spec.cases[i].params;
    const bool twinned = base.transfer == Transfer::flip && base.update == UpdateOrder::usl &&
                         (base.method == Method::mpm || base.method == Method::gimp);
    for (const UpdateOrder u :
         twinned ? std::vector{UpdateOrder::usl, UpdateOrder::usf, UpdateOrder::musl}
                 : std::vector{base.update}) {
      RunParams p = base;
      p.update = u;
      out.push_back(row(i, p,
                        key.second + (u == base.update ? "" : "/" + std::string(to_string(u))),
                        false, false));
    }
    using Twin = std::pair<bool, double>;  // (FMPM, the fraction of the amplitude)
    for (const auto& [fmpm, fraction] : {Twin{true, 1.0}, Twin{true, kLinearAmplitudeFraction},
                                         Twin{false, kLinearAmplitudeFraction}}) {
      if (!twinned) break;
      RunParams p = base;
      p.A = base.A * fraction;
      if (fmpm) {
        p.transfer = Transfer::fmpm;
        p.fmpm_order = kConsistentOrder;
      }
      const std::string name = std::string(to_string(base.method)) +
                               (fmpm ? "/fmpm(" + std::to_string(kConsistentOrder) + ")" : "");
      twins.push_back(
          row(i, p, name + (fraction == 1.0 ? "" : ", A = " + param(p.A)), fmpm, fraction != 1.0));
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
  const ojson* row = nullptr;
};

enum class Norm { over_time, l2_time, at_T };
std::optional<double> value_of(const Point& p, Norm n) {
  return n == Norm::over_time ? p.over_time : n == Norm::l2_time ? p.l2_time : p.error_at_T;
}

// The observed order between two successive points, log(e1 / e2) / log(x1 / x2); none where
// either lies outside the regime orders are fitted in.
std::optional<double> step_order(const Point& coarse, const Point& fine, Norm n) {
  if (!coarse.fit || !fine.fit) return std::nullopt;
  const auto a = value_of(coarse, n), b = value_of(fine, n);
  if (!a || !b || *a <= 0 || *b <= 0) return std::nullopt;
  return std::log(*a / *b) / std::log(coarse.x / fine.x);
}

// The observed order of the last refinement in the regime orders are fitted in, and its index.
std::optional<std::pair<double, std::size_t>> last_order(
    const std::vector<std::optional<double>>& q) {
  for (std::size_t k = q.size(); k-- > 0;)
    if (q[k]) return std::pair{*q[k], k};
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

// A refinement (one sweep, E, amplitude and method): its points from the coarsest to the finest
// and, in each norm, its fitted order, the observed order of each refinement (steps[k - 1]: from
// point k - 1 to point k) and Richardson's limit; where it lies: its E (and A, off the study's
// amplitude).
struct Orders {
  std::optional<double> fitted, limit;
  std::vector<std::optional<double>> steps;
};
struct Refinement {
  std::string where;  // "E = 64", off the study's amplitude "E = 64, A = 2e-4"
  std::vector<Point> points;
  std::array<Orders, 3> norms;
  const Orders& operator[](Norm n) const { return norms[static_cast<std::size_t>(n)]; }
};
using Refinements = std::map<std::pair<Key, std::string>, Refinement>;  // by E and method

// The rows grouped by sweep (h at the study's amplitude, the first h row's, and at another: fine;
// dt and peer), then by E and method.
std::tuple<Refinements, Refinements, Refinements, Refinements> refinements(
    const std::vector<ojson>& rows) {
  std::map<std::string, Refinements> g;
  const ojson* first_h = nullptr;
  for (const auto& r : rows) {
    Point p{.row = &r};
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
    if (!first_h && sweep_of(r) == "h") first_h = &r;
    const bool fine = sweep_of(r) == "h" && r["A"] != (*first_h)["A"];
    Refinement& ref =
        g[fine ? "fine" : sweep_of(r)][{Key(r["E"].get<double>(), "E"), method_label(r)}];
    ref.where = "E = " + shortest(r["E"].get<double>()) +
                (fine ? ", A = " + param(r["A"].get<double>()) : "");
    ref.points.push_back(p);
  }
  for (auto& [sweep, by] : g)
    for (auto& [key, ref] : by) {
      auto& points = ref.points;
      std::sort(points.begin(), points.end(),
                [](const Point& a, const Point& b) { return TotalLess()(b.x, a.x); });
      for (const Norm n : {Norm::over_time, Norm::l2_time, Norm::at_T}) {
        Orders& o = ref.norms[static_cast<std::size_t>(n)];
        // The fitted order: the slope of log(error) against log(x) over the points with an error
        // in the regime orders are fitted in (at least three).
        std::vector<std::pair<double, double>> xy;
        for (const auto& p : points)
          if (const auto e = value_of(p, n); e && p.fit) xy.emplace_back(p.x, *e);
        o.fitted = loglog_slope(xy);
        o.limit = richardson_limit(points, n);
        for (std::size_t k = 1; k < points.size(); ++k)
          o.steps.push_back(step_order(points[k - 1], points[k], n));
      }
    }
  return {std::move(g["h"]), std::move(g["fine"]), std::move(g["dt"]), std::move(g["peer"])};
}

double spread(const std::map<Key, double>& orders) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& [E, o] : orders) {
    lo = std::min(lo, o);
    hi = std::max(hi, o);
  }
  return orders.empty() ? 0 : hi - lo;
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
    std::vector<double> q;  // the observed orders in the regime
    for (const auto& step : over_time.steps)
      if (step) q.push_back(*step);
    o.asymptotic[E] =
        q.size() >= 2 && std::abs(q[q.size() - 1] - q[q.size() - 2]) <= kAsymptoticSpread;
  }
  for (auto& [method, o] : m) {
    o.compared = o.order.size() >= 2;
    o.agree = o.compared && spread(o.order) <= kOrderAgreement;
    std::map<Key, double> last_orders;  // E -> the last refinement's order
    for (const auto& [E, q] : o.steps)
      if (const auto last = last_order(q)) last_orders[E] = last->first;
    if (!last_orders.empty()) o.last_spread = spread(last_orders);
    o.last_agree = o.last_spread && *o.last_spread <= kOrderAgreement;
  }
  return m;
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

// How many of a set (methods, pairs, rows) satisfy a claim, with the range of a value over them
// and where the runs that decide it lie.
struct Count {
  int met = 0, total = 0;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  Coverage on;
  void add(bool hit, double v = 0) {
    ++total;
    met += hit;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  void cover(const Refinement& ref) {
    for (const auto& p : ref.points)
      if (p.fit) on.add(*p.row);
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
  Refinements h, fine, dt, peer;                          // the sweeps
  Coverage fine_on;                                       // the runs of `fine`
  const ojson* first_h = nullptr;                         // the first row of the h sweep
  const ojson* peer_row = nullptr;                        // the last row of the peer measurement
  std::vector<std::pair<Key, double>> special, ordinary;  // E -> |sin(c pi T)|, below or not
  std::map<Key, double> wave_passes;                      // of the h sweep, per E
  std::map<std::string, MethodOrders> methods;
  Count agree;  // methods whose orders agree across E
  // Refinements of a basis with a published order: the last refinement's order (the range) within
  // kOrderAgreement of it; those beyond it named with both orders.
  Count published;
  std::vector<std::string> published_last;
  // Per method, its fitted orders in h beside the last refinement's, with its grids.
  std::map<std::string, std::vector<std::string>> ours;
  // Fitted orders above what theory allows, each named with the evidence, the last refinement's
  // order (what the order tends to once the coarse grids stop weighing); met where it falls back
  // to the theory's (within kOrderAgreement), those named in `fall`, the others in `stay`.
  Count explained;
  std::vector<std::string> above, fall, stay;
  std::vector<TimeErrorRow> time;
  Count usl, usf_musl;  // time orders met, each with the range of the orders
  // USL with FLIP: the observed order of the first halving (met: the difference at the smallest C
  // smaller than each USF row's at the same E), and of the last (met: within kOrderAgreement of
  // first order). USL with the other transfers: the fitted orders (met: the difference at the
  // smallest C larger than each USF row's at the same E), and their labels.
  Count first_halving, last_halving, other;
  std::vector<std::string> not_first_order;  // named with the last halving's order
  std::set<std::string> other_labels;
  // In the linear limit, per basis and E: the FMPM twin within kOrderAgreement of the leapfrog's
  // order where FLIP is not (the range: FMPM's), each named with both; the FMPM twins at the
  // study's amplitude (the range of their orders).
  Count consistent, consistent_study;
  std::vector<std::string> consistent_orders;
  Baseline baseline;
  std::optional<double> peer_at_T;  // our order in the baseline's norm
  Coverage peer_on;
  std::map<Key, OrdersAtE> index;
  VerdictTally drawn;  // the figure: the stable runs of the h sweep
  std::vector<const ojson*> drawn_rows;
  std::vector<double> short_cT;
  int left_out = 0;
};

// The time order of every row, and what the claims and the reading count: the sweep's rows against
// their update order's expected order (USL's by transfer: with FLIP its first and last halving of
// C, and each row's difference at the smallest C against the USF rows' at the same E), the
// consistent-mass twins in the linear limit against 2 and against FLIP's.
void time_orders(std::vector<TimeErrorRow> t, Findings& f) {
  std::map<Key, std::vector<double>> usf;  // E -> the USF rows' differences at the smallest C
  const auto last = [](const TimeErrorRow& row) { return row.study.points.back().max_difference; };
  for (auto& row : t) {
    std::vector<std::pair<double, double>> xy;  // the fitted order of the largest difference
    for (const auto& p : row.study.points)
      if (p.max_difference && *p.max_difference > 0) xy.emplace_back(p.courant, *p.max_difference);
    row.order = loglog_slope(xy);
    if (row.update == "usf" && last(row)) usf[Key(row.E, "E")].push_back(*last(row));
  }
  const auto near = [](const std::optional<double>& order, double expected) {
    return order && std::abs(*order - expected) <= kOrderAgreement;
  };
  std::optional<double> fmpm;  // the linear FMPM twin, until its FLIP control
  for (const auto& row : t) {
    if (row.consistent_mass && !row.linear && row.order)
      f.consistent_study.add(near(row.order, kPublishedTimeOrder), *row.order);
    if (row.consistent_mass && row.linear) fmpm = row.order;
    if (row.linear) f.consistent.on.add(row.run);
    if (!row.consistent_mass && row.linear && fmpm) {
      f.consistent.add(near(fmpm, kPublishedTimeOrder) && !near(row.order, kPublishedTimeOrder),
                       *fmpm);
      f.consistent_orders.push_back(row.method.substr(0, row.method.find(',')) +
                                    " at E = " + shortest(row.E) + " (FMPM(" +
                                    std::to_string(kConsistentOrder) + ") " + fixed(*fmpm, 2) +
                                    ", FLIP " + opt_fixed(row.order, 2) + ")");
    }
    if (row.consistent_mass || row.linear) continue;
    Count& n = row.update == "usl" ? f.usl : f.usf_musl;
    n.on.add(row.run);
    if (row.order) n.add(near(row.order, expected_time_order(row.update)), *row.order);
    const auto u = usf.find(Key(row.E, "E"));
    const auto& pts = row.study.points;
    if (row.update != "usl" || !last(row) || u == usf.end() || pts.size() < 3) continue;
    const auto [lo, hi] = std::minmax_element(u->second.begin(), u->second.end());
    if (!row.flip) {
      if (row.order) f.other.add(*last(row) > *hi, *row.order);
      f.other_labels.insert(row.method);
      continue;
    }
    auto q = [&](std::size_t k) -> std::optional<double> {
      if (!pts[k - 1].max_difference || !pts[k].max_difference || *pts[k].max_difference <= 0)
        return std::nullopt;
      return std::log2(*pts[k - 1].max_difference / *pts[k].max_difference);
    };
    const auto a = q(1), b = q(pts.size() - 1);  // the first and the last halving
    if (!a || !b) continue;
    f.first_halving.add(*last(row) < *lo, *a);
    f.last_halving.add(near(b, 1), *b);
    if (!near(b, 1))
      f.not_first_order.push_back(row.method + " at E = " + shortest(row.E) + " (" + fixed(*b, 2) +
                                  ")");
  }
  f.time = std::move(t);
}

// The findings from the rows and, in the report, the time error runs (time_error_rows).
Findings find(const Spec& spec, const std::vector<ojson>& rows, std::vector<TimeErrorRow> t = {}) {
  Findings f;
  std::tie(f.h, f.fine, f.dt, f.peer) = refinements(rows);
  std::map<Key, double> factor;  // E -> |sin(c pi T)|
  for (const auto& row : rows) {
    const RunRow r(row);
    const std::string sweep = sweep_of(row);
    const Key E(row["E"].get<double>(), "E");
    if (sweep == "peer") {
      f.peer_row = &row;
      f.peer_on.add(row);
    }
    if (sweep != "peer")
      factor[E] =
          std::abs(std::sin(std::sqrt(E.value()) * std::acos(-1.0) * row["T"].get<double>()));
    if (sweep != "h") continue;
    if (!f.first_h) f.first_h = &row;
    if (row["A"] != (*f.first_h)["A"]) {  // the finer grids at a smaller amplitude: not drawn
      f.fine_on.add(row);
      continue;
    }
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
  // The orders in h of each method across E; of every refinement against the theory's order and,
  // where one is published, the last refinement's against it.
  f.methods = orders_by_method(f.h);
  for (const auto& [key, ref] : f.h) {
    if (f.methods.at(key.second).compared) f.agree.cover(ref);
    OrdersAtE& at = f.index[key.first];
    at.by_method.emplace_back(key.second, ref[Norm::over_time].fitted);
    at.any_fitted = at.any_fitted || ref[Norm::over_time].fitted.has_value();
  }
  for (const auto& [method, o] : f.methods)
    if (o.compared) f.agree.add(o.agree);
  for (const Refinements* sweep : {&f.h, &f.fine})
    for (const auto& [key, ref] : *sweep) {
      const Orders& over_time = ref[Norm::over_time];
      const auto last = last_order(over_time.steps);
      if (over_time.fitted)
        f.ours[key.second].push_back(ref.where + ": " + fixed(*over_time.fitted, 2) + ", last " +
                                     (last ? fixed(last->first, 2) + " (" +
                                                 ref.points[last->second].label + " to " +
                                                 ref.points[last->second + 1].label + ")"
                                           : std::string("–")));
      if (const auto pub = published_order(key.second).order; pub && last) {
        const bool near = std::abs(last->first - *pub) <= kOrderAgreement;
        f.published.add(near, last->first);
        f.published.cover(ref);
        if (!near)
          f.published_last.push_back(key.second + " at " + ref.where + ": " +
                                     fixed(last->first, 2) + " against " + shortest(*pub));
      }
      if (!over_time.fitted || *over_time.fitted <= kTheoryMaxOrder + kOrderAgreement) continue;
      const std::string name = key.second + " at " + ref.where;
      const bool falls = last && last->first <= kTheoryMaxOrder + kOrderAgreement;
      f.explained.add(falls);
      f.explained.cover(ref);
      f.above.push_back(name + " (fitted " + fixed(*over_time.fitted, 2) + ", last refinement " +
                        (last ? fixed(last->first, 2) : std::string("–")) + ")");
      (falls ? f.fall : f.stay).push_back(name);
    }
  time_orders(std::move(t), f);
  f.baseline = read_baseline(spec.reference);
  if (!f.peer.empty()) f.peer_at_T = f.peer.begin()->second[Norm::at_T].fitted;
  return f;
}

// A claim about each case of a Count, within kOrderAgreement, measured on the Count's runs.
Claim counted(const char* id, const char* statement, const char* evidence, const Count& n) {
  Claim c = claim(id, statement, evidence);
  return c.number("tolerance", kOrderAgreement).every("met", n.met, "total", n.total).on(n.on);
}

// USL (leapfrog) or USF and MUSL: the time order of every method and E against the published one.
Claim time_order_claim(const Count& n, bool leapfrog) {
  const char* evidence = "{met} of {total} within {tolerance}; fitted orders {lo} to {hi}";
  Claim c = leapfrog ? counted("time-order-usl",
                               "With USL the time error (the difference from a run at a much "
                               "smaller step on the same grid) falls at the published order "
                               "{expected} for every method and E",
                               evidence, n)
                     : counted("time-order-usf-musl",
                               "With USF and MUSL the time error falls at first order ({expected}) "
                               "for MPM and GIMP at every E",
                               evidence, n);
  c.number("expected", leapfrog ? kPublishedTimeOrder : 1.0)
      .value("lo", n.total ? fixed(n.lo, 2) : "–")
      .value("hi", n.total ? fixed(n.hi, 2) : "–");
  return c;
}

std::vector<Claim> convergence_claims(const Findings& f) {
  Claim consistent = counted(
      "time-order-consistent-mass",
      "At an amplitude {fraction} of the study's, USL's time error falls at the leapfrog order "
      "{expected} (within {tolerance}) with the consistent mass restored (FMPM of order {order}) "
      "and not with FLIP, for MPM and GIMP at every E: there FLIP's first-order term is its "
      "lumped-mass re-projection",
      "{met} of {total} (basis and E) ({orders})", f.consistent);
  consistent.number("fraction", kLinearAmplitudeFraction)
      .number("expected", kPublishedTimeOrder)
      .count("order", kConsistentOrder)
      .value("orders", list_of(f.consistent_orders));
  Claim published = counted("published-spatial-orders",
                            "Where an order in h is published for the basis, the last "
                            "refinement's observed order (the order to expect on finer grids) lies "
                            "within {tolerance} of it at every E and amplitude run",
                            "{met} of {total} refinements within it (last refinements' orders "
                            "{lo} to {hi}); beyond it: {last}",
                            f.published);
  published.value("lo", f.published.total ? fixed(f.published.lo, 2) : "–")
      .value("hi", f.published.total ? fixed(f.published.hi, 2) : "–")
      .value("last", f.published_last.empty() ? "none" : list_of(f.published_last));
  Claim theory = counted("orders-within-theory",
                         "Every fitted order in h above the theory's {theory} (by more than "
                         "{tolerance}) is pre-asymptotic: its last refinement falls at most at "
                         "{theory} + {tolerance}",
                         "{met} of {total} fitted orders above it", f.explained);
  theory.number("theory", kTheoryMaxOrder);
  Claim uintah = claim("uintah-baseline-order",
                       "Linear MPM's order in h on the manufactured solution agrees with Uintah's "
                       "own baseline within {tolerance} (the error at the final time, as the "
                       "baseline measures it)",
                       "ours {ours}, the baseline's {theirs}");
  uintah.number("tolerance", kOrderAgreement)
      .value("ours", opt_fixed(f.peer_at_T, 2))
      .value("theirs", opt_fixed(f.baseline.order_max, 2))
      .on(f.peer_on.text() + "; the baseline's records");
  uintah.holds = f.peer_at_T && f.baseline.order_max &&
                 std::abs(*f.peer_at_T - *f.baseline.order_max) <= kOrderAgreement;
  return {counted("orders-agree-across-E",
                  "The fitted orders in h of each method agree across E within {tolerance}",
                  "{met} of {total} methods", f.agree),
          published,
          time_order_claim(f.usl, true),
          time_order_claim(f.usf_musl, false),
          consistent,
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
  md << last << rule << rule_cells(ref.points.size());
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
    md << " " << opt_fixed(ref[n].fitted, 2) << " | " << opt_sci(ref[n].limit) << " | "
       << opt_sci(at_T) << " |\n";
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
      qs.push_back(opt_fixed(v, 2));
    per_E.push_back(fixed(order, 2) + " at E = " + shortest(E) + " (observed " + list_of(qs) +
                    (o.asymptotic.at(E) ? ", asymptotic" : ", not yet asymptotic") + ")");
  }
  std::string last = "; the last refinements' orders spread by " + opt_fixed(o.last_spread, 2);
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
  std::vector<std::string> fitted;  // the E at which any order is fitted
  for (const auto& [E, at] : f.index)
    if (at.any_fitted) fitted.push_back("E = " + shortest(E));
  md << "The fitted orders of " << list_of(agree) << " agree across the E at which orders are "
     << "fitted (" << list_of(fitted) << ") within " << shortest(kOrderAgreement) << ". ";
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
  md << f.above.size() << " fitted orders exceed it by more than " << shortest(kOrderAgreement)
     << ": " << list_of(f.above) << ". ";
  if (!f.fall.empty())
    md << "At the last refinement " << list_of(f.fall) << " "
       << (f.fall.size() == 1 ? "falls" : "fall") << " to within " << shortest(kOrderAgreement)
       << " of it: there the fitted order is weighted by coarse grids whose order does not "
          "persist, and the order to expect on finer grids is the last refinement's. ";
  if (!f.stay.empty())
    md << list_of(f.stay) << " " << (f.stay.size() == 1 ? "stays" : "stay") << " above it at the "
       << "last refinement: the grids run do not show where "
       << (f.stay.size() == 1 ? "its" : "their") << " order settles. ";
  md << "What makes the coarse grids converge faster is not isolated here.";
  return md.str();
}

// The refinements off the study's amplitude: the bases with a published order on finer grids.
std::string fine_section(const Findings& f) {
  if (f.fine.empty()) return "";
  const ojson& first = *f.fine.begin()->second.points.front().row;
  return "### The bases with a published order on finer grids\n\nThe same error over time on "
         "finer grids, at a smaller amplitude so that no particle crosses a cell there (" +
         f.fine_on.text() + ", dt = " + param(first["dt"].get<double>()) + "):\n\n" +
         sweep_table(f.fine, Norm::over_time) + "\n";
}

// Each method's published order beside ours: per E (and amplitude) the fitted order and the last
// refinement's observed order, with its grids.
std::string published_table(const Findings& f) {
  std::ostringstream md;
  md << "| method | published order in h | source | ours (error over time): fitted, and the last "
        "refinement's observed order |\n|---|---|---|---|\n";
  for (const auto& [method, o] : f.methods) {
    const PublishedOrder pub = published_order(method);
    const auto ours = f.ours.find(method);
    md << "| " << method << " | " << (pub.order ? shortest(*pub.order) : "–") << " | " << pub.source
       << " | " << (ours == f.ours.end() ? "" : list_of(ours->second)) << " |\n";
  }
  return md.str();
}

// What the USL rows show, by transfer, and the consistent-mass twins beside them.
std::string usl_reading(const Findings& f) {
  if (f.first_halving.total == 0) return "";
  const Count &a = f.first_halving, &b = f.last_halving, &o = f.other, &fmpm = f.consistent_study;
  std::ostringstream md;
  md << "**Reading.** With USL and FLIP (" << a.total
     << " rows) the observed order of the first halving (from C = " << shortest(kTimeSampleCourant)
     << ") is " << fixed(a.lo, 2) << " to " << fixed(a.hi, 2) << " and that of the last "
     << fixed(b.lo, 2) << " to " << fixed(b.hi, 2) << "; the last lies within "
     << shortest(kOrderAgreement) << " of first order in " << b.met << " of " << b.total << " rows"
     << (f.not_first_order.empty() ? "" : " (not in " + list_of(f.not_first_order) + ")")
     << ", and the difference at the smallest C is smaller than each USF row's at the same E in "
     << a.met << " of " << a.total << ". ";
  if (o.total > 0)
    md << "The rows of " << list_of({f.other_labels.begin(), f.other_labels.end()}) << " ("
       << o.total << " rows, USL) barely fall with the step: fitted orders " << fixed(o.lo, 2)
       << " to " << fixed(o.hi, 2)
       << "; at the smallest C their difference is larger than each USF row's at "
       << "the same E in " << o.met << " of " << o.total << ". ";
  md << "The FMPM(" << kConsistentOrder
     << ") twins of the FLIP rows of MPM and GIMP, whose series restores the consistent mass, "
        "test one candidate for FLIP's first-order term, its re-projection of the particle "
        "velocities through the lumped mass (docs/theory.md, \"Orders of convergence\"), with "
        "FLIP itself as the control, at an amplitude "
     << shortest(kLinearAmplitudeFraction)
     << " of the study's, where the particles barely move across the grid: "
     << list_of(f.consistent_orders) << "; the claim above says what they decide. ";
  if (fmpm.total > 0)
    md << "At the study's amplitude the FMPM twins fall at " << fixed(fmpm.lo, 2) << " to "
       << fixed(fmpm.hi, 2) << ", within " << shortest(kOrderAgreement)
       << " of the leapfrog order in " << fmpm.met << " of " << fmpm.total
       << (fmpm.met == 0 ? ": there the consistent mass alone does not bring that order, and what "
                           "else is first order there is not isolated here"
                         : "")
       << ".";
  md << "\n\n";
  return md.str();
}

std::string time_error_table(const std::vector<TimeErrorRow>& t) {
  if (t.empty()) return "";
  std::ostringstream md;
  md << "| E | method |";
  for (const auto& p : t.front().study.points)
    md << " C = " << shortest(p.courant) << " |";
  md << " fitted order | expected | particle-steps |\n|---|---|"
     << rule_cells(t.front().study.points.size()) << "---|---|---|\n";
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
    md << " " << opt_fixed(row.order, 2) << " | " << shortest(expected_time_order(row.update))
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
  md << list_of(pairs) << "; fitted order in h " << opt_fixed(b.order_max, 2) << " (max) and "
     << opt_fixed(b.order_l2, 2) << " (L2).\n\n"
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
      md << " " << opt_fixed(ref[n].fitted, 2) << " |\n";
    }
  }
  md << "\n**Reading.** In the baseline's norm our order is " << opt_fixed(f.peer_at_T, 2)
     << " and the baseline's " << opt_fixed(b.order_max, 2)
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
std::string convergence_index(const Spec& spec, const std::vector<ojson>& rows, const ojson&) {
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
      md << (k ? ", " : "") << at.by_method[k].first << " " << opt_fixed(at.by_method[k].second, 2);
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
       << " particles per cell, the fixed step of each row of the spec, meant to keep the time "
          "error below the spatial one (the time error section below measures it on one grid). ";
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
     << fine_section(f)
     << "### Published orders beside ours\n\nThe sources are listed in docs/theory.md "
        "(\"Published orders\"). Where a number is published, the claim in the conclusions above "
        "compares it with the last refinement's observed order, the order to expect on finer "
        "grids by the reading above.\n\n"
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
