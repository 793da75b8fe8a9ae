// Energy: the energy balance of every transfer and update order at Table 1 cells, its drift per
// period against dt and h with fitted orders, and how early the balance, eq. (108) and the
// spectral limit warn of a failure (docs/theory.md, "Energy"). The cases say which part they
// belong to by what they are: fixed-step cells run with more than one transfer or update order
// are the histories, cfl runs the drift sweeps (on 100 cells against C, at one C against the
// cells), fixed-step runs that fail the early warnings.
#include <algorithm>
#include <cmath>
#include <limits>
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

namespace mpmstab {

namespace studies::energy {
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
std::string cell_text(const Cell& c) {
  return std::get<0>(c) + ", E = " + shortest(std::get<1>(c)) +
         ", A = " + shortest(std::get<2>(c)) + ", dt = " + shortest(std::get<3>(c));
}

bool fixed_step(const ojson& r) {
  return r["policy"].get<std::string>() == "fixed";
}

// The cells run with more than one transfer or update order: the histories.
std::set<Cell> history_cells(const std::vector<ojson>& rows) {
  std::map<Cell, std::set<std::string>> variants;
  for (const auto& r : rows)
    if (fixed_step(r)) variants[cell_of(r)].insert(method_label(r));
  std::set<Cell> cells;
  for (const auto& [c, v] : variants)
    if (v.size() > 1) cells.insert(c);
  return cells;
}

std::string num(const ojson& r, const char* column, int digits = 2) {
  return has_number(r, column) ? sci(r[column].get<double>(), digits) : std::string("–");
}

// The balance of each history cell, one row per transfer or update order.
std::string history_table(const std::vector<ojson>& rows, const std::set<Cell>& cells) {
  std::ostringstream md;
  for (const Cell& c : cells) {
    md << "**" << cell_text(c) << "** (c dt/h = ";
    bool first = true;
    for (const auto& r : rows) {
      if (!fixed_step(r) || cell_of(r) != c) continue;
      if (first) {
        md << shortest(RunRow(r).courant.value())
           << ", A/h = " << shortest(r["A_over_h"].get<double>())
           << ", c T = " << shortest(*RunRow(r).wave_passes)
           << ")\n\n| transfer and update | outcome | balance error, max | against the exact "
              "K + U, max | drift per period | error over time |\n|---|---|---|---|---|---|\n";
        first = false;
      }
      md << "| " << method_label(r) << " | " << verdict(r) << " | " << num(r, "energy_error_max")
         << " | " << num(r, "energy_exact_error_max") << " | " << num(r, "energy_drift") << " | "
         << opt_sci(RunRow(r).error_over_time) << " |\n";
    }
    md << "\n";
  }
  return md.str();
}

// The drift sweeps of one method: (variable, row), coarsest first.
struct Sweep {
  std::string method;
  std::string variable;  // "C" or "cells"
  std::vector<std::pair<double, const ojson*>> points;
};
std::vector<Sweep> drift_sweeps(const std::vector<ojson>& rows) {
  std::map<std::pair<std::string, std::string>, Sweep> s;
  for (const auto& r : rows) {
    if (r["policy"].get<std::string>() != "cfl") continue;
    const std::string m = method_label(r);
    const double C = r["cfl_factor"].get<double>();
    const int cells = r["cells"].get<int>();
    if (cells == kDtSweepCells) {
      auto& sw = s[{m, "C"}];
      sw.method = m;
      sw.variable = "C";
      sw.points.emplace_back(C, &r);
    }
    if (C == kHSweepCourant) {
      auto& sw = s[{m, "cells"}];
      sw.method = m;
      sw.variable = "cells";
      sw.points.emplace_back(1.0 / cells, &r);
    }
  }
  std::vector<Sweep> out;
  for (auto& [k, sw] : s) {
    std::sort(sw.points.begin(), sw.points.end(),
              [](const auto& a, const auto& b) { return TotalLess()(b.first, a.first); });
    out.push_back(sw);
  }
  return out;
}

// The fitted order of |column| against the sweep's variable (C or h), stable runs only.
// A point enters an order only in its regime (report_util.hpp): an accurate run, and against h
// one in which no particle crosses a cell.
bool in_regime(const Sweep& sw, const ojson& r) {
  return accurate_run(r) && (sw.variable == "C" || crossing_free(r));
}

std::optional<double> sweep_order(const Sweep& sw, const char* column) {
  std::vector<std::pair<double, double>> xy;
  for (const auto& [x, r] : sw.points) {
    if (!in_regime(sw, *r) || !has_number(*r, column)) continue;
    const double v = std::abs((*r)[column].get<double>());
    if (v > 0) xy.emplace_back(x, v);
  }
  return loglog_slope(xy);
}

// The rows of the drift sweeps (the cfl runs).
std::vector<ojson> drift_rows(const std::vector<ojson>& rows) {
  std::vector<ojson> out;
  for (const auto& r : rows)
    if (r["policy"].get<std::string>() == "cfl") out.push_back(r);
  return out;
}

std::string energy_order_text(const std::optional<double>& o) {
  return o ? fixed(*o, 2) : "–";
}

std::string drift_table(const std::vector<Sweep>& sweeps) {
  std::ostringstream md;
  md << "| method | against | points: balance error, max / drift per period | order of the "
        "balance error | order of the drift |\n|---|---|---|---|---|\n";
  for (const auto& sw : sweeps) {
    std::vector<std::string> pts;
    for (const auto& [x, r] : sw.points) {
      const std::string label =
          sw.variable == "C" ? "C = " + shortest(x) : shortest(1.0 / x) + " cells";
      pts.push_back(label + ": " + num(*r, "energy_error_max") + " / " + num(*r, "energy_drift") +
                    (in_regime(sw, *r) ? "" : " †"));
    }
    md << "| " << sw.method << " | " << (sw.variable == "C" ? "c dt/h" : "h") << " | "
       << list_of(pts) << " | " << energy_order_text(sweep_order(sw, "energy_error_max")) << " | "
       << energy_order_text(sweep_order(sw, "energy_drift")) << " |\n";
  }
  return md.str();
}

// The early warnings of a failed run.
struct Warning {
  const ojson* row = nullptr;
  bool failed = false;         // the run failed; otherwise it reached T
  long long failure_step = 0;  // the failing step, or the last step of a run that reached T
  std::optional<long long> energy_step;  // first step with the balance beyond kEnergyWarning
  std::optional<long long> eq108_step;   // first step whose dt exceeds eq. (108) of its state
  std::optional<bool> above_spectral;    // c dt/h above the spectral limit (from step 0)
};
std::vector<Warning> warnings(const std::vector<ojson>& rows, const SweepOutcome& outcome_) {
  std::vector<Warning> w;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ojson& r = rows[i];
    if (!fixed_step(r)) continue;
    Warning x;
    x.row = &r;
    x.failed = outcome(r) == "unstable" && has_number(r, "failure_step");
    x.failure_step = x.failed ? r["failure_step"].get<long long>() : r["steps"].get<long long>();
    if (has_number(r, "energy_warning_step"))
      x.energy_step = r["energy_warning_step"].get<long long>();
    const double dt = r["dt"].get<double>();
    const ojson* record = i < outcome_.records.size() ? &outcome_.records[i] : nullptr;
    if (record && record->is_object() && record->contains("history")) {
      for (const auto& h : (*record)["history"]) {
        // The bound of the state after step n limits step n + 1.
        if (h["dt_stable"].is_number() && dt > h["dt_stable"].get<double>()) {
          x.eq108_step = h["step"].get<long long>() + 1;
          break;
        }
      }
    }
    x.above_spectral = above_spectral_limit(r);
    w.push_back(x);
  }
  return w;
}

std::string lead_text(const std::optional<long long>& step, long long failure) {
  if (!step) return "no warning";
  return "step " + std::to_string(*step) + " (" + std::to_string(failure - *step) + " before)";
}

std::string warning_table(const std::vector<Warning>& w) {
  std::ostringstream md;
  md << "| case | c dt/h (spectral limit) | A/h | failure | energy balance beyond "
     << shortest(kEnergyWarning) << " | dt above eq. (108) | spectral limit |\n"
     << "|---|---|---|---|---|---|---|\n";
  for (const auto& x : w) {
    if (!x.failed) continue;
    const ojson& r = *x.row;
    const RunRow run(r);
    md << "| " << cell_text(cell_of(r)) << " | " << fixed(*run.courant, 3) << " ("
       << (run.courant_spectral ? fixed(*run.courant_spectral, 3) : "–") << ") | "
       << shortest(r["A_over_h"].get<double>()) << " | " << run.failure_reason.value_or("")
       << " at step " << x.failure_step << " | " << lead_text(x.energy_step, x.failure_step)
       << " | " << lead_text(x.eq108_step, x.failure_step) << " | "
       << (!x.above_spectral   ? "not recorded"
           : *x.above_spectral ? "above from the first step"
                               : "below: no warning")
       << " |\n";
  }
  return md.str();
}

// FLIP against PIC at each history cell.
Claim pic_dissipates_claim(const std::vector<ojson>& rows, const std::set<Cell>& cells) {
  int holds = 0, total = 0;
  for (const Cell& c : cells) {
    std::optional<double> flip, pic;
    for (const auto& r : rows) {
      if (!fixed_step(r) || cell_of(r) != c || !has_number(r, "energy_error_max")) continue;
      if (method_label(r) == std::get<0>(c)) flip = r["energy_error_max"].get<double>();
      if (method_label(r) == std::get<0>(c) + "/pic") pic = r["energy_error_max"].get<double>();
    }
    if (!flip || !pic) continue;
    ++total;
    holds += *pic > *flip;
  }
  Claim c = claim("pic-dissipates",
                  "PIC's energy balance error exceeds FLIP's at every history cell (PIC "
                  "dissipates what FLIP keeps)",
                  "{holds} of {total} cells");
  c.every("holds", holds, "total", total);
  return c;
}

// The balance error converges with dt and h.
Claim balance_converges_claim(const std::vector<Sweep>& sweeps) {
  int converge = 0, total = 0;
  for (const auto& sw : sweeps) {
    const auto o = sweep_order(sw, "energy_error_max");
    if (!o) continue;
    ++total;
    converge += *o > 0;
  }
  Claim c = claim("balance-converges",
                  "The energy balance error falls as dt and h fall, for MPM and GIMP on the "
                  "bar at the drift sweeps' amplitude, over the runs in the regime orders are "
                  "fitted in",
                  "{converge} of {total} sweeps have a positive fitted order");
  c.every("converge", converge, "total", total);
  return c;
}

// The failed runs and the fixed-step runs that reach T, which the warning claims count.
struct WarningCounts {
  long long failed = 0, survived = 0;
};

WarningCounts warning_counts(const std::vector<Warning>& w) {
  WarningCounts n;
  for (const auto& x : w)
    (x.failed ? n.failed : n.survived) += 1;
  return n;
}

// A warning claim: it holds when the signal came before every failure (`hits`, the value named
// `hits_name`) and in no run that reached T.
Claim warning_claim(const char* id, const std::string& statement, const char* evidence,
                    const char* hits_name, int hits, int false_warnings, const WarningCounts& n) {
  Claim c = claim(id, statement, evidence);
  c.count(hits_name, hits)
      .count("failed", n.failed)
      .count("false_warnings", false_warnings)
      .count("survived", n.survived);
  c.holds = n.failed > 0 && hits == n.failed && false_warnings == 0;
  return c;
}

// An early warning (the step at which `member` first fired) before every failure, and the same
// signal in the runs that reach T (false warnings).
Claim lead_claim(const std::vector<Warning>& w, std::optional<long long> Warning::*member,
                 const char* id, const char* what) {
  const WarningCounts n = warning_counts(w);
  int warned = 0, false_warnings = 0;
  for (const auto& x : w) {
    const auto& s = x.*member;
    if (x.failed) {
      warned += s && *s < x.failure_step;
    } else {
      false_warnings += s.has_value();
    }
  }
  return warning_claim(
      id,
      std::string(what) + " warns before every failure of this study and in no run that reaches T",
      "before {warned} of {failed} failures; in {false_warnings} of {survived} fixed-step runs "
      "that reach T",
      "warned", warned, false_warnings, n);
}

Claim spectral_warns_claim(const std::vector<Warning>& w) {
  const WarningCounts n = warning_counts(w);
  int above = 0, false_warnings = 0;
  for (const auto& x : w) {
    const bool a = x.above_spectral && *x.above_spectral;
    (x.failed ? above : false_warnings) += a;
  }
  return warning_claim("spectral-warns",
                       "A c dt/h above the spectral limit warns before every failure of this "
                       "study and in no run that reaches T",
                       "{above} of {failed} failed runs step above the limit; {false_warnings} of "
                       "{survived} fixed-step runs that reach T",
                       "above", above, false_warnings, n);
}

std::vector<Claim> energy_claims(const std::vector<ojson>& rows, const std::set<Cell>& cells,
                                 const std::vector<Sweep>& sweeps, const std::vector<Warning>& w) {
  return {
      pic_dissipates_claim(rows, cells), balance_converges_claim(sweeps),
      lead_claim(w, &Warning::energy_step, "energy-warns", "The energy balance leaving its band"),
      lead_claim(w, &Warning::eq108_step, "eq108-warns", "A dt above eq. (108)"),
      spectral_warns_claim(w)};
}

// <name>_data.csv: panel (history cell), series (transfer and update order), t and the balance.
std::string energy_data(const std::vector<ojson>& rows, const SweepOutcome& out,
                        const std::set<Cell>& cells, const std::string& header) {
  std::map<Cell, int> panel;
  int k = 0;
  for (const Cell& c : cells)
    panel[c] = k++;
  std::map<std::string, int> series;
  for (const auto& r : rows)
    if (fixed_step(r) && cells.count(cell_of(r))) series.emplace(method_label(r), 0);
  k = 0;
  for (auto& [m, s] : series)
    s = k++;
  std::ostringstream csv;
  csv << header << "panel,series,cell,method,t,energy_balance\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ojson& r = rows[i];
    if (!fixed_step(r) || !cells.count(cell_of(r))) continue;
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

StudyReport energy_report(const ReportContext& ctx) {
  const auto& rows = ctx.rows;
  const auto cells = history_cells(rows);
  const auto sweeps = drift_sweeps(rows);
  const auto w = warnings(rows, ctx.outcome);
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
     << history_table(rows, cells)
     << "## The drift against dt and h\n\nThe bar at A = " << listing(drift_rows(rows), "A")
     << " (its rows are in the CSV; A / h = " << listing(drift_rows(rows), "A_over_h")
     << "); each point: the balance error, max, and the drift per period. The orders are "
        "least-squares slopes on log-log axes against c dt/h (on "
     << kDtSweepCells << " cells) and against h (at C = " << shortest(kHSweepCourant)
     << "), of the absolute values; " << order_regime_text() << " (`†`: outside it).\n\n"
     << drift_table(sweeps)
     << "\n## Warnings before a failure\n\nFor each run of the study that fails: the step at "
        "which its energy balance first leaves the band of "
     << shortest(kEnergyWarning)
     << " of the initial energy, the first step whose dt exceeds eq. (108) of the state before "
        "it, and whether its c dt/h exceeds the spectral limit of its layout (a fixed step is "
        "above it from the start or never). Each warning is given with how many steps it comes "
        "before the failure. The claims also count the same signals in the fixed-step runs of the "
        "study that reach T: a warning that also fires there does not tell a failure apart.\n\n"
     << warning_table(w);
  StudyReport report;
  report.markdown = md.str();
  report.data_csv = energy_data(rows, ctx.outcome, cells, ctx.csv_header);
  report.claims = energy_claims(rows, cells, sweeps, w);
  return report;
}

std::string energy_subtitle(const Spec&, const ojson& doc) {
  int n = 0;
  for (const auto& r : doc["cases"])
    n += r["policy"].get<std::string>() == "fixed" && !RunRow(r).outcome.empty() &&
         RunRow(r).survived();
  return std::to_string(n) + " fixed-step runs that reach T";
}

std::string energy_index(const Spec& spec, const std::vector<ojson>& rows) {
  const auto w = warnings(rows, SweepOutcome{});
  int energy = 0, failed = 0, false_warnings = 0, survived = 0;
  for (const auto& x : w) {
    failed += x.failed;
    survived += !x.failed;
    energy += x.failed && x.energy_step && *x.energy_step < x.failure_step;
    false_warnings += !x.failed && x.energy_step.has_value();
  }
  std::ostringstream md;
  md << "![" << spec.title << "](" << spec.name << ".png)\n\n**What it shows.** The energy balance "
     << "of each transfer and update order over time, its drift against dt and h, and, for "
     << failed << " failing runs, how early the balance (it leaves its band before " << energy
     << " of " << failed << " failures, and also in " << false_warnings << " of " << survived
     << " runs that reach T), eq. (108) and the spectral limit warn: [" << spec.name << ".md]("
     << spec.name << ".md).\n\n";
  return md.str();
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
}  // namespace studies::energy

}  // namespace mpmstab
