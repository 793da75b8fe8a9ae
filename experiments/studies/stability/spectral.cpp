// The spectral study: each scheme's spectral limit (core/analysis/spectral.hpp) beside two runs of
// the bar at a tiny amplitude under the spectral policy, at 0.95 and at 1.05 times the limit. The
// limit is confirmed when the first stays bounded and the second grows. Beside them, eq. (108)'s
// minimum over runs below the limit at every E the studies use, every particles per cell and
// several grids: its ratio to the limit, which is not fixed by c dt / h, A/h and c T (eq. (108) is
// not dimensionally homogeneous), against its value at rest.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "analysis/spectral.hpp"
#include "analysis/stable_dt.hpp"
#include "base/params.hpp"
#include "claims.hpp"
#include "csv.hpp"
#include "key.hpp"
#include "report_util.hpp"
#include "run_row.hpp"
#include "shared/paper_table1.hpp"
#include "study.hpp"

namespace mpmstab::studies::spectral {
namespace {

using ojson = nlohmann::ordered_json;

// A bounded run's error, its phase error included, is at most 2 A; a growing mode passes 3 A.
constexpr double kBound = 3.0;
// The particles per cell of the paper's bar (the default layout).
const int kDefaultPpc = RunParams{}.ppc;
// The methods of the figure's data, in the order of their codes.
const std::vector<std::string> kFigureMethods = {"mpm", "gimp"};

// The scheme rows: those at the first row's E and grid (each scheme's pair of runs). The others
// measure eq. (108) against the limit at other E and particle counts (one run each, at 0.95
// times the limit).
bool scheme_row(const ojson& r, const ojson& first) {
  return r["E"] == first["E"] && r["cells"] == first["cells"];
}

// The distinct safety factors s of the runs below (s < 1) or above (s > 1) the limit, of the
// scheme rows only or of every row: "0.95".
std::string safeties(const std::vector<ojson>& rows, bool below, bool schemes_only) {
  std::vector<double> v;
  for (const auto& r : rows) {
    if (!has_number(r, "safety") || (schemes_only && !scheme_row(r, rows.front()))) continue;
    const double s = r["safety"].get<double>();
    if (below ? s < 1 : s > 1) v.push_back(s);
  }
  return listing(std::move(v));
}

// A run is bounded when it reached T and its error over time stayed within kBound A, as the
// spectral_edge search counts it; a bounded run may still be meaningless (error >= A), which
// its text says.
bool bounded(const ojson& r) {
  const RunRow run(r);
  return run.survived() && run.error_over_time && *run.error_over_time <= kBound * *run.A;
}

// "bounded (error 0.41 A)", "bounded (error 1.2 A, meaningless)", "grew (error 2.3e+02 A)",
// "* nonpositive_F at step 96 (...)".
std::string run_text(const ojson& r) {
  const RunRow run(r);
  if (run.outcome == "unstable") return verdict(r);
  if (!run.error_over_time) return "–";
  const double ratio_to_A = *run.error_over_time / *run.A;
  return std::string(bounded(r) ? "bounded" : "grew") + " (error " + sci(ratio_to_A) + " A" +
         (bounded(r) && run.outcome == "meaningless" ? ", meaningless" : "") + ")";
}

// A row's layout parameter (0, the uniform layout, where the row has none).
double layout_of(const ojson& r, const char* key) {
  return has_number(r, key) ? r[key].get<double>() : 0.0;
}

// One scheme: its two runs, by the policy's safety factor.
struct Scheme {
  std::string name;              // scheme_label
  const ojson* below = nullptr;  // s < 1
  const ojson* above = nullptr;  // s > 1
  const ojson& row() const { return below ? *below : *above; }
  std::optional<double> limit() const { return RunRow(row()).courant_spectral; }
  int ppc() const { return row()["ppc"].get<int>(); }
  bool uniform_two() const {  // the default particles per cell, uniform layout
    return ppc() == kDefaultPpc && layout_of(row(), "shift") == 0 &&
           layout_of(row(), "jitter") == 0;
  }
  bool confirmed() const { return below && above && bounded(*below) && !bounded(*above); }
  // The eq. (108) bound of the run below the limit (its minimum over the run), in c dt / h.
  std::optional<double> eq108() const {
    if (!below || !has_number(*below, "dt_stable_min")) return std::nullopt;
    return (*below)["dt_stable_min"].get<double>() / (*below)["dt_cfl"].get<double>();
  }
};

// The schemes of the scheme rows.
std::vector<Scheme> schemes_of(const std::vector<ojson>& rows) {
  std::vector<Scheme> out;
  for (const auto& r : rows) {
    if (!scheme_row(r, rows.front())) continue;
    const std::string name = scheme_label(r);
    auto it = std::find_if(out.begin(), out.end(), [&](const Scheme& s) { return s.name == name; });
    if (it == out.end()) it = out.insert(out.end(), Scheme{name});
    const double s = has_number(r, "safety") ? r["safety"].get<double>() : 1.0;
    (s < 1 ? it->below : it->above) = &r;
  }
  return out;
}

// The measured edges of the spectral_edge experiment at a tiny amplitude, by scheme label, in
// c dt / h (empty when it has not been run), and where their runs lie.
std::map<std::string, double> measured_edges(const StudyInputs& inputs, Coverage& at) {
  std::map<std::string, double> out;
  const auto it = inputs.find("spectral_edge");
  if (it == inputs.end() || !it->second.present()) return out;
  for (const auto& r : it->second.doc.at("cases")) {
    if (r["A"].get<double>() >= 1e-5 || !has_number(r, "dt_edge")) continue;
    out[scheme_label(r)] = r["dt_edge"].get<double>() / r["dt_cfl"].get<double>();
    at.add(r);
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Eq. (108) against the limit, per E and per particle count

// The bases eq. (108) is derived for, in the order of the tables.
const std::vector<std::string> kEq108Bases = {"mpm", "gimp", "cpgimp"};

// One run below the limit (s < 1) of a basis eq. (108) is derived for, with USL, FLIP and the
// uniform layout: eq. (108)'s minimum over it and the limit, both in c dt / h, and eq. (108) at
// rest at the same E, grid and particles per cell.
struct Eq108Point {
  std::string method;
  double E = 0;
  int cells = 0, ppc = 0, particles = 0;
  double A = 0, T = 0, safety = 0;
  double limit = 0, eq108 = 0, rest = 0;
  const ojson* row = nullptr;  // its run
  double ratio() const { return eq108 / limit; }
  double c() const { return std::sqrt(E); }  // the bar's density is 1
  // How far the run's state moved eq. (108) from its value at rest, relative.
  double state_shift() const { return std::abs(1 - eq108 / rest); }
};

std::vector<Eq108Point> eq108_points(const std::vector<ojson>& rows) {
  std::vector<Eq108Point> out;
  for (const auto& r : rows) {
    const RunRow run(r);
    const std::string& m = run.method;
    const auto method = parse_method(m);
    if (!method || !has_eq108(*method) || run.method_label != m || layout_of(r, "shift") != 0 ||
        layout_of(r, "jitter") != 0 || !has_number(r, "safety") || r["safety"].get<double>() >= 1 ||
        !run.courant_spectral || !has_number(r, "dt_stable_min"))
      continue;
    const double dt_cfl = r["dt_cfl"].get<double>();
    Eq108Point p{m,
                 r["E"].get<double>(),
                 r["cells"].get<int>(),
                 r["ppc"].get<int>(),
                 int(*run.particles),
                 r["A"].get<double>(),
                 r["T"].get<double>(),
                 r["safety"].get<double>(),
                 *run.courant_spectral,
                 r["dt_stable_min"].get<double>() / dt_cfl};
    // Eq. (108) at rest (F = 1, no stress, no velocity) at the run's E, h = c dt_cfl and
    // particles per cell, in c dt / h: the formula's constants alone.
    StableDtInputs rest;
    rest.F_max = 1;
    const double h = dt_cfl * std::sqrt(p.E);
    const StableDtGeometry geometry{*method, p.E, h, p.ppc, h / p.ppc};
    p.rest = stable_dt(rest, geometry, StressScaling::scaled) / dt_cfl;
    p.row = &r;
    out.push_back(p);
  }
  return out;
}

// Thresholds of the claims. A bound homogeneous in E would give the same ratio at every E of a
// run at the same c dt / h, A and c T (E alone rescales time). At a fixed grid the measured ratio
// falls about as ppc^(-1/2); at a fixed number of particles per cell it does not move with the
// grid. At a tiny amplitude the state (F - 1, the stress, the velocities) moves the bound by
// less than kStateNegligible, relative, from its value at rest.
constexpr double kHomogeneousSpread = 1.1;
constexpr double kSqrtSlope = -0.5, kSlopeTolerance = 0.1;
constexpr double kStateNegligible = 0.01;

// The runs the eq. (108) section reads: every run's point, and those on the first row's grid by
// E, particles per cell and basis.
struct Eq108Grid {
  std::vector<Eq108Point> points;
  int cells0 = 0, ppc0 = 0;
  double E0 = 0, cT_lo = 1e300, cT_hi = 0;
  std::vector<double> Es;
  std::vector<int> ppcs;
  std::vector<std::string> bases;
  const Eq108Point* find(const std::string& m, double E, int ppc) const {
    for (const auto& p : points)
      if (p.method == m && p.E == E && p.ppc == ppc && p.cells == cells0) return &p;
    return nullptr;
  }
  // The runs of basis `m` at the first row's E and particles per cell, by particle count (grids
  // refined at a fixed particles per cell); empty where fewer than two.
  std::vector<const Eq108Point*> by_count(const std::string& m) const {
    std::vector<const Eq108Point*> out;
    for (const auto& p : points)
      if (p.method == m && p.E == E0 && p.ppc == ppc0) out.push_back(&p);
    if (out.size() < 2) return {};
    std::sort(out.begin(), out.end(),
              [](const Eq108Point* x, const Eq108Point* y) { return x->particles < y->particles; });
    return out;
  }
  std::vector<int> ppcs_of(const std::string& m) const {
    std::vector<int> out;
    for (int ppc : ppcs)
      if (std::any_of(Es.begin(), Es.end(), [&](double E) { return find(m, E, ppc); }))
        out.push_back(ppc);
    return out;
  }
};

Eq108Grid eq108_grid(const std::vector<ojson>& rows) {
  Eq108Grid g;
  g.points = eq108_points(rows);
  const ojson& first = rows.front();
  g.cells0 = first["cells"].get<int>();
  g.ppc0 = first["ppc"].get<int>();
  g.E0 = first["E"].get<double>();
  for (const auto& p : g.points) {
    if (p.cells != g.cells0) continue;
    add_unique(g.Es, p.E);
    add_unique(g.ppcs, p.ppc);
    g.cT_lo = std::min(g.cT_lo, p.c() * p.T);
    g.cT_hi = std::max(g.cT_hi, p.c() * p.T);
  }
  std::sort(g.Es.begin(), g.Es.end(), TotalLess());
  std::sort(g.ppcs.begin(), g.ppcs.end());
  for (const auto& b : kEq108Bases)
    if (std::any_of(g.points.begin(), g.points.end(),
                    [&](const Eq108Point& p) { return p.method == b && p.cells == g.cells0; }))
      g.bases.push_back(b);
  return g;
}

// Per E at the first row's particles per cell, one row of the table per basis run there: its run
// and its ratio over every particles per cell run at that E (n of them, ppc_lo to ppc_hi).
struct Eq108Row {
  const Eq108Point* p = nullptr;
  double lo = 1e300, hi = 0;
  int n = 0, ppc_lo = 0, ppc_hi = 0;
};

// What the eq. (108) section finds: its runs; how far one basis and layout moves with E (the
// largest spread, between the runs spread_lo and spread_hi of one basis and particles per cell);
// GIMP's ratio against the particles per cell at the first E and against the particle count; how
// far the state moved the bound from rest; the table per E and each E's range of the ratio over
// the bases and particles per cell; the range at the first row's particles per cell over every E,
// for the scheme table's reading (lo > hi: none); the grids run; the runs below the limit and the
// one with the largest ratio; where the runs of each claim lie (run_row.hpp): every run, those on
// the first row's grid, GIMP's against the particles per cell and against the particle count.
// Its pointers are into grid.points: it is moved, never copied.
struct Eq108Findings {
  Eq108Grid grid;
  double spread = 1;
  const Eq108Point *spread_lo = nullptr, *spread_hi = nullptr;  // none: no spread above 1
  std::vector<std::pair<double, double>> by_ppc;                // GIMP at the first E: ppc, ratio
  std::vector<const Eq108Point*> gimp_count;                    // GIMP by particle count
  std::optional<double> ppc_slope, count_slope;
  double shift = 0;
  const Eq108Point* shifted = nullptr;  // the run whose state moved the bound most
  std::vector<Eq108Row> rows;
  std::vector<std::pair<double, std::pair<double, double>>> per_E;  // E -> ratio lo, hi
  double lo = 1e300, hi = 0;
  int cells_lo = 0, cells_hi = 0, below = 0;
  const Eq108Point* worst = nullptr;
  Coverage points_at, grid_at, ppc_at, count_at;
};

// The largest spread of the ratio over E at one basis and particles per cell.
void find_spread(Eq108Findings& f) {
  const Eq108Grid& g = f.grid;
  for (const auto& b : g.bases) {
    for (int ppc : g.ppcs) {
      const Eq108Point *lo = nullptr, *hi = nullptr;
      for (double E : g.Es) {
        const Eq108Point* p = g.find(b, E, ppc);
        if (!p) continue;
        if (!lo || p->ratio() < lo->ratio()) lo = p;
        if (!hi || p->ratio() > hi->ratio()) hi = p;
      }
      if (lo && hi->ratio() / lo->ratio() > f.spread) {
        f.spread = hi->ratio() / lo->ratio();
        f.spread_lo = lo;
        f.spread_hi = hi;
      }
    }
  }
}

// The findings of the eq. (108) section.
Eq108Findings eq108_findings(const std::vector<ojson>& rows) {
  Eq108Findings f{.grid = eq108_grid(rows)};
  const Eq108Grid& g = f.grid;
  find_spread(f);
  for (double E : g.Es) {
    double lo = 1e300, hi = 0;
    for (const auto& b : g.bases) {
      Eq108Row row{.p = g.find(b, E, g.ppc0)};
      for (int ppc : g.ppcs) {
        if (const Eq108Point* p = g.find(b, E, ppc)) {
          row.lo = std::min(row.lo, p->ratio());
          row.hi = std::max(row.hi, p->ratio());
          ++row.n;
        }
      }
      lo = std::min(lo, row.lo);
      hi = std::max(hi, row.hi);
      if (!row.p) continue;
      f.lo = std::min(f.lo, row.p->ratio());
      f.hi = std::max(f.hi, row.p->ratio());
      row.ppc_lo = g.ppcs_of(b).front();
      row.ppc_hi = g.ppcs_of(b).back();
      f.rows.push_back(row);
    }
    if (hi > 0) f.per_E.push_back({E, {lo, hi}});
  }
  f.cells_lo = f.cells_hi = g.cells0;
  for (const auto& p : g.points) {
    f.cells_lo = std::min(f.cells_lo, p.cells);
    f.cells_hi = std::max(f.cells_hi, p.cells);
    f.below += p.ratio() < 1;
    f.points_at.add(*p.row);
    if (p.cells == g.cells0) f.grid_at.add(*p.row);
    if (!f.worst || p.ratio() > f.worst->ratio()) f.worst = &p;
    if (p.method == "gimp" && p.E == g.E0 && p.cells == g.cells0) {
      f.by_ppc.emplace_back(p.ppc, p.ratio());
      f.ppc_at.add(*p.row);
    }
    if (!f.shifted || p.state_shift() > f.shift) {
      f.shift = p.state_shift();
      f.shifted = &p;
    }
  }
  f.ppc_slope = loglog_slope(f.by_ppc);
  if (std::find(g.bases.begin(), g.bases.end(), "gimp") != g.bases.end())
    f.gimp_count = g.by_count("gimp");
  std::vector<std::pair<double, double>> by_count;  // GIMP: particles, ratio
  for (const Eq108Point* p : f.gimp_count) {
    by_count.emplace_back(p->particles, p->ratio());
    f.count_at.add(*p->row);
  }
  f.count_slope = loglog_slope(by_count);
  return f;
}

// The paper's dt stable column of Table 1 in c dt / h, per method, A and E: the median of its
// rows (each dt), the E and the (method, A) in the order read, and how many medians lie above
// the spectral limit of their method (of those with a limit).
struct PaperFindings {
  std::vector<double> Es;
  std::vector<std::pair<std::string, double>> keys;
  std::map<std::tuple<std::string, Key, Key>, double> medians;
  int above = 0, cells = 0;
};

// What the study finds, from its rows, the measured edges (spectral_edge, where it has been run)
// and the paper's Table 1: each scheme and whether its limit is confirmed, the safety factors of
// its runs, the range of the limits per update order (at the default particles per cell and the
// uniform layout), of eq. (108) and of the measured edge over the limit, and the eq. (108)
// section's and the paper's findings; where the schemes' runs and the measured edges' runs lie
// (run_row.hpp). Its schemes point into the rows.
struct Findings {
  std::vector<Scheme> schemes;
  Coverage schemes_at, edges_at;
  int confirmed = 0;
  std::vector<std::string> not_confirmed;
  std::string below, above;  // the safety factors of the scheme rows: "0.95", "1.05"
  std::map<std::string, std::pair<double, double>> limits;  // update order -> lo, hi
  double eq_lo = 1e300, eq_hi = 0, edge_lo = 1e300, edge_hi = 0;
  int particles_lo = 0, particles_hi = 0;
  std::map<std::string, double> edges;  // measured_edges
  Eq108Findings eq108;
  std::optional<PaperFindings> paper;  // none without Table 1
  const Scheme* scheme(const std::string& name) const {
    for (const auto& s : schemes)
      if (s.name == name) return &s;
    return nullptr;
  }
};

// The paper's grid for Table 1 (experiments/table1.json): h = 1 / kPaperCells.
constexpr int kPaperCells = 100;

// The findings on Table 1 (none without it).
std::optional<PaperFindings> paper_findings(const std::filesystem::path& reference,
                                            const Findings& f) {
  if (reference.empty() || !std::filesystem::exists(reference)) return std::nullopt;
  PaperFindings p;
  std::map<std::tuple<std::string, Key, Key>, std::vector<double>> values;
  for (const PaperRow& r : read_paper_rows(reference)) {
    add_unique(p.Es, r.E);
    add_unique(p.keys, {r.method, r.A});
    // Table 1's own reading of a cell: '*' and unreadable text ('4.?e-6') are no number.
    const PaperValue& dt_stable = r.cell.dt_stable;
    if (dt_stable.kind != PaperValue::number || !(dt_stable.value > 0)) continue;
    values[{r.method, Key(r.A), Key(r.E)}].push_back(dt_stable.value * std::sqrt(r.E) *
                                                     kPaperCells);
  }
  std::sort(p.Es.begin(), p.Es.end());  // finite: read_paper_rows refuses any other E
  for (const auto& [key, v] : values) {
    const double m = p.medians[key] = quantile(v, 0.5);
    const Scheme* s = f.scheme(std::get<0>(key));
    if (!s || !s->limit()) continue;
    ++p.cells;
    p.above += m > *s->limit() ? 1 : 0;
  }
  return p;
}

// The findings of the rows, the measured edges and Table 1 (none for the index and the
// subtitle, which print no finding of the measured edges).
Findings find(const Spec& spec, const std::vector<ojson>& rows, const StudyInputs& inputs) {
  Findings f{.schemes = schemes_of(rows),
             .below = safeties(rows, true, true),
             .above = safeties(rows, false, true),
             .eq108 = eq108_findings(rows)};
  f.edges = measured_edges(inputs, f.edges_at);
  for (const auto& s : f.schemes) {
    for (const ojson* r : {s.below, s.above})
      if (r) f.schemes_at.add(*r);
    if (s.confirmed())
      ++f.confirmed;
    else
      f.not_confirmed.push_back(s.name);
    const auto limit = s.limit();
    if (limit && s.uniform_two()) {
      std::string update = "usl";  // the name's update order: "gimp/xpic(2)/usf" -> "usf"
      for (const char* u : {"/usf", "/musl"})
        if (s.name.find(u) != std::string::npos) update = u + 1;
      auto [it, fresh] = f.limits.emplace(update, std::pair{*limit, *limit});
      it->second = {std::min(it->second.first, *limit), std::max(it->second.second, *limit)};
    }
    if (const auto e = s.eq108(); e && limit) {
      f.eq_lo = std::min(f.eq_lo, *e / *limit);
      f.eq_hi = std::max(f.eq_hi, *e / *limit);
      const int particles = int(*RunRow(s.row()).particles);
      f.particles_lo = f.particles_lo ? std::min(f.particles_lo, particles) : particles;
      f.particles_hi = std::max(f.particles_hi, particles);
    }
    if (const auto e = f.edges.find(s.name); e != f.edges.end() && limit) {
      f.edge_lo = std::min(f.edge_lo, e->second / *limit);
      f.edge_hi = std::max(f.edge_hi, e->second / *limit);
    }
  }
  f.paper = paper_findings(spec.reference, f);
  return f;
}

// ---------------------------------------------------------------------------------------------
// Claims

// The schemes' limits confirmed by their runs.
Claim confirmed_claim(const Findings& f) {
  return claim("spectral-limit-confirmed",
               "Every scheme's spectral limit is confirmed by runs: the run just below it "
               "stays bounded and the run just above it grows",
               "{confirmed} of {schemes} schemes, runs at {below} and {above} times the limit")
      .every("confirmed", f.confirmed, "schemes", static_cast<long long>(f.schemes.size()))
      .value("below", f.below)
      .value("above", f.above)
      .on(f.schemes_at);
}

// The claim that the runs' state does not move eq. (108) at the tiny amplitude.
Claim eq108_rest_claim(const Eq108Findings& f) {
  const Eq108Grid& g = f.grid;
  const auto n = static_cast<long long>(g.points.size());
  Claim e = claim("eq108-at-rest",
                  "At the tiny amplitude the state of the runs does not move eq. (108): its "
                  "minimum is its value at rest, so what changes it with E, the particles per "
                  "cell and the grid is the formula's constants",
                  "{n} runs at A = {A}: the largest relative gap to eq. (108) at rest is {gap}, "
                  "{basis} at E = {E}, ppc {ppc} (negligible: below {tolerance})");
  e.count("n", n)
      .value("A", g.points.empty() ? "–" : shortest(g.points.front().A))
      .value("gap", n ? sci(f.shift, 2) : "–")
      .value("basis", f.shifted ? f.shifted->method : "–")
      .value("E", f.shifted ? shortest(f.shifted->E) : "–")
      .value("ppc", f.shifted ? std::to_string(f.shifted->ppc) : "–")
      .value("tolerance", shortest(kStateNegligible));
  e.holds = n > 0 && f.shift < kStateNegligible;
  return e.on(f.points_at);
}

std::vector<Claim> eq108_claims(const Eq108Findings& f) {
  const Eq108Grid& g = f.grid;
  const Eq108Point* worst = f.worst;
  std::vector<Claim> claims;
  Claim a = claim("eq108-below-limit-every-E",
                  "Eq. (108) lies below the spectral limit at every E ({Es}) and particles per "
                  "cell ({ppcs}) run, at A = {A}",
                  "{below} of {n} runs; the largest ratio is {worst}, {basis} at E = {E}, ppc "
                  "{ppc}");
  std::vector<double> ppcs(g.ppcs.begin(), g.ppcs.end());
  a.value("Es", listing(g.Es)).value("ppcs", span(ppcs)).on(f.points_at);
  a.value("A", listing(f.points_at.A));
  a.every("below", f.below, "n", static_cast<long long>(g.points.size()))
      .value("worst", worst ? fixed(worst->ratio(), 3) : "–")
      .value("basis", worst ? worst->method : "–")
      .value("E", worst ? shortest(worst->E) : "–")
      .value("ppc", worst ? std::to_string(worst->ppc) : "–");
  claims.push_back(a);
  Claim b = claim("eq108-not-homogeneous",
                  "Eq. (108)'s ratio to the spectral limit changes with E at the same c dt/h, "
                  "A/h and c T: it is not dimensionally homogeneous",
                  "at one basis and layout the ratio changes with E by up to a factor {spread}: "
                  "{basis} at ppc {ppc}, {lo} at E = {E_lo} and {hi} at E = {E_hi} "
                  "(homogeneous: below {threshold})");
  const Eq108Point *s_lo = f.spread_lo, *s_hi = f.spread_hi;
  b.value("spread", fixed(f.spread, 2))
      .value("basis", s_lo ? s_lo->method : "–")
      .value("ppc", s_lo ? std::to_string(s_lo->ppc) : "–")
      .value("lo", s_lo ? fixed(s_lo->ratio(), 3) : "–")
      .value("E_lo", s_lo ? shortest(s_lo->E) : "–")
      .value("hi", s_lo ? fixed(s_hi->ratio(), 3) : "–")
      .value("E_hi", s_lo ? shortest(s_hi->E) : "–")
      .value("threshold", shortest(kHomogeneousSpread));
  b.holds = f.spread > kHomogeneousSpread;
  claims.push_back(b.on(f.grid_at));

  Claim c = claim("eq108-falls-as-sqrt-ppc",
                  "At a fixed grid, eq. (108)'s ratio to the limit falls as the inverse square "
                  "root of the particles per cell",
                  "GIMP at E = {E}, {points} values of particles per cell: fitted exponent "
                  "{slope} (expected {expected} within {tolerance})");
  c.value("E", shortest(g.E0))
      .count("points", static_cast<long long>(f.by_ppc.size()))
      .value("slope", opt_fixed(f.ppc_slope))
      .value("expected", shortest(kSqrtSlope))
      .value("tolerance", shortest(kSlopeTolerance));
  c.holds = f.ppc_slope && std::abs(*f.ppc_slope - kSqrtSlope) <= kSlopeTolerance;
  claims.push_back(c.on(f.ppc_at));

  Claim d = claim("eq108-independent-of-grid",
                  "At a fixed number of particles per cell, refining the grid leaves eq. (108)'s "
                  "ratio to the limit unchanged",
                  "GIMP at E = {E}, {points} grids: fitted exponent against the particle count "
                  "{slope} (unchanged: within {tolerance} of zero)");
  d.value("E", shortest(g.E0))
      .count("points", static_cast<long long>(f.gimp_count.size()))
      .value("slope", opt_fixed(f.count_slope))
      .value("tolerance", shortest(kSlopeTolerance));
  d.holds = f.count_slope && std::abs(*f.count_slope) <= kSlopeTolerance;
  claims.push_back(d.on(f.count_at));

  claims.push_back(eq108_rest_claim(f));
  return claims;
}

// ---------------------------------------------------------------------------------------------
// Rendering of the eq. (108) section

std::string eq108_intro(const Eq108Findings& f) {
  const Eq108Grid& g = f.grid;
  std::ostringstream md;
  md << "## Eq. (108) against the limit, per E and per particle count\n\n";
  if (!g.points.empty()) {
    const Eq108Point& p0 = g.points.front();
    md << "Eq. (108) is not dimensionally homogeneous: it adds sqrt(E), a speed in these units, to "
          "F_max, a pure number, divides the stress by sqrt(E), and adds the l2 norm of the "
          "nodal velocities, a sum over the nodes. So its step in units of h/c is not fixed by "
          "what fixes the scheme's behaviour (c dt / h, A/h and c T): it changes with E, as the "
          "first table shows, and with the particles per cell. Each run is the bar at A = "
       << shortest(p0.A) << " with USL, FLIP and the uniform layout, under the spectral policy at "
       << shortest(p0.safety) << " times the limit, ";
    if (g.cT_hi <= g.cT_lo * (1 + 1e-9))
      md << "for T = " << shortest(g.cT_lo) << " / sqrt(E) (c T / L = " << shortest(g.cT_lo)
         << " crossings of the bar and the same steps at every E)";
    else
      md << "for c T / L = " << shortest(g.cT_lo) << " to " << shortest(g.cT_hi)
         << " crossings of the bar";
    md << ", on " << g.cells0 << " cells";
    if (f.cells_hi > f.cells_lo)
      md << " (the last table: " << f.cells_lo << " to " << f.cells_hi << " cells)";
    md << ". Eq. (108) is the minimum of the bound over the run, in units of h/c; the spectral "
          "limit, in c dt / h, is the same at every E.\n\n";
  }
  return md.str();
}

// The per-E table at the first row's particles per cell.
std::string eq108_per_E(const Eq108Findings& f) {
  std::ostringstream md;
  md << "**Per E**, at " << f.grid.ppc0
     << " particles per cell (the last column: the ratio over every particles per cell run at "
        "that E)\n\n| E | c | basis | spectral limit (c dt / h) | eq. (108) minimum (h / c) | "
        "eq. (108) / limit | eq. (108) / limit over the particles per cell |\n"
        "|---|---|---|---|---|---|---|\n";
  for (const Eq108Row& r : f.rows) {
    const Eq108Point* p = r.p;
    md << "| " << shortest(p->E) << " | " << significant(p->c(), 3) << " | " << p->method << " | "
       << fixed(p->limit, 4) << " | " << fixed(p->eq108, 4) << " | " << fixed(p->ratio(), 3)
       << " | "
       << (r.n > 1 ? fixed(r.lo, 3) + " to " + fixed(r.hi, 3) + " (ppc " +
                         std::to_string(r.ppc_lo) + " to " + std::to_string(r.ppc_hi) + ")"
                   : std::string("–"))
       << " |\n";
  }
  return md.str();
}

std::string eq108_per_E_reading(const Eq108Findings& f) {
  const Eq108Point *lo = f.spread_lo, *hi = f.spread_hi;
  std::ostringstream md;
  if (!f.per_E.empty()) {
    md << "\nThe ratio per E, over the bases and particles per cell:";
    std::string sep = " ";
    for (const auto& [E, r] : f.per_E) {
      md << sep << "E = " << shortest(E) << ", " << fixed(r.first, 3) << " to "
         << fixed(r.second, 3);
      sep = "; ";
    }
    md << ".";
    if (lo)
      md << " At one basis and layout it changes with E by up to a factor " << fixed(f.spread, 2)
         << " (" << lo->method << " at " << lo->ppc
         << " particles per cell: " << fixed(lo->ratio(), 3) << " at E = " << shortest(lo->E)
         << ", " << fixed(hi->ratio(), 3) << " at E = " << shortest(hi->E)
         << "); a bound homogeneous in E would give one ratio at every E.";
    md << "\n\n";
  }
  return md.str();
}
// By particles per cell at every E, for the bases run at more than one.
std::string eq108_per_ppc(const Eq108Findings& f) {
  const Eq108Grid& g = f.grid;
  std::ostringstream md;
  if (g.ppcs.size() > 1) {
    md << "**Per particles per cell** on " << g.cells0
       << " cells: the spectral limit, then eq. (108) / limit at each E\n\n| basis | E |";
    for (int ppc : g.ppcs)
      md << " ppc " << ppc << " |";
    md << "\n|---|---|" << rule_cells(g.ppcs.size()) << "\n";
    for (const auto& b : g.bases) {
      if (g.ppcs_of(b).size() < 2) continue;
      md << "| " << b << " | spectral limit |";
      for (int ppc : g.ppcs) {
        const Eq108Point* p = nullptr;
        for (double E : g.Es)
          if (!p) p = g.find(b, E, ppc);
        md << " " << (p ? fixed(p->limit, 3) : std::string("–")) << " |";
      }
      md << "\n";
      for (double E : g.Es) {
        md << "| " << b << " | " << shortest(E) << " |";
        for (int ppc : g.ppcs) {
          const Eq108Point* p = g.find(b, E, ppc);
          md << " " << (p ? fixed(p->ratio(), 3) : std::string("–")) << " |";
        }
        md << "\n";
      }
    }
    md << "\nAt a fixed grid the ratio falls with the particles per cell";
    if (f.ppc_slope)
      md << ": fitted exponent " << fixed(*f.ppc_slope, 3) << " (GIMP at E = " << shortest(g.E0)
         << ")";
    md << ".\n\n";
  }
  return md.str();
}

// Against the particle count: the first E and particles per cell on every grid.
std::string eq108_per_count(const Eq108Findings& f) {
  const Eq108Grid& g = f.grid;
  std::ostringstream md;
  std::ostringstream count_table;
  for (const auto& b : g.bases) {
    for (const Eq108Point* p : g.by_count(b)) {
      count_table << "| " << p->method << " | " << p->cells << " | " << p->particles << " | "
                  << fixed(p->ratio(), 3) << " | "
                  << fixed(p->ratio() * std::sqrt(double(p->particles)), 3) << " |\n";
    }
  }
  if (!count_table.str().empty()) {
    md << "**Against the particle count**, at E = " << shortest(g.E0) << " and " << g.ppc0
       << " particles per cell on every grid\n\n| basis | cells | particles | eq. (108) / "
          "limit | eq. (108) / limit x sqrt(particles) |\n|---|---|---|---|---|\n"
       << count_table.str() << "\n";
    if (f.gimp_count.size() >= 2) {
      const Eq108Point *a = f.gimp_count.front(), *z = f.gimp_count.back();
      md << "Refining the grid from " << a->particles << " to " << z->particles
         << " particles moves GIMP's ratio from " << fixed(a->ratio(), 3) << " to "
         << fixed(z->ratio(), 3);
      if (f.count_slope)
        md << " (fitted exponent against the particle count " << fixed(*f.count_slope, 3) << ")";
      md << ", and the ratio times sqrt(particles) from "
         << fixed(a->ratio() * std::sqrt(double(a->particles)), 3) << " to "
         << fixed(z->ratio() * std::sqrt(double(z->particles)), 3) << ". ";
      if (f.count_slope && std::abs(*f.count_slope) <= kSlopeTolerance)
        md << "So eq. (108) does not shrink as 1/sqrt(particles) when the grid is refined at a "
              "fixed number of particles per cell; at a fixed grid, where the particles per cell "
              "set the count, it falls with them as the previous table shows.";
      else if (f.count_slope)
        md << "So eq. (108)'s ratio changes with the particle count on a refined grid as its power "
           << fixed(*f.count_slope, 3) << ".";
      md << "\n\n";
    }
  }
  return md.str();
}

// The state against the bound at rest.
std::string eq108_state(const Eq108Findings& f) {
  const Eq108Grid& g = f.grid;
  std::ostringstream md;
  if (!g.points.empty()) {
    md << "The l2 norm of the nodal velocities grows as the square root of the node count for "
          "nodal velocities of a given size, and the bound falls as it grows. ";
    if (f.shift < kStateNegligible)
      md << "At A = " << shortest(g.points.front().A) << " that term does not show: over the "
         << g.points.size() << " runs, eq. (108)'s minimum lies within " << sci(f.shift, 2)
         << " (relative) of its value at rest (F = 1, no stress, no velocity, at the run's E, "
            "grid and particles per cell), so what the tables show is the formula's constants "
            "(sqrt(E) beside F_max = 1, and the particles per cell m in h sqrt(m) / (4 m "
            "(sqrt(E) + F_max + ||v||) + ...)), not the state of the runs.\n\n";
    else
      md << "Over the " << g.points.size() << " runs the state moves eq. (108)'s minimum by up to "
         << sci(f.shift, 2)
         << " (relative) from its value at rest (F = 1, no stress, no velocity).\n\n";
  }
  return md.str();
}

// ---------------------------------------------------------------------------------------------
// Text

std::string reading(const Findings& f, const ojson& first) {
  std::ostringstream md;
  md << "**Reading** (computed from the rows). The limit is confirmed (the run at " << f.below
     << " times it stays bounded, the run at " << f.above << " times it grows) for " << f.confirmed
     << " of " << f.schemes.size() << " schemes (" << f.schemes_at.text() << ")";
  if (f.not_confirmed.empty()) {
    md << ". ";
  } else {
    md << "; not for ";
    for (std::size_t i = 0; i < f.not_confirmed.size(); ++i)
      md << (i ? ", " : "") << "`" << f.not_confirmed[i] << "`";
    md << " (their rows show which run disagrees). ";
  }
  md << "Limits at " << kDefaultPpc
     << " particles per cell and the uniform layout, in c dt / h, by update order:";
  std::string sep = " ";
  for (const char* u : {"usl", "usf", "musl"}) {
    const auto it = f.limits.find(u);
    if (it == f.limits.end()) continue;
    md << sep << u << " " << fixed(it->second.first, 3) << " to " << fixed(it->second.second, 3);
    sep = "; ";
  }
  md << " (the CFL number is 1).";
  if (f.edge_hi > 0)
    md << " The measured edges lie at " << fixed(f.edge_lo, 4) << " to " << fixed(f.edge_hi, 4)
       << " times the limit (" << f.edges_at.text() << ").";
  if (f.eq_hi > 0) {
    const Eq108Findings& eq108 = f.eq108;
    const std::vector<double>& Es = eq108.grid.Es;  // in increasing order
    md << " Eq. (108) at the same state lies at " << fixed(f.eq_lo, 3) << " to "
       << fixed(f.eq_hi, 3) << " times the limit, at E = " << shortest(first["E"].get<double>())
       << " on " << first["cells"].get<int>() << " cells ("
       << (f.particles_lo == f.particles_hi
               ? std::to_string(f.particles_lo)
               : std::to_string(f.particles_lo) + " to " + std::to_string(f.particles_hi))
       << " particles) only: its ratio changes with E";
    if (eq108.hi > 0 && Es.back() > Es.front())
      md << " (at " << first["ppc"].get<int>() << " particles per cell with USL and FLIP, "
         << fixed(eq108.lo, 3) << " to " << fixed(eq108.hi, 3)
         << " over E = " << shortest(Es.front()) << " to " << shortest(Es.back()) << ")";
    md << " and with the particles per cell (the section on eq. (108) below).";
  }
  md << "\n\n";
  return md.str();
}

// The paper's dt stable column of Table 1 in c dt / h, per method, A and E, beside the spectral
// limit and our eq. (108) ("" without Table 1).
std::string paper_table(const Findings& f) {
  if (!f.paper) return "";
  const PaperFindings& p = *f.paper;
  auto of = [&](const std::string& method, bool limit) -> std::string {
    const Scheme* s = f.scheme(method);
    return opt_fixed(!s ? std::nullopt : limit ? s->limit() : s->eq108());
  };
  std::ostringstream md;
  md << "## The paper's dt stable column\n\nTable 1's \"dt stable\" (eq. (108) of the paper's "
        "runs, at its amplitudes and E, on "
     << kPaperCells
     << " cells), converted to c dt / h: the median over the dts of each cell's block. The "
        "paper's bound changes with the state (A and E); the spectral limit, a property of the "
        "scheme in c dt / h, does not. Our eq. (108) at the tiny amplitude is given at one E "
        "(named in its column); it changes with E too (per E in the table above).\n\n"
        "| method | A | ";
  for (double E : p.Es)
    md << "E = " << shortest(E) << " | ";
  md << "spectral limit | our eq. (108) at A = "
     << (f.schemes.empty() ? std::string("–")
                           : value_text(f.schemes.front().row()["A"].get<double>()))
     << ", E = "
     << (f.schemes.empty() ? std::string("–")
                           : value_text(f.schemes.front().row()["E"].get<double>()))
     << " |\n|---|---|" << rule_cells(p.Es.size() + 2) << "\n";
  for (const auto& [method, A] : p.keys) {
    md << "| " << method << " | " << shortest(A) << " | ";
    for (double E : p.Es) {
      const auto it = p.medians.find({method, Key(A), Key(E)});
      md << (it == p.medians.end() ? std::string("–") : fixed(it->second, 3)) << " | ";
    }
    md << of(method, true) << " | " << of(method, false) << " |\n";
  }
  md << "\n**Reading** (computed from the rows). " << p.above << " of " << p.cells
     << " of the paper's medians lie above the spectral limit of their method (a step the "
        "linearised scheme amplifies at a tiny amplitude).\n\n";
  return md.str();
}

std::string spectral_markdown(const std::vector<ojson>& rows, const Findings& f) {
  const ojson& first = rows.front();
  std::ostringstream md;
  md << "![The spectral limit and eq. (108) / limit against the particles per cell](spectral.png)"
        "\n\n"
     << "Each scheme's spectral limit: the largest c dt / h at which its one-step map, "
        "linearised about rest with the particles frozen at the bar's initial layout, amplifies "
        "nothing (docs/theory.md, \"The spectral limit\"): the Bloch limit of the interior for a "
        "uniform layout, the dense map of the whole bar for a jittered one. Beside it, two runs "
        "of the bar under the spectral policy at s = "
     << f.below << " and s = " << f.above
     << " times the limit, at A = " << shortest(first["A"].get<double>())
     << ", E = " << shortest(first["E"].get<double>())
     << " and T = " << shortest(first["T"].get<double>())
     << " (c T / L = " << shortest(std::sqrt(first["E"].get<double>()) * first["T"].get<double>())
     << " crossings of the bar), " << first["cells"].get<int>()
     << " cells. A run is *bounded* when it reaches T with an error over time of at most "
     << shortest(kBound)
     << " A (a bounded run's error, its phase error included, is at most twice A; one that "
        "reaches A is also marked meaningless); a run that grows passes "
     << shortest(kBound)
     << " A or fails. Eq. (108) is defined for MPM, GIMP and cpGIMP only (`–` for the other "
        "bases). The measured edge is the spectral_edge experiment's "
        "([spectral_edge.md](spectral_edge.md)): the largest fixed dt that stays bounded, "
        "found by its search without reading the limit. Eq. (108) is the minimum of our bound "
        "over the run at "
     << f.below << " times the limit. The CFL number is 1 in these units.\n\n"
     << reading(f, first)
     << "| scheme | spectral limit (c dt / h) | analysis | measured edge | eq. (108) at the same "
        "state | run at "
     << f.below << " x | run at " << f.above
     << " x | confirmed |\n|---|---|---|---|---|---|---|---|\n";
  for (const auto& s : f.schemes) {
    const auto limit = s.limit();
    const auto edge = f.edges.find(s.name);
    const auto eq = s.eq108();
    md << "| " << s.name << " | "
       << (limit ? fixed(*limit, 4) : "none up to " + shortest(kMaxSpectralCourant)) << " | "
       << (s.row()["spectral_analysis"].is_string()
               ? s.row()["spectral_analysis"].get<std::string>()
               : std::string("–"))
       << " | " << (edge != f.edges.end() ? fixed(edge->second, 4) : std::string("–")) << " | "
       << opt_fixed(eq, 4) << " | " << (s.below ? run_text(*s.below) : "–") << " | "
       << (s.above ? run_text(*s.above) : "–") << " | " << (s.confirmed() ? "yes" : "**no**")
       << " |\n";
  }
  // The eq. (108) section, its tables and readings; then the paper's column.
  const Eq108Findings& e = f.eq108;
  md << "\n"
     << eq108_intro(e) << eq108_per_E(e) << eq108_per_E_reading(e) << eq108_per_ppc(e)
     << eq108_per_count(e) << eq108_state(e) << paper_table(f);
  return md.str();
}

// ---------------------------------------------------------------------------------------------
// Figure

// The figure: MPM and GIMP (USL, FLIP, uniform layout) on the first row's grid against the
// particles per cell: the limit and the measured edge (first E), eq. (108) and its ratio to the
// limit at every E.
std::string spectral_data(const ReportContext& c, const Findings& f) {
  const ojson& first = c.rows.front();
  std::ostringstream csv;
  csv << c.csv_header << "# method: " << codes(kFigureMethods) << " (USL, FLIP, uniform layout, "
      << first["cells"].get<int>()
      << " cells); in c dt / h: limit the spectral limit, edge the measured edge (empty: not "
         "measured), eq108 our eq. (108), the minimum over the run at "
      << safeties(c.rows, true, false)
      << " times the limit; ratio eq108 / limit\n"
         "method,E,ppc,limit,edge,eq108,ratio\n";
  // Sorted by method, E and ppc: each curve one contiguous block.
  auto points = f.eq108.grid.points;
  std::stable_sort(points.begin(), points.end(), [](const Eq108Point& a, const Eq108Point& b) {
    return std::tuple(a.method != "mpm", Key(a.E, "E"), a.ppc) <
           std::tuple(b.method != "mpm", Key(b.E, "E"), b.ppc);
  });
  for (const auto& p : points) {
    const auto code = std::find(kFigureMethods.begin(), kFigureMethods.end(), p.method);
    if (p.cells != first["cells"].get<int>() || code == kFigureMethods.end()) continue;
    std::string name = p.method;
    if (p.ppc != kDefaultPpc) name += " (ppc " + std::to_string(p.ppc) + ")";
    const auto edge = p.E == first["E"].get<double>() ? f.edges.find(name) : f.edges.end();
    csv << code - kFigureMethods.begin() << ',' << shortest(p.E) << ',' << p.ppc << ','
        << shortest(p.limit) << ',' << (edge != f.edges.end() ? shortest(edge->second) : "") << ','
        << shortest(p.eq108) << ',' << shortest(p.ratio()) << '\n';
  }
  return csv.str();
}

// What the figure draws, from the records.
std::string spectral_subtitle(const Spec& spec, const ojson& doc) {
  const std::vector<ojson> rows(doc["cases"].begin(), doc["cases"].end());
  if (rows.empty()) return "";
  const Findings f = find(spec, rows, {});
  const auto& points = f.eq108.grid.points;
  std::ostringstream s;
  s << "USL, FLIP, uniform layout, " << rows.front()["cells"].get<int>() << " cells";
  if (!points.empty()) {
    const Eq108Point& p = points.front();
    s << "; eq. (108): its minimum over a run at " << shortest(p.safety)
      << " x the limit, A = " << shortest(p.A) << ", T = " << shortest(p.c() * p.T) << " / sqrt(E)";
  }
  return s.str();
}

std::string spectral_index(const Spec& spec, const std::vector<ojson>& rows, const ojson&) {
  const Findings f = find(spec, rows, {});
  std::ostringstream md;
  md << "![" << spec.title << "](" << spec.name
     << ".png)\n\n**What it shows.** The spectral limit of " << f.schemes.size()
     << " schemes (basis x transfer x update order, particles per cell and layout), each checked "
        "by two runs at a tiny amplitude just below and just above it: confirmed for "
     << f.confirmed << " of " << f.schemes.size() << " (" << f.schemes_at.text() << ")"
     << "; and eq. (108) against the limit at every E the studies use: [" << spec.name << ".md]("
     << spec.name << ".md).\n\n";
  return md.str();
}

const StudyRegistration kSpectral{{
    .name = "spectral",
    .summary = "each scheme's spectral limit, checked by runs just below and above it, beside "
               "the measured edge, eq. (108) and the paper's dt stable; eq. (108) against the "
               "limit per E and per particle count",
    .records = {.error_over_time = true, .dt_stable = true},
    .inputs = {{.name = "spectral_edge"}},
    .figure = true,
    .report =
        [](const ReportContext& c) {
          const Findings f = find(c.spec, c.rows, c.inputs);
          std::vector<Claim> claims = eq108_claims(f.eq108);
          claims.insert(claims.begin(), confirmed_claim(f));
          return StudyReport{.markdown = spectral_markdown(c.rows, f),
                             .data_csv = spectral_data(c, f),
                             .claims = std::move(claims)};
        },
    .index = spectral_index,
    .figure_subtitle = spectral_subtitle,
}};

}  // namespace
}  // namespace mpmstab::studies::spectral
