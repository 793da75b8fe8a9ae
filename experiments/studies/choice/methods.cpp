// Choosing a method: one row per method (basis x velocity transfer x update order) with the
// error at Table 1's setting, the orders in h and dt with the runs each is fitted over, the cells
// per wavelength a wave needs to stay within a tolerance of the exact one after a number of
// periods (phase and damping together, from the Bloch symbol), the survival and accuracy edges
// at a tiny amplitude and the counted work per particle-step. It recommends nothing: the
// project's recommendations are advice.md's (advice.hpp). The edges are this study's own cases
// (edge searches); the errors and orders come from the rows of methods_grid, which it reads; the
// wave column from each scheme's Bloch symbol (core/analysis/dispersion.hpp), set against a
// single-mode run of each scheme at the column's value (its follow-up runs).
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "analysis/bloch.hpp"
#include "analysis/dispersion.hpp"
#include "analysis/spectral.hpp"
#include "base/accuracy.hpp"
#include "claims.hpp"
#include "csv.hpp"
#include "report_util.hpp"
#include "run_row.hpp"
#include "step/simulation.hpp"
#include "study.hpp"

namespace mpmstab::studies::methods {
namespace {

using ojson = nlohmann::ordered_json;

// ---------------------------------------------------------------------------------------------
// Findings: each method's row (its runs and fitted orders), its wave column, the wave column
// against runs, and the reading's facts

// What identifies a method in a row: basis, wall treatment, transfer and its order, update.
using MethodKey = std::tuple<std::string, std::string, std::string, int, std::string>;
MethodKey key_of(const ojson& r) {
  const std::string transfer = r["transfer"].get<std::string>();
  const std::string order = transfer + "_order";  // xpic_order, fmpm_order
  return {RunRow(r).method, r["walls"].get<std::string>(), transfer,
          int(number_or_zero(r, order.c_str())), r["update"].get<std::string>()};
}

std::string basis_text(const MethodKey& k) {
  const auto& [method, walls, transfer, order, update] = k;
  if (walls == "modified") return method + " (modified)";
  return method;
}

std::string transfer_text(const MethodKey& k) {
  const auto& [method, walls, transfer, order, update] = k;
  return order > 0 ? transfer + "(" + std::to_string(order) + ")" : transfer;
}

// Passes over the particle's stencil per step, counted from Simulation::step: p2g, g2p and the
// stress update (3); USF adds p2g_force, MUSL p2g_momentum; APIC adds p2g_affine (twice with
// MUSL) and the interpolation of C_p in g2p; XPIC(m) adds 2 (m - 1) for its series and one for
// the correction in g2p; FMPM(k) adds 2 (k - 1) per series, run once (USL) or twice (USF, MUSL).
int stencil_passes(const MethodKey& k) {
  const auto& [method, walls, transfer, order, update] = k;
  int passes = 3;
  if (update != "usl") passes += 1;
  if (transfer == "apic") passes += update == "musl" ? 3 : 2;
  if (transfer == "xpic") passes += 2 * (order - 1) + 1;
  if (transfer == "fmpm") passes += 2 * (order - 1) * (update == "usl" ? 1 : 2);
  return passes;
}

// 0 for a basis this program does not know (a results file written by hand).
int node_visits(const MethodKey& k) {
  const auto method = parse_method(std::get<0>(k));
  return method ? stencil_width(*method) * stencil_passes(k) : 0;
}

// A fitted order and its support: the runs in the regime it describes (the points fitted) of
// the runs of its kind.
struct Order {
  std::optional<double> value;
  int fitted = 0, runs = 0;
};

struct MethodRow {
  MethodKey key;
  const ojson* edge = nullptr;    // this study's edge search
  const ojson* table1 = nullptr;  // methods_grid: 100 cells, dt = 1e-4
  std::vector<const ojson*> grid;
  Order order_h, order_dt;
  // The error over time at Table 1's setting, where its run ended stable.
  std::optional<double> error() const {
    return table1 ? stable_error_over_time(*table1) : std::nullopt;
  }
};

// Table 1's setting among the rows of methods_grid: the paper's grid at its smallest fixed dt.
constexpr int kTable1Cells = 100;
constexpr double kTable1Dt = 1e-4;
// The order in h is fitted over methods_grid's CFL runs at this Courant number (the smallest the
// grid sweeps: the time error least visible) and this amplitude, small enough that A / h stays
// far below a quarter of a cell on the finest of their grids, so that no particle crosses a cell
// (at Table 1's A = 0.015, A / h is at least 0.375 on the sweep's grids, where report_util.hpp's
// regime keeps no run). The order in dt is fitted over the runs at Table 1's amplitude on its grid.
constexpr double kOrderHCourant = 0.2;
constexpr double kOrderHAmplitude = 2.5e-4;

bool is_table1_setting(const ojson& r) {
  return r["policy"].get<std::string>() == "fixed" && r["cells"].get<int>() == kTable1Cells &&
         has_number(r, "dt") && r["dt"].get<double>() == kTable1Dt;
}

bool is_order_h_run(const ojson& r) {
  return r["policy"].get<std::string>() == "cfl" &&
         r["cfl_factor"].get<double>() == kOrderHCourant &&
         r["A"].get<double>() == kOrderHAmplitude;
}

double dt_of(const ojson& r) {
  return has_number(r, "dt") ? r["dt"].get<double>()
                             : r["cfl_factor"].get<double>() * r["dt_cfl"].get<double>();
}

std::vector<MethodRow> method_rows(const std::vector<ojson>& edges,
                                   const std::vector<ojson>& grid) {
  std::vector<MethodRow> rows;
  std::map<MethodKey, std::size_t> index;
  for (const auto& r : edges) {
    index[key_of(r)] = rows.size();
    rows.push_back(MethodRow{.key = key_of(r), .edge = &r});
  }
  for (const auto& r : grid) {
    const auto it = index.find(key_of(r));
    if (it == index.end()) continue;
    MethodRow& m = rows[it->second];
    m.grid.push_back(&r);
    if (is_table1_setting(r)) m.table1 = &r;
  }
  for (MethodRow& m : rows) {
    std::vector<std::pair<double, double>> h_points, dt_points;
    for (const ojson* r : m.grid) {
      const auto e = stable_error_over_time(*r);
      // Orders only in their regime (report_util.hpp): accurate runs, and for h no crossing.
      if (is_order_h_run(*r)) {
        ++m.order_h.runs;
        if (e && accurate_run(*r) && crossing_free(*r))
          h_points.emplace_back(1.0 / (*r)["cells"].get<double>(), *e);
      }
      // The order in dt: Table 1's grid and amplitude, and that of the convergent scheme: not
      // from a run above its limit.
      if (!m.table1 || (*r)["cells"].get<int>() != kTable1Cells ||
          (*r)["A"].get<double>() != (*m.table1)["A"].get<double>())
        continue;
      ++m.order_dt.runs;
      // The error over time (max over steps and particles) of a stable run is what the orders
      // are fitted to and the methods are ranked by; the error at T is shown, never fitted
      // (docs/theory.md, "Orders of convergence").
      const bool below_limit = !above_spectral_limit(*r);
      if (e && below_limit && accurate_run(*r)) dt_points.emplace_back(dt_of(*r), *e);
    }
    m.order_h.value = loglog_slope(h_points);
    m.order_h.fitted = int(h_points.size());
    m.order_dt.value = loglog_slope(dt_points);
    m.order_dt.fitted = int(dt_points.size());
  }
  return rows;
}

std::string method_name(const MethodRow& m) {
  return basis_text(m.key) + " / " + transfer_text(m.key) + " / " + std::get<4>(m.key);
}

// The wave column: how many cells per wavelength a wave needs to come out within kWaveTolerance
// of the exact one after kWavePeriods of its periods, at c dt / h = kWaveCourant. A wave of the
// uniform layout's interior is carried by the scheme's physical branch lambda (its Bloch symbol,
// core/analysis/dispersion.hpp); its error per unit amplitude after n steps is
// |lambda^n - e^{i omega n dt}| (amplitude_error), the damping and the phase error together.
constexpr double kWaveCourant = 0.5;
constexpr double kWavePeriods = 10;
constexpr double kWaveTolerance = 0.01;
// The column set against runs: a single-mode run (the mode scene, one free standing wave of the
// periodic bar, its wavelength the bar's length) on as many cells as the column gives, rounded
// up, at kWaveCourant to kWavePeriods periods, at the dispersion study's E and A (linear: E only
// rescales time). A run costs ppc n x (periods n / C) particle-steps on n cells: a scheme whose
// column exceeds kMaxWaveRunCells (PIC's thousands of cells) is not run, and the report says so.
constexpr double kWaveRunE = 1;
constexpr double kWaveRunAmplitude = 1e-6;
constexpr int kMaxWaveRunCells = 1024;
constexpr const char* kWaveRun = "single-mode run at the wave column's cells";

// What identifies a scheme's interior: the method key without the walls (they do not enter the
// symbol, and the periodic mode scene has none), with the particles per cell.
using Interior = std::pair<MethodKey, int>;
Interior interior_of(MethodKey k, const ojson& row) {
  std::get<1>(k) = "";
  return {k, has_number(row, "ppc") ? row["ppc"].get<int>() : 0};
}

// The scheme of a row's method at `ppc` particles per cell (nullopt for a name this program does
// not know); the walls do not enter the interior's symbol.
std::optional<RunParams> scheme_params(const Interior& id) {
  const auto& [method, walls, transfer, order, update] = id.first;
  const auto b = parse_method(method);
  const auto t = parse_transfer(transfer);
  const auto u = parse_update_order(update);
  if (!b || !t || !u) return std::nullopt;
  RunParams p{.method = *b, .ppc = id.second, .transfer = *t, .update = *u};
  if (*t == Transfer::xpic && order > 0) p.xpic_order = order;
  if (*t == Transfer::fmpm && order > 0) p.fmpm_order = order;
  return p;
}

// A scheme's wave column and, where it was run, its single-mode run on that many cells (where
// the symbol's error is within the tolerance, by the column's definition).
struct WaveCells {
  bool computed = false;        // false where the symbol does not apply (or the name is unknown)
  bool above_limit = false;     // kWaveCourant at or above the scheme's Bloch limit
  std::optional<double> cells;  // nullopt: more than kMaxCellsPerWavelength (or not computed)
  std::string transfer;         // the scheme's transfer ("fmpm(2)")
  const ojson* run = nullptr;   // the single-mode run, where there is one
  // The cells a run at the column's value takes (0 where the column has none).
  int run_cells() const { return cells ? int(std::ceil(*cells)) : 0; }
  bool within() const {
    return run && RunRow(*run).stable_over_a_wave_pass() &&
           RunRow(*run).error_over_A() <= kWaveTolerance;
  }
};

WaveCells wave_cells(const std::optional<RunParams>& p) {
  WaveCells w;
  if (!p) return w;
  try {
    const RunParams q = dispersion_scheme(*p);
    const auto limit = bloch_courant(q);
    w.computed = true;
    w.above_limit = limit && *limit <= kWaveCourant;
    if (!w.above_limit)
      w.cells = cells_per_wavelength_amplitude(q, kWaveCourant, kWavePeriods, kWaveTolerance);
  } catch (const std::invalid_argument&) {
    w.computed = false;
  }
  return w;
}

// The follow-up runs: one per scheme (the walls' treatments share it) whose column is at most
// kMaxWaveRunCells, on that many cells rounded up (one wavelength), at kWaveCourant.
std::vector<FollowUp> wave_runs(const FollowUpContext& c) {
  std::vector<FollowUp> runs;
  std::set<Interior> asked;
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    const Interior id = interior_of(key_of(c.rows[i]), c.rows[i]);
    const int cells = wave_cells(scheme_params(id)).run_cells();
    if (cells == 0 || cells > kMaxWaveRunCells || !asked.insert(id).second) continue;
    RunParams p = c.spec.cases.at(i).params;
    std::tie(p.scene, p.bc, p.walls) = std::tuple{SceneKind::mode, Boundary::periodic, Walls::clip};
    std::tie(p.E, p.A, p.cells) = std::tuple{kWaveRunE, kWaveRunAmplitude, cells};
    p.stepping.policy = TimeStepPolicy::fixed;
    p.T = kWavePeriods / std::sqrt(kWaveRunE);  // a period is 1 / c
    p.dt = kWaveCourant / (cells * std::sqrt(kWaveRunE));
    runs.push_back({.of = i, .role = kWaveRun, .params = p});
  }
  return runs;
}

// One per method row, the schemes that share an interior computed once, each with its
// single-mode run among `follow_up`.
std::vector<WaveCells> wave_column(const std::vector<MethodRow>& rows,
                                   const std::vector<ojson>& follow_up) {
  std::map<Interior, WaveCells> computed;
  for (const auto& r : follow_up)
    if (r.value(kFollowUpRole, "") == kWaveRun) computed[interior_of(key_of(r), r)].run = &r;
  std::vector<WaveCells> out;
  for (const auto& m : rows) {
    const Interior id = interior_of(m.key, *m.edge);
    if (WaveCells& w = computed[id]; !w.computed) {
      const ojson* run = w.run;
      w = wave_cells(scheme_params(id));
      std::tie(w.transfer, w.run) = std::tuple{transfer_text(m.key), run};
    }
    out.push_back(computed[id]);
  }
  return out;
}

// Three significant digits: "45.9", "176", "7370".
std::string cells_text(double cells) {
  const int magnitude = int(std::floor(std::log10(cells)));
  const double unit = std::pow(10.0, magnitude - 2);
  return fixed(std::round(cells / unit) * unit, std::max(0, 2 - magnitude));
}

// The rows of methods_grid (none where its results are not in the folder).
std::vector<ojson> grid_rows(const StudyInputs& inputs) {
  const auto in = inputs.find("methods_grid");
  if (in == inputs.end() || !in->second.present()) return {};
  return std::vector<ojson>(in->second.doc["cases"].begin(), in->second.doc["cases"].end());
}

// What the report, its claim, the index paragraph and the subtitle say, found once.
struct Findings {
  std::vector<MethodRow> methods;  // one per row, with its runs and fitted orders
  std::vector<WaveCells> waves;    // the wave column, one per method
  // The runs of methods_grid the error at Table 1's setting and each order are measured over.
  std::vector<ojson> table1_runs, h_runs, cfl_runs, fixed_runs;
  Coverage edges_on, dt_on;  // where the edges and the orders in dt are measured
  // At Table 1's setting: how the methods' runs ended (others: too short or not run).
  int stable = 0, meaningless = 0, unstable = 0, others = 0, accurate = 0, inaccurate = 0;
  int with_order_h = 0, with_order_dt = 0, edges = 0, meaningless_edges = 0;
  int beyond = 0;  // the methods whose wave needs more than kMaxCellsPerWavelength
  // A smallest or largest value, with the methods whose value prints as its does.
  struct Extreme {
    std::optional<double> value;
    std::string methods;
  } best_error, fewest_cells, most_cells, widest_edge;
  // The wave column against its single-mode runs (one per scheme): the runs, how many come out
  // within the tolerance, by transfer (within, runs); the schemes above the cap, not run, and
  // what their runs would cost; what the runs made cost, in particle-steps.
  std::vector<ojson> wave_rows;
  int within = 0, not_run = 0;
  std::map<std::string, std::pair<int, int>> by_transfer;
  double run_cost = 0, not_run_cost = 0;
};

// The smallest value over the methods (the largest with `largest`), where a method has one, with
// the methods whose value prints as its does (ties at the printed precision), by name.
template <class Value, class Text>
Findings::Extreme extreme(const std::vector<MethodRow>& rows, Value value, bool largest,
                          Text text) {
  Findings::Extreme x;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (const auto v = value(i); v && (!x.value || (largest ? *v > *x.value : *v < *x.value)))
      x.value = v;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < rows.size() && x.value; ++i)
    if (const auto v = value(i); v && text(*v) == text(*x.value))
      names.push_back(method_name(rows[i]));
  x.methods = list_of(names);
  return x;
}

// The findings from the rows (the edge searches), those of methods_grid and the follow-up runs
// (the report's; the index and the subtitle have only the rows).
Findings find(const std::vector<ojson>& rows, const std::vector<ojson>& grid,
              const std::vector<ojson>& follow_up) {
  Findings f{.methods = method_rows(rows, grid)};
  f.waves = wave_column(f.methods, follow_up);
  for (const auto& r : grid) {
    if (is_table1_setting(r)) f.table1_runs.push_back(r);
    if (is_order_h_run(r)) {
      f.h_runs.push_back(r);
      continue;
    }
    if (r["cells"].get<int>() != kTable1Cells) continue;
    (r["policy"].get<std::string>() == "cfl" ? f.cfl_runs : f.fixed_runs).push_back(r);
    f.dt_on.add(r);
  }
  f.edges_on = coverage_of(rows);
  // The reading's facts at Table 1's setting, of the wave column and of the edges.
  std::set<Interior> schemes;  // the wave column's runs, counted once per scheme
  for (std::size_t i = 0; i < f.methods.size(); ++i) {
    const MethodRow& m = f.methods[i];
    const WaveCells& w = f.waves[i];
    if (const double n = w.run_cells(); schemes.insert(interior_of(m.key, *m.edge)).second) {
      // A scheme not run: what its run would cost, ppc n x the steps to its periods.
      f.not_run += n > kMaxWaveRunCells;
      if (n > kMaxWaveRunCells)
        f.not_run_cost +=
            number_or_zero(*m.edge, "ppc") * n * std::ceil(kWavePeriods * n / kWaveCourant);
      if (w.run) {
        f.wave_rows.push_back(*w.run);
        f.run_cost += RunRow(*w.run).particle_steps();
        f.within += w.within();
        f.by_transfer[w.transfer].first += w.within();
        ++f.by_transfer[w.transfer].second;
      }
    }
    const std::string ending = m.table1 ? outcome(*m.table1) : std::string();
    f.stable += ending == "stable";
    f.meaningless += ending == "meaningless";
    f.unstable += ending == "unstable";
    if (m.error()) (accurate_run(*m.table1) ? f.accurate : f.inaccurate) += 1;
    f.with_order_h += m.order_h.value.has_value();
    f.with_order_dt += m.order_dt.value.has_value();
    f.beyond += f.waves[i].computed && !f.waves[i].above_limit && !f.waves[i].cells;
    if (!has_number(*m.edge, "dt_edge_over_cfl")) continue;
    ++f.edges;
    f.meaningless_edges += outcome(*m.edge) == "meaningless";
  }
  f.others = int(f.methods.size()) - f.stable - f.meaningless - f.unstable;
  const auto error = [&](std::size_t i) { return f.methods[i].error(); };
  const auto cells = [&](std::size_t i) { return f.waves[i].cells; };
  const auto edge = [&](std::size_t i) -> std::optional<double> {
    const ojson& r = *f.methods[i].edge;
    if (!has_number(r, "dt_edge_over_cfl") || outcome(r) == "meaningless") return std::nullopt;
    return r["dt_edge_over_cfl"].get<double>();
  };
  f.best_error = extreme(f.methods, error, false, [](double v) { return sci(v); });
  f.fewest_cells = extreme(f.methods, cells, false, cells_text);
  f.most_cells = extreme(f.methods, cells, true, cells_text);
  f.widest_edge = extreme(f.methods, edge, true, [](double v) { return fixed(v, 3); });
  return f;
}

// ---------------------------------------------------------------------------------------------
// Claims

Claim wave_run_claim(const Findings& f) {
  Claim c = claim("wave-column-within-tolerance-in-a-run",
                  "At its wave column's value, rounded up to whole cells, the single-mode run of "
                  "every scheme whose column is at most {cap} cells stays within {tolerance} of "
                  "A over {periods} periods at c dt / h = {courant}",
                  "{within} of {runs} schemes' runs end stable with an error over time of at "
                  "most {tolerance} A");
  c.value("cap", std::to_string(kMaxWaveRunCells))
      .value("tolerance", percent(kWaveTolerance))
      .value("periods", shortest(kWavePeriods))
      .value("courant", shortest(kWaveCourant))
      .every("within", f.within, "runs", (long long)f.wave_rows.size())
      .on(coverage_of(f.wave_rows));
  return c;
}

// ---------------------------------------------------------------------------------------------
// Text

// "2.01 (5 of 5)": the order and the runs it is fitted over of the runs of its kind; "– (2 of 5)"
// with fewer than loglog_slope needs.
std::string order_text(const Order& o) {
  if (o.runs == 0) return "–";
  return (o.value ? fixed(*o.value, 2) : std::string("–")) + " (" + std::to_string(o.fitted) +
         " of " + std::to_string(o.runs) + ")";
}

std::string edge_text(const ojson& r, const char* column, const char* missing) {
  return has_number(r, column) ? fixed(r[column].get<double>(), 3) : std::string(missing);
}

// The accuracy edge, or why there is none: withheld where the search's reference run or its run
// at the edge is not accurate (report.hpp, add_accuracy_classes); "–" where the search found
// none (its reference run meaningless).
std::string accuracy_edge_text(const ojson& r) {
  const bool withheld = r.value("accuracy_edge_withheld", false);
  return edge_text(r, "dt_accurate_over_cfl", withheld ? "withheld" : "–");
}

// The error at T at Table 1's setting, or the verdict where the run did not end stable.
std::string table1_text(const MethodRow& m) {
  if (!m.table1) return "–";
  const ojson& r = *m.table1;
  return outcome(r) == "stable" && has_number(r, "max_error") ? sci(r["max_error"].get<double>())
                                                              : verdict(r);
}

// The error over time at Table 1's setting with its size per A and its accuracy class, and the
// energy balance error there ("–" where the run did not end stable: its verdict is in the column
// before).
std::string table1_over_time(const MethodRow& m) {
  const auto e = m.error();
  if (!e || !has_number(*m.table1, "A")) return "–";
  const double A = (*m.table1)["A"].get<double>();
  return sci(*e) + " (" + ratio(*e / A) + " A, " + std::string(to_string(accuracy_class(*e, A))) +
         ")";
}
std::string table1_energy(const MethodRow& m) {
  if (!m.table1 || outcome(*m.table1) != "stable" || !has_number(*m.table1, "energy_error_max"))
    return "–";
  return sci((*m.table1)["energy_error_max"].get<double>());
}

std::string wave_text(const WaveCells& w) {
  if (!w.computed) return "–";
  if (w.above_limit) return "above the limit";
  return w.cells ? cells_text(*w.cells) : "> " + shortest(kMaxCellsPerWavelength);
}

// The column's single-mode run: its error over time per A as a percentage (on the side of the
// tolerance it was judged), or its verdict, or why there is none.
std::string wave_run_text(const WaveCells& w) {
  if (!w.run) return w.run_cells() > kMaxWaveRunCells ? "not run (column above its cap)" : "–";
  const RunRow run(*w.run);
  if (!run.stable_over_a_wave_pass() || !run.error_over_A()) return verdict(*w.run);
  return beside_thresholds(100 * *run.error_over_A(), {100 * kWaveTolerance}) + "%";
}

// The schemes whose run is within the tolerance, by transfer: "flip 18 of 18, apic 6 of 18".
std::string transfers_text(const Findings& f) {
  std::vector<std::string> names;
  for (const auto& [transfer, counts] : f.by_transfer)
    names.push_back(transfer + " " + std::to_string(counts.first) + " of " +
                    std::to_string(counts.second));
  return list_of(names);
}

// The reading: facts of the table, every number from its rows.
std::string reading(const Findings& f) {
  std::ostringstream md;
  md << "Of " << f.methods.size() << " methods at Table 1's setting ("
     << coverage_of(f.table1_runs).text() << "), " << f.stable << " end stable (" << f.accurate
     << " accurate, error over time below " << shortest(kAccurateFraction) << " A; " << f.inaccurate
     << " inaccurate, from " << shortest(kAccurateFraction) << " A up to A), " << f.meaningless
     << " meaningless and " << f.unstable << " unstable";
  if (f.others > 0) md << " (" << f.others << " too short or not run)";
  if (f.best_error.value) {
    md << "; the smallest error over time there is " << sci(*f.best_error.value) << " ("
       << f.best_error.methods << ")";
  }
  md << ". An order in h is fitted for " << f.with_order_h << " of " << f.methods.size()
     << " methods and an order in dt for " << f.with_order_dt << ". ";
  if (f.fewest_cells.value) {
    md << "By the Bloch symbol, the smallest number of cells per wavelength for a wave error of at "
          "most "
       << percent(kWaveTolerance) << " after " << shortest(kWavePeriods)
       << " periods at c dt / h = " << shortest(kWaveCourant) << " is "
       << cells_text(*f.fewest_cells.value) << " (" << f.fewest_cells.methods
       << "), the largest found " << cells_text(*f.most_cells.value) << " (" << f.most_cells.methods
       << ")";
    if (f.beyond > 0)
      md << "; " << f.beyond << " methods need more than " << shortest(kMaxCellsPerWavelength);
    md << ". Run on its own column's value, rounded up (" << coverage_of(f.wave_rows).text()
       << "), the single-mode run of " << f.within << " of " << f.wave_rows.size()
       << " schemes stays within " << percent(kWaveTolerance) << " of A over its periods"
       << ", by transfer " << transfers_text(f) << " (" << f.not_run
       << " others not run: their column exceeds " << kMaxWaveRunCells
       << " cells): the column is the symbol's, and where a scheme's run is not within, that "
          "many cells do not give a run of that scheme the tolerance. ";
  }
  md << "Of " << f.edges << " survival edges at the tiny amplitude (" << f.edges_on.text() << "), "
     << f.meaningless_edges
     << " are runs whose error over time reached A (meaningless: marked in the table and the "
        "figure)";
  if (f.widest_edge.value) {
    md << "; the widest of the others is " << fixed(*f.widest_edge.value, 3) << " h/c ("
       << f.widest_edge.methods
       << "), at this amplitude and run length only: an edge is not a recommended step";
  }
  md << ".";
  return md.str();
}

std::string methods_table(const Findings& f) {
  std::ostringstream md;
  md << "| basis | transfer | update | error at T at Table 1's setting | error over time there | "
        "energy balance error there | cells per wavelength for a wave error (damping and phase "
        "together, per amplitude) of at most "
     << percent(kWaveTolerance) << " after " << shortest(kWavePeriods)
     << " periods (Bloch symbol of the linearised step, C = " << shortest(kWaveCourant)
     << ") | its single-mode run on that many cells: error over time / A | order in h ("
     << coverage_of(f.h_runs).text() << "; fitted over n of N runs) | order in dt ("
     << f.dt_on.text() << "; fitted over n of N runs) | spectral limit (h/c) | survival edge (h/c; "
     << f.edges_on.text() << ") | accuracy edge (h/c; the same runs) | node visits per "
     << "particle-step |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < f.methods.size(); ++i) {
    const MethodRow& m = f.methods[i];
    const RunRow edge(*m.edge);
    md << "| " << basis_text(m.key) << " | " << transfer_text(m.key) << " | " << std::get<4>(m.key)
       << " | " << table1_text(m) << " | " << table1_over_time(m) << " | " << table1_energy(m)
       << " | " << wave_text(f.waves[i]) << " | " << wave_run_text(f.waves[i]) << " | "
       << order_text(m.order_h) << " | " << order_text(m.order_dt) << " | "
       << (edge.courant_spectral ? fixed(*edge.courant_spectral, 3)
                                 : "> " + shortest(kMaxSpectralCourant))
       << " | " << edge_text(*m.edge, "dt_edge_over_cfl", "not found in the scan");
    if (has_number(*m.edge, "dt_edge") && edge.outcome == "meaningless") md << " (meaningless)";
    md << " | " << accuracy_edge_text(*m.edge) << " | " << node_visits(m.key) << " |\n";
  }
  return md.str();
}

// How the error at Table 1's setting and the orders are measured, every number from the rows
// of methods_grid that give them.
std::string how_to_read_the_setting(const Findings& f) {
  const auto& [table1, h_runs, cfl_runs, fixed_runs] =
      std::tie(f.table1_runs, f.h_runs, f.cfl_runs, f.fixed_runs);
  std::ostringstream md;
  md << "- *error at T at Table 1's setting*: max_p |u_p - u(X_p, T)| at T = "
     << listing(table1, "T") << " on the bar, E = " << listing(table1, "E")
     << ", A = " << listing(table1, "A") << ", " << kTable1Cells << " cells x "
     << listing(table1, "ppc") << " particles, dt = " << param(kTable1Dt)
     << " (the verdict where the run did not end stable), shown, never fitted; *error over time "
        "there*: the largest such error after any step, with its size per A and its accuracy "
        "class; *energy balance error there*: the largest balance error of the particles' kinetic "
        "and strain energy and the body force's work, per the initial energy (docs/theory.md, "
        "\"Energy\");\n- *order in h*: least-squares slope of log(error over time) against "
        "log(h) over the runs on "
     << listing(h_runs, "cells") << " cells at C = c dt / h = " << shortest(kOrderHCourant)
     << " and A = " << listing(h_runs, "A") << " (E = " << listing(h_runs, "E")
     << ", T = " << listing(h_runs, "T") << "; A / h " << span(numbers(h_runs, "A_over_h"))
     << "); *order in dt*: against log(dt), over the runs at Table 1's amplitude below the "
        "scheme's spectral limit, on "
     << kTable1Cells << " cells over C = " << listing(cfl_runs, "cfl_factor")
     << " and dt = " << listing(fixed_runs, "dt")
     << " (C = " << listing(values_of(fixed_runs, &RunRow::courant)) << "); " << order_regime_text()
     << ". Beside each order, (n of N): the N runs of its kind the method has and the n of them "
        "in the regime, the points it is fitted over (`–` before them with fewer than the fit "
        "needs). An order in dt near zero says that over these runs the error over time hardly "
        "changes with dt;\n";
  return md.str();
}

std::string wave_how_to_read(const std::vector<ojson>& edge_rows, const Findings& f) {
  std::ostringstream md;
  md << "- *cells per wavelength for |lambda^n - e^(i omega t)| <= " << percent(kWaveTolerance)
     << " after " << shortest(kWavePeriods)
     << " periods*: the smallest number of cells per wavelength above which, by the Bloch "
        "symbol of the scheme's step linearised at rest, a wave of the interior of the uniform "
        "layout comes out within "
     << percent(kWaveTolerance) << " of the exact wave after " << shortest(kWavePeriods)
     << " of its periods, at c dt / h = " << shortest(kWaveCourant)
     << ". The wave is carried by the scheme's physical branch lambda, the acoustic eigenvalue "
        "of its Bloch symbol ([dispersion.md](dispersion.md); docs/theory.md, \"Dispersion\"), "
        "and its error per unit amplitude after n steps of dt is |lambda^n - e^(i omega n dt)|, "
        "omega = c k: the damping (|lambda| below one) and the phase error together, taken at "
        "t = "
     << shortest(kWavePeriods)
     << " periods (a wave whose branch stops propagating counts as beyond the tolerance). The "
        "scan runs from the longest waves up, then bisects (core/analysis/dispersion.hpp, "
        "cells_per_wavelength_amplitude); `> "
     << shortest(kMaxCellsPerWavelength)
     << "` where the error exceeds the tolerance even at that many cells per wavelength; `above "
        "the limit` where c dt / h = "
     << shortest(kWaveCourant)
     << " is at or above the scheme's spectral limit. At the rows' particles per cell ("
     << listing(edge_rows, "ppc")
     << "); the walls do not enter it (a B-spline with modified walls has its interior's "
        "value). dispersion.md's cells per wavelength for a phase error alone leave the damping "
        "out;\n- *its single-mode run on that many cells*: the error over time per A (or the "
        "verdict) of one run of the mode scene, one free standing wave of the periodic bar with "
        "the bar's length as its wavelength, on the column's value rounded up, at c dt / h = "
     << shortest(kWaveCourant) << " to the end of " << shortest(kWavePeriods)
     << " periods (E = " << shortest(kWaveRunE) << ", A = " << param(kWaveRunAmplitude)
     << "), where the symbol's error is within the tolerance by the column's definition; one run "
        "per scheme, the walls' treatments sharing it. The symbol follows the particles' "
        "velocities and strains (and APIC's affine terms) through the step linearised at rest; a "
        "run's error is that of the displacement, the sum of the grid velocities over the steps. "
        "The runs take "
     << sci(f.run_cost) << " particle-steps; `not run (column above its cap)` where the column "
     << "exceeds " << kMaxWaveRunCells << " cells (" << f.not_run
     << " schemes, whose runs would take " << sci(f.not_run_cost) << " particle-steps);\n";
  return md.str();
}

std::string methods_index(const Spec& spec, const std::vector<ojson>& rows, const ojson&) {
  std::ostringstream md;
  md << "![" << spec.title << "](" << spec.name << ".png)\n\n**What it shows.** "
     << method_rows(rows, {}).size()
     << " methods (basis x transfer x update order), each with its error at Table 1's setting, "
        "its orders in h and dt with the runs each is fitted over, the cells per wavelength for "
        "a wave error of at most "
     << percent(kWaveTolerance) << " after " << shortest(kWavePeriods)
     << " periods by the Bloch symbol with a single-mode run on that many cells, its edges at a "
        "tiny amplitude and its work per particle-step; the recommendations are "
        "advice.md's. Details: ["
     << spec.name << ".md](" << spec.name << ".md).\n\n";
  return md.str();
}

// ---------------------------------------------------------------------------------------------
// Figure

const std::vector<std::string> kBases = {"mpm",
                                         "gimp",
                                         "cpgimp",
                                         "cpdi",
                                         "bspline2",
                                         "bspline3",
                                         "bspline2 (modified)",
                                         "bspline3 (modified)"};
const std::vector<std::string> kTransfers = {"flip", "pic", "apic", "xpic(2)", "fmpm(2)"};
const std::vector<std::string> kUpdates = {"usl", "usf", "musl"};

int index_in(const std::vector<std::string>& list, const std::string& s) {
  const auto it = std::find(list.begin(), list.end(), s);
  return it == list.end() ? -1 : int(it - list.begin());
}

// <name>_data.csv: one row per method with an error over time at Table 1's setting and a survival
// edge.
std::string methods_data(const std::vector<MethodRow>& rows, const std::string& header) {
  std::ostringstream csv;
  csv << header << "# panel: update order (" << codes(kUpdates) << "); series: basis ("
      << codes(kBases) << "); shape: transfer (" << codes(kTransfers) << ")\n"
      << "panel,series,shape,edge_over_cfl,error,meaningless_at_edge\n";
  for (const auto& m : rows) {
    const auto e = m.error();
    if (!e || !has_number(*m.edge, "dt_edge_over_cfl")) continue;
    csv << index_in(kUpdates, std::get<4>(m.key)) << ',' << index_in(kBases, basis_text(m.key))
        << ',' << index_in(kTransfers, transfer_text(m.key)) << ','
        << shortest((*m.edge)["dt_edge_over_cfl"].get<double>()) << ',' << shortest(*e) << ','
        << (outcome(*m.edge) == "meaningless" ? 1 : 0) << '\n';
  }
  return csv.str();
}

// "120 methods with a survival edge; E = 64, A = 1e-4, 100 cells".
std::string methods_subtitle(const Spec&, const ojson& doc) {
  const std::vector<ojson> rows(doc["cases"].begin(), doc["cases"].end());
  const Findings f = find(rows, {}, {});
  return std::to_string(f.edges) + " methods with a survival edge; E = " + listing(rows, "E") +
         ", A = " + listing(rows, "A") + ", " + listing(rows, "cells") + " cells";
}

// The report, from the findings: the reading, how to read a row, the table, the wave check.
StudyReport methods_report(const ReportContext& c) {
  const std::vector<ojson> grid = grid_rows(c.inputs);  // the findings point into it
  const Findings f = find(c.rows, grid, c.follow_up);
  std::ostringstream md;
  md << "## Results\n\n**Reading.** " << reading(f) << "\n\n"
     << "This table measures; it does not recommend: this project answers a user's problem with "
        "`mpmstab advise`, which runs each answer on that problem before giving it "
        "([advice.md](advice.md)).\n\n"
     << cost_metric_text() << "\n\n![" << c.spec.title << "](" << c.spec.name
     << ".png)\n\nThe figure places each method by its survival edge at the tiny amplitude A = "
     << listing(c.rows, "A")
     << " (x) and its error over time at Table 1's setting (y), one panel per update order; a "
        "method unstable at that setting or without an edge is left out. Vector version: ["
     << c.spec.name << ".svg](" << c.spec.name << ".svg); data: [" << c.spec.name << "_data.csv]("
     << c.spec.name << "_data.csv).\n\n"
     << "How to read a row:\n\n"
     << how_to_read_the_setting(f) << wave_how_to_read(c.rows, f)
     << "- *spectral limit*: the largest c dt / h at which the scheme's map, linearised about "
        "rest at the uniform layout, amplifies nothing: the Bloch limit of the interior "
        "(docs/theory.md, \"The spectral limit\"; the walls' treatment does not enter it; "
        "spectral.md sets the limits against runs); `> "
     << shortest(kMaxSpectralCourant) << "` when nothing amplifies up to "
     << shortest(kMaxSpectralCourant) << ";\n"
     << "- *survival edge*: the largest fixed dt with which the bar at A = " << listing(c.rows, "A")
     << ", E = " << listing(c.rows, "E") << " survives to T = " << listing(c.rows, "T")
     << ", in units of h/c; *accuracy edge*: the largest dt up to which its error stays within "
     << shortest(c.spec.study->edge.accuracy_factor)
     << " times that of the smallest dt that survives (the edge study's rules), `withheld` where "
        "that reference run or the run at the edge is not accurate (error over time at least "
     << shortest(kAccurateFraction) << " A);\n"
     << "- *node visits per particle-step*: the nodes of the stencil times the passes over it "
        "that one step makes (counted from the code: p2g, g2p and the stress update, plus what "
        "the update order and the transfer add), what makes one particle-step of a method dearer "
        "than another's; the measured time per particle-step is in performance.md.\n\n";
  if (grid.empty())
    md << "methods_grid has not been run into this folder: the columns it provides are `–`.\n\n";
  md << methods_table(f) << "\n";
  return StudyReport{.markdown = md.str(),
                     .data_csv = methods_data(f.methods, c.csv_header),
                     .claims = {wave_run_claim(f)}};
}

const StudyRegistration kMethods{{
    .name = "methods",
    .summary = "one row per method: error, orders with their support, cells per wavelength for "
               "a wave error after some periods, tiny-amplitude edges, work per particle-step",
    .work = CaseWork::edge_search,
    .inputs = {{.name = "methods_grid", .required = true}},
    .figure = true,
    .follow_up = wave_runs,
    .report = methods_report,
    .index = methods_index,
    .figure_subtitle = methods_subtitle,
}};

}  // namespace
}  // namespace mpmstab::studies::methods
