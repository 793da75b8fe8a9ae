// Energy: the energy balance of every transfer and update order at Table 1 cells, its drift per
// period against dt and h with fitted orders, and how early the balance, eq. (108) and the
// spectral limit warn of a failure (docs/theory.md, "Energy"). The cases say which part they
// belong to by what they are: fixed-step cells run with more than one transfer or update order
// are the histories, cfl runs the drift sweeps (on 100 cells against C, at one C against the
// cells), fixed-step runs that fail the early warnings.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "claims.hpp"
#include "csv.hpp"
#include "key.hpp"
#include "observers/energy.hpp"
#include "report_util.hpp"
#include "run_row.hpp"
#include "study.hpp"
#include "sweep.hpp"

namespace mpmstab::studies::energy {
namespace {

using ojson = nlohmann::ordered_json;

// The drift sweeps: against C on this many cells, against the cells at this C.
constexpr int kDtSweepCells = 100;
constexpr double kHSweepCourant = 0.1;
// At most this many points of a history per series in the figure's data.
constexpr int kFigurePoints = 400;

// A Table 1 cell: method, E, A, dt.
using Cell = std::tuple<std::string, Key, Key, Key>;
Cell cell_of(const ojson& r) {
  return {RunRow(r).method, Key(r["E"].get<double>(), "E"), Key(r["A"].get<double>(), "A"),
          Key(r["dt"].get<double>(), "dt")};
}

bool fixed_step(const ojson& r) {
  return r["policy"].get<std::string>() == "fixed";
}

// The cells run with more than one transfer or update order (the histories): the indices of
// their fixed-step rows, in row order.
std::map<Cell, std::vector<std::size_t>> histories(const std::vector<ojson>& rows) {
  std::map<Cell, std::set<std::string>> variants;
  for (const auto& r : rows)
    if (fixed_step(r)) variants[cell_of(r)].insert(method_label(r));
  std::map<Cell, std::vector<std::size_t>> cells;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (fixed_step(rows[i]) && variants[cell_of(rows[i])].size() > 1)
      cells[cell_of(rows[i])].push_back(i);
  return cells;
}

// The drift sweeps of one method: (variable, row), coarsest first, and the fitted orders of the
// balance error, max, and of the drift per period.
struct Sweep {
  std::string method, variable;  // the variable: "C" or "cells"
  struct Point {
    double x = 0;
    const ojson* row = nullptr;
    bool in_regime = false;  // enters the orders
  };
  std::vector<Point> points;
  std::optional<double> error_order, drift_order;
};

// The fitted order of |column| against the sweep's variable (C or h), stable runs only.
// A point enters an order only in its regime (report_util.hpp): an accurate run, and against h
// one in which no particle crosses a cell.
std::optional<double> sweep_order(const Sweep& sw, const char* column) {
  std::vector<std::pair<double, double>> xy;
  for (const auto& p : sw.points) {
    if (!p.in_regime || !has_number(*p.row, column)) continue;
    const double v = std::abs((*p.row)[column].get<double>());
    if (v > 0) xy.emplace_back(p.x, v);
  }
  return loglog_slope(xy);
}

std::vector<Sweep> drift_sweeps(const std::vector<ojson>& rows) {
  std::map<std::pair<std::string, std::string>, Sweep> s;
  for (const auto& r : rows) {
    if (r["policy"].get<std::string>() != "cfl") continue;
    const std::string m = method_label(r);
    const double C = r["cfl_factor"].get<double>();
    const int cells = r["cells"].get<int>();
    if (cells == kDtSweepCells) s[{m, "C"}].points.push_back({C, &r, accurate_run(r)});
    if (C == kHSweepCourant)
      s[{m, "cells"}].points.push_back({1.0 / cells, &r, accurate_run(r) && crossing_free(r)});
  }
  std::vector<Sweep> out;
  for (auto& [k, sw] : s) {
    std::tie(sw.method, sw.variable) = k;
    std::sort(sw.points.begin(), sw.points.end(),
              [](const auto& a, const auto& b) { return TotalLess()(b.x, a.x); });
    sw.error_order = sweep_order(sw, "energy_error_max");
    sw.drift_order = sweep_order(sw, "energy_drift");
    out.push_back(sw);
  }
  return out;
}

// The early warnings of a fixed-step run.
struct Warning {
  const ojson* row = nullptr;
  bool failed = false;         // the run failed; otherwise it reached T
  long long failure_step = 0;  // the failing step, or the last step of a run that reached T
  std::optional<long long> energy_step;  // first step with the balance beyond kEnergyWarning
  std::optional<long long> eq108_step;   // first step whose dt exceeds eq. (108) of its state
  std::optional<bool> above_spectral;    // c dt/h above the spectral limit (from step 0)
};

// How often a signal fired: before a failure (warned), and in a run that reached T.
struct Lead {
  int warned = 0, false_warnings = 0;
  void add(bool failed, bool fired) { (failed ? warned : false_warnings) += fired; }
};

// What the study finds: the histories, the drift sweeps with their orders and the early warnings,
// with every count its claims, its text, its index paragraph and its subtitle give.
struct Findings {
  std::map<Cell, std::vector<std::size_t>> histories;
  std::vector<double> drift_A, drift_A_over_h;  // of the drift sweeps' runs
  std::vector<Sweep> sweeps;
  std::vector<Warning> failures;          // the warnings of the runs that failed
  long long failed = 0, survived = 0;     // fixed-step runs that failed and that reached T
  Lead energy, eq108, spectral;           // the balance, eq. (108) and the spectral limit
  long long drawn = 0, drawn_failed = 0;  // the histories' runs, and those that failed
  int pic_above = 0, pic_cells = 0;  // history cells with both, PIC's balance error above FLIP's
  int converge = 0, fitted = 0;      // sweeps with a fitted order of the balance error, positive
  // Where the runs that decide each claim lie: the history cells' FLIP and PIC runs, the points of
  // the sweeps with a fitted order, the fixed-step runs.
  Coverage pic_on, converge_on, warnings_on;
};

// The findings from the rows and, in the report, the records (whose histories give the step at
// which eq. (108) first warns; the index and the subtitle, which print no such step, pass none).
Findings find(const std::vector<ojson>& rows, const SweepOutcome& records) {
  Findings f;
  f.histories = histories(rows);
  // PIC's and FLIP's balance errors at each history cell.
  for (const auto& [c, cell_rows] : f.histories) {
    std::optional<double> flip, pic;
    for (const std::size_t i : cell_rows) {
      const ojson& r = rows[i];
      ++f.drawn;
      f.drawn_failed += !survived(r);
      if (!has_number(r, "energy_error_max")) continue;
      if (method_label(r) == std::get<0>(c)) flip = r["energy_error_max"].get<double>();
      if (method_label(r) == std::get<0>(c) + "/pic") pic = r["energy_error_max"].get<double>();
    }
    if (!flip || !pic) continue;
    ++f.pic_cells;
    f.pic_above += *pic > *flip;
    f.pic_on.add(rows[cell_rows.front()]);  // a cell's runs share A, c T, grid and scene
  }
  f.sweeps = drift_sweeps(rows);
  for (const auto& sw : f.sweeps) {
    f.fitted += sw.error_order.has_value();
    f.converge += sw.error_order && *sw.error_order > 0;
    for (const auto& p : sw.points)
      if (sw.error_order && p.in_regime) f.converge_on.add(*p.row);
  }
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ojson& r = rows[i];
    if (r["policy"].get<std::string>() == "cfl") {
      if (has_number(r, "A")) f.drift_A.push_back(r["A"].get<double>());
      if (has_number(r, "A_over_h")) f.drift_A_over_h.push_back(r["A_over_h"].get<double>());
    }
    if (!fixed_step(r)) continue;
    f.warnings_on.add(r);
    Warning x;
    x.row = &r;
    x.failed = outcome(r) == "unstable" && has_number(r, "failure_step");
    x.failure_step = x.failed ? r["failure_step"].get<long long>() : r["steps"].get<long long>();
    if (has_number(r, "energy_warning_step"))
      x.energy_step = r["energy_warning_step"].get<long long>();
    const double dt = r["dt"].get<double>();
    const ojson* record = i < records.records.size() ? &records.records[i] : nullptr;
    if (record && record->is_object() && record->contains("history"))
      for (const auto& h : (*record)["history"]) {
        // The bound of the state after step n limits step n + 1.
        if (h["dt_stable"].is_number() && dt > h["dt_stable"].get<double>()) {
          x.eq108_step = h["step"].get<long long>() + 1;
          break;
        }
      }
    x.above_spectral = above_spectral_limit(r);
    // Before the failure, in a run that failed; at all, in one that reached T.
    const auto fired = [&](const std::optional<long long>& s) {
      return x.failed ? s && *s < x.failure_step : s.has_value();
    };
    f.energy.add(x.failed, fired(x.energy_step));
    f.eq108.add(x.failed, fired(x.eq108_step));
    f.spectral.add(x.failed, x.above_spectral && *x.above_spectral);
    (x.failed ? f.failed : f.survived) += 1;
    if (x.failed) f.failures.push_back(x);
  }
  return f;
}

// An early warning before every failure, and the same signal in the runs that reach T (false
// warnings): it holds when the signal came before every failure (`hits`, the value named
// `hits_name`) and in no run that reached T.
Claim lead_claim(const Findings& f, const Lead& lead, const char* id, const char* what,
                 const char* hits_name = "warned",
                 const char* evidence =
                     "before {warned} of {failed} failures; in {false_warnings} of {survived} "
                     "fixed-step runs that reach T") {
  Claim c = claim(
      id,
      std::string(what) + " warns before every failure of this study and in no run that reaches T",
      evidence);
  c.count(hits_name, lead.warned)
      .count("failed", f.failed)
      .count("false_warnings", lead.false_warnings)
      .count("survived", f.survived);
  c.holds = f.failed > 0 && lead.warned == f.failed && lead.false_warnings == 0;
  return c.on(f.warnings_on);
}

std::vector<Claim> energy_claims(const Findings& f) {
  Claim pic =
      claim("pic-dissipates", "PIC's energy balance error exceeds FLIP's at every history cell",
            "{holds} of {total} cells");
  pic.every("holds", f.pic_above, "total", f.pic_cells).on(f.pic_on);
  Claim converges = claim("balance-converges",
                          "The energy balance error falls as dt and h fall, for MPM and GIMP on "
                          "the bar at the drift sweeps' amplitude, over the runs in the regime "
                          "orders are fitted in",
                          "{converge} of {total} sweeps have a positive fitted order");
  converges.every("converge", f.converge, "total", f.fitted).on(f.converge_on);
  return {pic, converges,
          lead_claim(f, f.energy, "energy-warns", "The energy balance leaving its band"),
          lead_claim(f, f.eq108, "eq108-warns", "A dt above eq. (108)"),
          lead_claim(f, f.spectral, "spectral-warns", "A c dt/h above the spectral limit", "above",
                     "{above} of {failed} failed runs step above the limit; {false_warnings} of "
                     "{survived} fixed-step runs that reach T")};
}

std::string cell_text(const Cell& c) {
  return std::get<0>(c) + ", E = " + shortest(std::get<1>(c)) +
         ", A = " + shortest(std::get<2>(c)) + ", dt = " + shortest(std::get<3>(c));
}

std::string num(const ojson& r, const char* column, int digits = 2) {
  return has_number(r, column) ? sci(r[column].get<double>(), digits) : std::string("–");
}

// The balance of each history cell, one row per transfer or update order.
std::string history_table(const std::vector<ojson>& rows, const Findings& f) {
  std::ostringstream md;
  for (const auto& [c, cell_rows] : f.histories) {
    const ojson& first = rows[cell_rows.front()];
    md << "**" << cell_text(c) << "** (c dt/h = " << shortest(RunRow(first).courant.value())
       << ", A/h = " << shortest(first["A_over_h"].get<double>())
       << ", c T = " << shortest(*RunRow(first).wave_passes)
       << ")\n\n| transfer and update | outcome | balance error, max | against the exact "
          "K + U, max | drift per period | error over time |\n|---|---|---|---|---|---|\n";
    for (const std::size_t i : cell_rows) {
      const ojson& r = rows[i];
      md << "| " << method_label(r) << " | " << verdict(r) << " | " << num(r, "energy_error_max")
         << " | " << num(r, "energy_exact_error_max") << " | " << num(r, "energy_drift") << " | "
         << opt_sci(RunRow(r).error_over_time) << " |\n";
    }
    md << "\n";
  }
  return md.str();
}

std::string drift_table(const std::vector<Sweep>& sweeps) {
  std::ostringstream md;
  md << "| method | against | points: balance error, max / drift per period | order of the "
        "balance error | order of the drift |\n|---|---|---|---|---|\n";
  for (const auto& sw : sweeps) {
    std::vector<std::string> pts;
    for (const auto& p : sw.points) {
      const std::string label =
          sw.variable == "C" ? "C = " + shortest(p.x) : shortest(1.0 / p.x) + " cells";
      pts.push_back(label + ": " + num(*p.row, "energy_error_max") + " / " +
                    num(*p.row, "energy_drift") + (p.in_regime ? "" : " †"));
    }
    md << "| " << sw.method << " | " << (sw.variable == "C" ? "c dt/h" : "h") << " | "
       << list_of(pts) << " | " << opt_fixed(sw.error_order, 2) << " | "
       << opt_fixed(sw.drift_order, 2) << " |\n";
  }
  return md.str();
}

std::string lead_text(const std::optional<long long>& step, long long failure) {
  if (!step) return "no warning";
  return "step " + std::to_string(*step) + " (" + std::to_string(failure - *step) + " before)";
}

std::string warning_table(const std::vector<Warning>& failures) {
  std::ostringstream md;
  md << "| case | c dt/h (spectral limit) | A/h | failure | energy balance beyond "
     << shortest(kEnergyWarning) << " | dt above eq. (108) | spectral limit |\n"
     << "|---|---|---|---|---|---|---|\n";
  for (const auto& x : failures) {
    const ojson& r = *x.row;
    const RunRow run(r);
    Cell c = cell_of(r);
    std::get<0>(c) = run.method_label;  // with its transfer and update order
    md << "| " << cell_text(c) << " | " << fixed(*run.courant, 3) << " ("
       << opt_fixed(run.courant_spectral) << ") | " << shortest(r["A_over_h"].get<double>())
       << " | " << run.failure_reason.value_or("") << " at step " << x.failure_step << " | "
       << lead_text(x.energy_step, x.failure_step) << " | "
       << lead_text(x.eq108_step, x.failure_step) << " | "
       << (!x.above_spectral   ? "not recorded"
           : *x.above_spectral ? "above from the first step"
                               : "below: no warning")
       << " |\n";
  }
  return md.str();
}

std::string energy_index(const Spec& spec, const std::vector<ojson>& rows, const ojson&) {
  const Findings f = find(rows, SweepOutcome{});
  return "![" + spec.title + "](" + spec.name +
         ".png)\n\n**What it shows.** The energy balance of each transfer and update order over "
         "time, its drift against dt and h, and, for " +
         std::to_string(f.failed) +
         " failing runs, how early the balance (it leaves its band before " +
         std::to_string(f.energy.warned) + " of " + std::to_string(f.failed) +
         " failures, and also in " + std::to_string(f.energy.false_warnings) + " of " +
         std::to_string(f.survived) +
         " runs that reach T), eq. (108) and the spectral limit warn: [" + spec.name + ".md](" +
         spec.name + ".md).\n\n";
}

// <name>_data.csv: panel (history cell), series (transfer and update order), t and the balance.
std::string energy_data(const std::vector<ojson>& rows, const SweepOutcome& out, const Findings& f,
                        const std::string& header) {
  std::map<Cell, int> panel;
  std::map<std::string, int> series;
  for (const auto& [c, cell_rows] : f.histories) {
    panel.emplace(c, static_cast<int>(panel.size()));
    for (const std::size_t i : cell_rows)
      series.emplace(method_label(rows[i]), 0);
  }
  int k = 0;
  for (auto& [m, s] : series)
    s = k++;
  std::ostringstream csv;
  csv << header << "panel,series,cell,method,t,energy_balance\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ojson& r = rows[i];
    if (!fixed_step(r) || !f.histories.count(cell_of(r))) continue;
    const ojson& record = out.records[i];
    if (!record.is_object() || !record.contains("history")) continue;
    const auto& h = record["history"];
    const std::size_t stride = std::max<std::size_t>(1, h.size() / kFigurePoints);
    for (std::size_t j = 0; j < h.size(); j += stride) {
      if (!h[j]["energy_balance"].is_number()) continue;
      std::string label = cell_text(cell_of(r));  // gnuplot splits quoted fields at commas
      std::replace(label.begin(), label.end(), ',', ' ');
      csv << panel[cell_of(r)] << "," << series[method_label(r)] << "," << label << ","
          << method_label(r) << "," << shortest(h[j]["time"].get<double>()) << ","
          << sci(h[j]["energy_balance"].get<double>(), 4) << "\n";
    }
  }
  return csv.str();
}

// The subtitle: the runs drawn, and those of them that stop before T.
std::string energy_subtitle(const Spec&, const ojson& doc) {
  const std::vector<ojson> rows(doc["cases"].begin(), doc["cases"].end());
  const Findings f = find(rows, {});
  return std::to_string(f.drawn) + " runs at " + std::to_string(f.histories.size()) +
         " Table 1 cells, " + std::to_string(f.drawn_failed) + " of them unstable before T";
}

// The report: the findings once, and from them the claims, the text and the figure's data.
StudyReport energy_report(const ReportContext& ctx) {
  const Findings f = find(ctx.rows, ctx.outcome);
  std::ostringstream md;
  md << "**The quantities** (docs/theory.md, \"Energy\"): the kinetic energy K (half of sum_p "
        "m_p v_p squared), the strain energy U (sum_p of the reference volume times W(F_p)), the "
        "work W of the body force along the particles' motion, and the balance error e = (K + U - "
        "W) - (the initial K + U); every one per the initial K + U, so dimensionless. *Balance "
        "error, max*: max over the steps of |e|; *against the exact K + U*: max over the steps of "
        "the difference from the exact energies of the manufactured solution; *drift per "
        "period*: the least-squares slope of e against time, times the period of the exact "
        "solution: the secular part, which an oscillation does not move.\n\n"
     << "![" << ctx.spec.title << "](" << ctx.spec.name << ".png)\n\n"
     << "## Each transfer and update order\n\nThe figure draws the balance error e over time for "
        "each; the table gives the measures of the whole run.\n\n"
     << history_table(ctx.rows, f)
     << "## The drift against dt and h\n\nThe bar at A = " << listing(f.drift_A)
     << " (its rows are in the CSV; A / h = " << listing(f.drift_A_over_h)
     << "); each point: the balance error, max, and the drift per period. The orders are "
        "least-squares slopes on log-log axes against c dt/h (on "
     << kDtSweepCells << " cells) and against h (at C = " << shortest(kHSweepCourant)
     << "), of the absolute values; " << order_regime_text() << " (`†`: outside it).\n\n"
     << drift_table(f.sweeps)
     << "\n## Warnings before a failure\n\nFor each run of the study that fails: the step at "
        "which its energy balance first leaves the band of "
     << shortest(kEnergyWarning)
     << " of the initial energy, the first step whose dt exceeds eq. (108) of the state before "
        "it, and whether its c dt/h exceeds the spectral limit of its layout (a fixed step is "
        "above it from the start or never). Each warning is given with how many steps it comes "
        "before the failure. The claims also count the same signals in the fixed-step runs of the "
        "study that reach T: a warning that also fires there does not tell a failure apart.\n\n"
     << warning_table(f.failures);
  return StudyReport{.markdown = md.str(),
                     .data_csv = energy_data(ctx.rows, ctx.outcome, f, ctx.csv_header),
                     .claims = energy_claims(f)};
}

const StudyRegistration kEnergy{{
    .name = "energy",
    .summary = "energy balance per transfer and update order, its drift and its early warning",
    .records = {.error_over_time = true, .dt_stable = true, .history = true},
    .figure = true,
    .report = energy_report,
    .index = energy_index,
    .figure_subtitle = energy_subtitle,
}};

}  // namespace
}  // namespace mpmstab::studies::energy
