// Choosing a method: one row per method (basis x velocity transfer x update order) with the
// error at Table 1's setting, the orders in h and dt, the survival and accuracy edges at a tiny
// amplitude and the counted work per particle-step. It measures and recommends nothing: every
// recommendation is advice.md's (advice.hpp). The edges are this study's own cases (edge
// searches); everything else comes from the rows of methods_grid, which it reads.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>

#include "analysis/spectral.hpp"
#include "csv.hpp"
#include "report_util.hpp"
#include "step/simulation.hpp"
#include "study.hpp"

namespace mpmstab {

namespace {

using ojson = nlohmann::ordered_json;

// What identifies a method in a row: basis, wall treatment, transfer and its order, update.
using MethodKey = std::tuple<std::string, std::string, std::string, int, std::string>;
MethodKey key_of(const ojson& r) {
  const std::string transfer = r["transfer"].get<std::string>();
  int order = 0;
  if (transfer == "xpic" && has_number(r, "xpic_order")) order = r["xpic_order"].get<int>();
  if (transfer == "fmpm" && has_number(r, "fmpm_order")) order = r["fmpm_order"].get<int>();
  return {r["method"].get<std::string>(), r["walls"].get<std::string>(), transfer, order,
          r["update"].get<std::string>()};
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

struct MethodRow {
  MethodKey key;
  const ojson* edge = nullptr;    // this study's edge search
  const ojson* table1 = nullptr;  // methods_grid: 100 cells, dt = 1e-4
  std::vector<const ojson*> grid;
  std::optional<double> order_h, order_dt;
};

// Table 1's setting among the rows of methods_grid: the paper's grid at its smallest fixed dt.
constexpr int kTable1Cells = 100;
constexpr double kTable1Dt = 1e-4;
// The order in h is fitted over the CFL runs at this Courant number (the smallest the grid
// sweeps: the time error least visible); the order in dt over every run on Table 1's grid.
constexpr double kOrderHCourant = 0.2;

bool is_table1_setting(const ojson& r) {
  return r["policy"].get<std::string>() == "fixed" && r["cells"].get<int>() == kTable1Cells &&
         has_number(r, "dt") && r["dt"].get<double>() == kTable1Dt;
}

std::optional<double> error_of(const ojson& r) {
  if (outcome(r) != "stable" || !has_number(r, "max_error")) return std::nullopt;
  return r["max_error"].get<double>();
}

// The error over time (max over steps and particles) of a stable run: what the orders are fitted
// to and the methods are ranked by; the error at T is shown, never fitted (docs/design.md,
// "Orders of convergence").
std::optional<double> over_time_of(const ojson& r) {
  if (outcome(r) != "stable" || !has_number(r, "max_error_over_time")) return std::nullopt;
  return r["max_error_over_time"].get<double>();
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
      const auto e = over_time_of(*r);
      const bool cfl = (*r)["policy"].get<std::string>() == "cfl";
      const bool finest_dt = cfl && (*r)["cfl_factor"].get<double>() == kOrderHCourant;
      // Orders only in their regime (report_util.hpp): accurate runs, and for h no crossing.
      if (e && finest_dt && accurate_run(*r) && crossing_free(*r))
        h_points.emplace_back(1.0 / (*r)["cells"].get<double>(), *e);
      // The order in dt is that of the convergent scheme: not from a run above its limit.
      const bool below_limit =
          !has_number(*r, "courant_spectral") ||
          (*r)["courant"].get<double>() <= (*r)["courant_spectral"].get<double>();
      if (e && below_limit && accurate_run(*r) && (*r)["cells"].get<int>() == kTable1Cells)
        dt_points.emplace_back(dt_of(*r), *e);
    }
    m.order_h = loglog_slope(h_points);
    m.order_dt = loglog_slope(dt_points);
  }
  return rows;
}

std::string order_text(const std::optional<double>& o) {
  return o ? fixed(*o, 2) : std::string("–");
}

std::string edge_text(const ojson& r, const char* column) {
  return has_number(r, column) ? fixed(r[column].get<double>(), 3) : std::string("none");
}

std::string table1_text(const MethodRow& m) {
  if (!m.table1) return "–";
  const auto e = error_of(*m.table1);
  return e ? sci(*e) : verdict(*m.table1);
}

// The error over time and the energy balance error at Table 1's setting ("–" where the run did
// not end stable: its verdict is in the column before).
std::string table1_over_time(const MethodRow& m) {
  const auto e = m.table1 ? over_time_of(*m.table1) : std::nullopt;
  return e ? sci(*e) : "–";
}
std::string table1_energy(const MethodRow& m) {
  if (!m.table1 || outcome(*m.table1) != "stable" || !has_number(*m.table1, "energy_error_max"))
    return "–";
  return sci((*m.table1)["energy_error_max"].get<double>());
}

std::string method_name(const MethodRow& m) {
  return basis_text(m.key) + " / " + transfer_text(m.key) + " / " + std::get<4>(m.key);
}

// The reading: facts of the table, every number from its rows.
std::string reading(const std::vector<MethodRow>& rows) {
  const MethodRow* best_error = nullptr;
  const MethodRow* widest = nullptr;  // among the edges whose run is not meaningless
  std::size_t unstable_table1 = 0, meaningless_edges = 0, edges = 0;
  for (const auto& m : rows) {
    const auto e = m.table1 ? over_time_of(*m.table1) : std::nullopt;
    if (!e) ++unstable_table1;
    if (e && (!best_error || *e < *over_time_of(*best_error->table1))) best_error = &m;
    if (!has_number(*m.edge, "dt_edge_over_cfl")) continue;
    ++edges;
    if (outcome(*m.edge) == "meaningless") {
      ++meaningless_edges;
      continue;
    }
    if ((!widest || (*m.edge)["dt_edge_over_cfl"].get<double>() >
                        (*widest->edge)["dt_edge_over_cfl"].get<double>())) {
      widest = &m;
    }
  }
  std::ostringstream md;
  md << "Of " << rows.size() << " methods, " << rows.size() - unstable_table1
     << " end stable at Table 1's setting";
  if (best_error) {
    md << "; the smallest error over time there is " << sci(*over_time_of(*best_error->table1))
       << " (" << method_name(*best_error) << ")";
  }
  md << ". ";
  md << "Of " << edges << " survival edges at the tiny amplitude, " << meaningless_edges
     << " are runs whose error over time reached A (meaningless: marked in the table and the "
        "figure)";
  if (widest) {
    md << "; the widest of the others is "
       << fixed((*widest->edge)["dt_edge_over_cfl"].get<double>(), 3) << " h/c ("
       << method_name(*widest) << "), a run of this length only: an edge is not a recommended "
       << "step";
  }
  md << ".";
  return md.str();
}

// The cells per wavelength each scheme needs for a 1% phase error at kDispersionCourant, from the
// dispersion study (its Bloch symbol; USL only), by the scheme's label ("gimp/xpic(2)").
constexpr double kDispersionCourant = 0.5;
struct CellsPerWavelength {
  std::map<std::string, double> by_label;
  double tolerance = 0;  // the phase error, as a fraction (0 when not read)
};
CellsPerWavelength cells_per_wavelength(const StudyInputs& inputs) {
  CellsPerWavelength out;
  const auto it = inputs.find("dispersion");
  if (it == inputs.end() || !it->second.present()) return out;
  const ojson& study = it->second.doc["study"];
  if (!study.is_object() || !study.contains("cells_per_wavelength") ||
      !study["phase_tolerance"].is_number())
    return out;
  out.tolerance = study["phase_tolerance"].get<double>();
  for (const auto& e : study["cells_per_wavelength"]) {
    if (!e["courant"].is_number() || e["courant"].get<double>() != kDispersionCourant ||
        !e["cells_per_wavelength_1pct"].is_number() || e["update"] != "usl")
      continue;
    out.by_label[e["method"].get<std::string>()] = e["cells_per_wavelength_1pct"].get<double>();
  }
  return out;
}

std::string cells_per_wavelength_text(const MethodRow& m, const CellsPerWavelength& cpw) {
  const auto& [method, walls, transfer, order, update] = m.key;
  if (update != "usl") return "–";
  std::string label = method;
  if (transfer != "flip") {
    label += '/';
    label += transfer_text(m.key);
  }
  const auto it = cpw.by_label.find(label);
  return it == cpw.by_label.end() ? "–" : fixed(it->second, 1);
}

std::string methods_table(const std::vector<MethodRow>& rows, const CellsPerWavelength& cpw) {
  std::ostringstream md;
  const std::string phase = cpw.tolerance > 0 ? shortest(100 * cpw.tolerance) + "%" : "given";
  md << "| basis | transfer | update | error at T at Table 1's setting | error over time there | "
        "energy balance error there | cells per wavelength for a "
     << phase
     << " phase error | order in h | order in dt | "
        "spectral limit (h/c) | survival edge (h/c) | accuracy edge (h/c) | node visits per "
        "particle-step |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& m : rows) {
    md << "| " << basis_text(m.key) << " | " << transfer_text(m.key) << " | " << std::get<4>(m.key)
       << " | " << table1_text(m) << " | " << table1_over_time(m) << " | " << table1_energy(m)
       << " | " << cells_per_wavelength_text(m, cpw) << " | " << order_text(m.order_h) << " | "
       << order_text(m.order_dt) << " | " << edge_text(*m.edge, "courant_spectral") << " | "
       << edge_text(*m.edge, "dt_edge_over_cfl");
    if (has_number(*m.edge, "dt_edge") && outcome(*m.edge) == "meaningless") md << " (meaningless)";
    md << " | " << edge_text(*m.edge, "dt_accurate_over_cfl") << " | " << node_visits(m.key)
       << " |\n";
  }
  return md.str();
}

std::vector<ojson> grid_rows(const StudyInputs& inputs) {
  const StudyInput& in = inputs.at("methods_grid");
  if (!in.present()) return {};
  return std::vector<ojson>(in.doc["cases"].begin(), in.doc["cases"].end());
}

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
    const auto e = m.table1 ? over_time_of(*m.table1) : std::nullopt;
    if (!e || !has_number(*m.edge, "dt_edge_over_cfl")) continue;
    csv << index_in(kUpdates, std::get<4>(m.key)) << ',' << index_in(kBases, basis_text(m.key))
        << ',' << index_in(kTransfers, transfer_text(m.key)) << ','
        << shortest((*m.edge)["dt_edge_over_cfl"].get<double>()) << ',' << shortest(*e) << ','
        << (outcome(*m.edge) == "meaningless" ? 1 : 0) << '\n';
  }
  return csv.str();
}

// How the error at Table 1's setting and the orders are measured, every number from the rows
// of methods_grid that give them.
std::string how_to_read_the_setting(const std::vector<ojson>& grid) {
  std::vector<ojson> table1, h_runs, cfl_runs, fixed_runs;
  for (const auto& r : grid) {
    const bool cfl = r["policy"].get<std::string>() == "cfl";
    if (is_table1_setting(r)) table1.push_back(r);
    if (cfl && r["cfl_factor"].get<double>() == kOrderHCourant) h_runs.push_back(r);
    if (r["cells"].get<int>() != kTable1Cells) continue;
    (cfl ? cfl_runs : fixed_runs).push_back(r);
  }
  std::ostringstream md;
  md << "- *error at T at Table 1's setting*: max_p |u_p - u(X_p, T)| at T = "
     << listing(table1, "T") << " on the bar, E = " << listing(table1, "E")
     << ", A = " << listing(table1, "A") << ", " << kTable1Cells << " cells x "
     << listing(table1, "ppc") << " particles, dt = " << param(kTable1Dt)
     << " (the verdict where the run did not end stable), shown, never fitted; *error over time "
        "there*: the largest such error after any step; *energy balance error there*: the largest "
        "balance error of the particles' kinetic and strain energy and the body force's work, per "
        "the initial energy (docs/design.md, \"Energy\");\n"
     << "- *order in h*: least-squares slope of log(error over time) against log(h) over "
     << listing(h_runs, "cells") << " cells at C = c dt / h = " << shortest(kOrderHCourant)
     << "; *order in dt*: against log(dt), over the runs below the scheme's spectral limit, on "
     << kTable1Cells << " cells over C = " << listing(cfl_runs, "cfl_factor")
     << " and dt = " << listing(fixed_runs, "dt") << " (C = " << listing(fixed_runs, "courant")
     << "); " << order_regime_text()
     << " (`–` otherwise; convergence.md fits orders in h at an amplitude at which no particle "
        "crosses a cell). An order in dt near zero means the grid's error hides the time "
        "error;\n";
  return md.str();
}

StudyReport methods_report(const ReportContext& c) {
  const std::vector<ojson> grid = grid_rows(c.inputs);
  const auto rows = method_rows(c.rows, grid);
  std::ostringstream md;
  md << "## Results\n\n**Reading.** " << reading(rows) << "\n\n"
     << "This table measures; it does not recommend: every recommendation of this project is "
        "made in [advice.md](advice.md), from settings checked at the corners of a stated "
        "region.\n\n"
     << cost_metric_text() << "\n\n![" << c.spec.title << "](" << c.spec.name
     << ".png)\n\nThe figure places each method by its survival edge at the tiny "
     << "amplitude (x) and its error over time at Table 1's setting (y), one panel per update "
        "order; a "
     << "method unstable at that setting or without an edge is left out. Vector version: ["
     << c.spec.name << ".svg](" << c.spec.name << ".svg); data: [" << c.spec.name << "_data.csv]("
     << c.spec.name << "_data.csv).\n\n"
     << "How to read a row:\n\n"
     << how_to_read_the_setting(grid)
     << "- *cells per wavelength for a phase error*: the smallest number of cells per "
        "wavelength above which the scheme's phase speed stays within the dispersion study's "
        "tolerance of c, at c dt / h = "
     << shortest(kDispersionCourant)
     << ", from its Bloch symbol ([dispersion.md](dispersion.md); USL only: `–` for USF and MUSL, "
        "and for every row when the dispersion study was not run);\n"
     << "- *spectral limit*: the largest c dt / h at which the scheme's map, linearised about "
        "rest at the uniform layout, amplifies nothing: the Bloch limit of the interior "
        "(docs/design.md, \"The spectral limit\"; the walls' treatment does not enter it; "
        "spectral.md checks each by runs); `none` when nothing amplifies up to "
     << shortest(kMaxSpectralCourant) << ";\n"
     << "- *survival edge*: the largest fixed dt with which the bar at A = " << listing(c.rows, "A")
     << ", E = " << listing(c.rows, "E") << " survives to T = " << listing(c.rows, "T")
     << ", in units of h/c; *accuracy edge*: the largest dt up to which its error stays within "
     << shortest(c.spec.study->edge.accuracy_factor)
     << " times that of the smallest dt that survives (the edge study's rules);\n"
     << "- *node visits per particle-step*: the nodes of the stencil times the passes over it "
        "that one step makes (counted from the code: p2g, g2p and the stress update, plus what "
        "the update order and the transfer add), what makes one particle-step of a method dearer "
        "than another's; the measured time per particle-step is in performance.md.\n\n";
  if (grid.empty()) {
    md << "methods_grid has not been run into this folder: the columns it provides are `–`.\n\n";
  }
  md << methods_table(rows, cells_per_wavelength(c.inputs));
  return StudyReport{.markdown = md.str(), .data_csv = methods_data(rows, c.csv_header)};
}

std::string methods_index(const Spec& spec, const std::vector<ojson>& rows) {
  std::ostringstream md;
  md << "![" << spec.title << "](" << spec.name << ".png)\n\n**What it shows.** " << rows.size()
     << " methods (basis x transfer x update order), each with its error, orders, edges and "
        "work per particle-step; the recommendations are advice.md's. Details: ["
     << spec.name << ".md](" << spec.name << ".md).\n\n";
  return md.str();
}

std::string methods_subtitle(const Spec&, const ojson& doc) {
  std::size_t n = 0;
  for (const auto& r : doc["cases"])
    n += has_number(r, "dt_edge_over_cfl") ? 1 : 0;
  const std::vector<ojson> rows(doc["cases"].begin(), doc["cases"].end());
  return std::to_string(n) + " methods with a survival edge; E = " + listing(rows, "E") + ", " +
         listing(rows, "cells") + " cells";
}

const StudyRegistration kMethods{{
    .name = "methods",
    .summary = "one row per method: error, orders, tiny-amplitude edges, work per particle-step",
    .work = CaseWork::edge_search,
    .inputs = {{.name = "methods_grid", .required = true}, {.name = "dispersion"}},
    .figure = true,
    .report = methods_report,
    .index = methods_index,
    .figure_subtitle = methods_subtitle,
}};

}  // namespace

}  // namespace mpmstab
