// The eq108 study: every reading of eq. (108) that its two documented ambiguities allow (the
// stress scaled by 1/sqrt(E) or not, the nodal velocity norm Euclidean or maximum) on the Table 1
// cells, each set against the paper's dt stable column; and the same cells run on another grid
// than the paper's bar (h = 1 / cells), each set against the same column.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "base/accuracy.hpp"
#include "claims.hpp"
#include "csv.hpp"
#include "report_util.hpp"
#include "run_row.hpp"
#include "shared/paper_table1.hpp"
#include "study.hpp"

namespace mpmstab::studies::eq108 {
namespace {

using ojson = nlohmann::ordered_json;

// A reading of eq. (108): "scaled, l2".
std::string reading_of(const ojson& r) {
  return text(r, "dt_stable_sigma") + ", " + text(r, "dt_stable_vnorm");
}

// One run of a cell: our flat row, and our bound / the paper's dt stable where they are compared.
struct Run {
  const ojson* row = nullptr;
  std::optional<double> ratio;
};

// One Table 1 cell: the paper's value and our run under each reading (in the spec's order).
struct Eq108Cell {
  const CaseSpec* spec = nullptr;    // the first case of the cell
  const PaperCell* paper = nullptr;  // in Findings::paper
  std::vector<Run> runs;
  const Eq108Cell* on_paper_grid = nullptr;  // on another grid, the cell on the paper's grid
};

// The cells of the study: each Table 1 cell with its paper row and its run under each reading,
// and the readings in the order the rows give them.
struct Eq108Cells {
  std::vector<std::string> readings;
  std::vector<Eq108Cell> cells;
};
// Only the cases on `grid` cells.
Eq108Cells eq108_cells(const Spec& spec, const std::vector<ojson>& rows,
                       const std::map<Table1Key, PaperCell>& paper, int grid) {
  Eq108Cells out;
  std::map<Table1Key, std::size_t> index;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (spec.cases[i].params.cells != grid) continue;
    const std::string reading = reading_of(rows[i]);
    add_unique(out.readings, reading);
    const Table1Key key = paper_key(spec.cases[i]);
    auto [it, fresh] = index.try_emplace(key, out.cells.size());
    if (fresh) {
      const auto p = paper.find(key);
      out.cells.push_back({&spec.cases[i], p == paper.end() ? nullptr : &p->second, {}});
    }
    // Our bound / the paper's dt stable where both are numbers and our run ended stable (a
    // meaningless run's bound is shown, not compared), as the comparison counts it.
    Eq108Cell& cell = out.cells[it->second];
    const bool compared = cell.paper && cell.paper->dt_stable.kind == PaperValue::number &&
                          outcome(rows[i]) == "stable" && has_number(rows[i], "dt_stable_min");
    cell.runs.push_back({&rows[i], compared ? std::optional(rows[i]["dt_stable_min"].get<double>() /
                                                            cell.paper->dt_stable.value)
                                            : std::nullopt});
  }
  return out;
}

// The grid of the paper's bar (Table 1's runs): the default cells.
const int kPaperGrid = RunParams{}.cells;

// The run of a cell under `reading`, if the cell has one.
const Run* run_of(const Eq108Cell& cell, const std::string& reading) {
  const auto run = std::find_if(cell.runs.begin(), cell.runs.end(),
                                [&](const Run& r) { return reading_of(*r.row) == reading; });
  return run == cell.runs.end() ? nullptr : &*run;
}

// Ours / paper over the compared runs (of a reading, a method, a grid): the ratios, those within
// the factor, the cells beyond it, named with the paper's value and the confidence of its
// transcription ("mpm E = 4, A = 0.05, dt = 1.2e-3 (0.08 times the paper's 5.0e-2, transcribed
// with low confidence)"), and the runs; on another grid, the same reading's ratios on the paper's.
struct Stats {
  std::vector<double> ratios, within, paper_grid_ratios;
  std::vector<std::string> outside;
  std::vector<const ojson*> rows;
};

// Adds a compared run of `cell` to `s`.
void add(Stats& s, const Eq108Cell& cell, const Run& run) {
  const RunParams& p = cell.spec->params;
  s.ratios.push_back(*run.ratio);
  s.rows.push_back(run.row);
  if (within_agreement_factor((*run.row)["dt_stable_min"].get<double>(),
                              cell.paper->dt_stable.value)) {
    s.within.push_back(*run.ratio);
    return;
  }
  s.outside.push_back(std::string(to_string(p.method)) + " E = " + shortest(p.E) +
                      ", A = " + shortest(p.A) + ", dt = " + param(p.dt) + " (" +
                      ratio(*run.ratio) + " times the paper's " + show(cell.paper->dt_stable) +
                      ", transcribed with " + cell.paper->confidence + " confidence)");
}

// One reading on the paper's grid: per method, over every method, and the mean |ln(ours /
// paper)| over every method's cells.
struct Reading {
  std::string name;
  std::map<std::string, Stats> by_method;
  Stats all;
  double mean_log_distance = 0;
};

// Another grid than the paper's: its cells, and per reading its Stats.
struct Grid {
  int cells = 0;
  Eq108Cells on;
  std::map<std::string, Stats> by_reading;
};

// Every reading on the paper's grid, the best of them (the most cells within the agreement
// factor, ties broken by the smallest mean |ln(ours / paper)|), and every other grid.
struct Findings {
  std::map<Table1Key, PaperCell> paper;  // the paper's table, which every cell points into
  Eq108Cells cells;                      // on the paper's grid
  std::vector<Reading> readings;
  std::size_t best = 0;  // in readings
  std::vector<Grid> grids;
};

// The findings from the rows (rows[i] is spec.cases[i]) and the paper's table.
Findings find(const Spec& spec, const std::vector<ojson>& rows) {
  Findings f{.paper = read_paper_table1(spec)};
  f.cells = eq108_cells(spec, rows, f.paper, kPaperGrid);
  for (const std::string& name : f.cells.readings) {
    Reading r{.name = name};
    for (const Eq108Cell& cell : f.cells.cells) {
      if (const Run* run = run_of(cell, name); run && run->ratio) {
        add(r.by_method[std::string(to_string(cell.spec->params.method))], cell, *run);
        add(r.all, cell, *run);
      }
    }
    double sum = 0;  // the mean |ln(ours / paper)|, infinite over no cell
    for (const double q : r.all.ratios)
      sum += std::abs(std::log(q));
    r.mean_log_distance =
        r.all.ratios.empty() ? std::numeric_limits<double>::infinity() : sum / r.all.ratios.size();
    const Reading* best = f.readings.empty() ? nullptr : &f.readings[f.best];
    const std::size_t within = r.all.within.size();
    if (best &&
        (within > best->all.within.size() ||
         (within == best->all.within.size() && r.mean_log_distance < best->mean_log_distance)))
      f.best = f.readings.size();
    f.readings.push_back(std::move(r));
  }
  // Each other grid: each run set against the paper, beside the same cell and reading on the
  // paper's grid.
  std::set<int> grids;  // the other grids, smallest first
  for (const CaseSpec& c : spec.cases)
    if (c.params.cells != kPaperGrid) grids.insert(c.params.cells);
  for (const int grid : grids) {
    Grid& g = f.grids.emplace_back(Grid{grid, eq108_cells(spec, rows, f.paper, grid), {}});
    for (Eq108Cell& cell : g.on.cells) {
      const auto& on = f.cells.cells;  // the same Table 1 cell on the paper's grid
      const auto it = std::find_if(on.begin(), on.end(), [&](const Eq108Cell& c) {
        return paper_key(*c.spec) == paper_key(*cell.spec);
      });
      cell.on_paper_grid = it == on.end() ? nullptr : &*it;
      for (const Run& run : cell.runs) {
        const std::string reading = reading_of(*run.row);
        const Run* paper_run = cell.on_paper_grid ? run_of(*cell.on_paper_grid, reading) : nullptr;
        Stats& s = g.by_reading[reading];
        if (paper_run && paper_run->ratio) s.paper_grid_ratios.push_back(*paper_run->ratio);
        if (run.ratio) add(s, cell, run);
      }
    }
  }
  return f;
}

// The claim of the paper's grid: the best reading gives the paper's column within the factor.
Claim reading_claim(const Findings& f) {
  const Reading best = f.readings.empty() ? Reading{} : f.readings[f.best];
  return claim("a-reading-gives-the-paper",
               "Some reading of eq. (108) on the paper's {cells} cells gives the paper's "
               "dt stable column within a factor {k} in every cell where both are measured",
               "the best reading ({best}: the most cells within it, ties broken by the "
               "smallest mean absolute natural log of ours / paper, here {distance}) is within "
               "it in {within} of {n} cells; its ratios {span}")
      .count("cells", kPaperGrid)
      .value("k", agreement_factor())
      .value("best", best.name)
      .every("within", static_cast<long long>(best.all.within.size()), "n",
             static_cast<long long>(best.all.ratios.size()))
      .value("span", span(best.all.ratios, 2))
      .number("distance", best.mean_log_distance, 3)
      .on(coverage_of(best.all.rows));
}

// The claim of one reading on another grid, over every method: every compared cell within the
// factor; beside it the ratios of the cells within it and the cells beyond it.
Claim grid_claim(const Grid& g, const std::string& reading, const Stats& s) {
  auto spans = [](const std::vector<double>& v) { return v.empty() ? "–" : span(v, 2); };
  const std::string evidence =
      "{within} of {n} cells, ratios {span}, in those within it {within_span} (on {paper_cells} "
      "cells {paper_span} in {paper_n} cells)";
  std::string slug = reading;  // "scaled, l2" -> "scaled-l2"
  if (const auto comma = slug.find(", "); comma != std::string::npos) slug.replace(comma, 2, "-");
  Claim c = claim("grid-" + std::to_string(g.cells) + "-" + slug + "-gives-the-paper",
                  "On {cells} cells (h = {h}) instead of the paper's {paper_cells}, eq. (108) "
                  "({reading}) gives the paper's dt stable column within a factor {k} in every "
                  "cell where both are measured",
                  s.outside.empty() ? evidence : evidence + "; beyond it: {outside}");
  if (!s.outside.empty()) c.value("outside", list_of(s.outside));
  return c.count("cells", g.cells)
      .value("h", shortest(1.0 / g.cells))
      .count("paper_cells", kPaperGrid)
      .value("reading", reading)
      .value("k", agreement_factor())
      .every("within", static_cast<long long>(s.within.size()), "n",
             static_cast<long long>(s.ratios.size()))
      .value("span", spans(s.ratios))
      .value("within_span", spans(s.within))
      .value("paper_span", spans(s.paper_grid_ratios))
      .count("paper_n", static_cast<long long>(s.paper_grid_ratios.size()))
      .on(coverage_of(s.rows));
}

// A run's bound as the tables show it: the number where it ended stable, the number marked where
// meaningless, the failure otherwise.
std::string bound_text(const ojson& r) {
  const std::string o = outcome(r);
  return o == "stable"        ? opt_sci(r["dt_stable_min"])
         : o == "meaningless" ? opt_sci(r["dt_stable_min"]) + " (meaningless)"
                              : verdict(r);
}

// The error over time / A and the accuracy class of a run that reached T; dashes otherwise.
std::string accuracy_columns(const ojson& r) {
  const RunRow run(r);
  if (!run.survived() || !run.error_over_A()) return "– | –";
  return sci(*run.error_over_A()) + " | " + std::string(to_string(*run.accuracy()));
}

// A cell's columns, its c dt/h from `row`: "| gimp | 4 | 0.05 | 1e-3 | 2.0e-2 | 0.5 | 2 | 1.2e-3
// |".
std::string cell_columns(const Eq108Cell& cell, const ojson& row) {
  const RunParams& p = cell.spec->params;
  return "| " + std::string(to_string(p.method)) + " | " + shortest(p.E) + " | " + shortest(p.A) +
         " | " + param(p.dt) + " | " + sci(RunRow(row).courant.value()) + " | " +
         significant(amplitude_per_cell(p), 3) + " | " + significant(wave_passes(p), 3) + " | " +
         (cell.paper ? show(cell.paper->dt_stable) : "–") + " |";
}

// A run's bound and its ratio to the paper: " 4.8e-6 | 0.12 |"; dashes without a run.
std::string bound_columns(const Run* run) {
  return " " + (run ? bound_text(*run->row) : "–") + " | " +
         (run && run->ratio ? ratio(*run->ratio) : "–") + " |";
}

// The table of every cell of the paper's grid under every reading.
std::string eq108_table(const Eq108Cells& e) {
  std::ostringstream table;
  table << "| method | E | A | dt | c dt/h | A/h | c T | paper's dt stable |";
  for (const auto& r : e.readings)
    table << " ours (" << r << ") | ratio |";
  table << "\n|---|---|---|---|---|---|---|---|" << rule_cells(2 * e.readings.size()) << "\n";
  for (const auto& cell : e.cells) {
    table << cell_columns(cell, *cell.runs.front().row);
    for (const auto& reading : e.readings)
      table << bound_columns(run_of(cell, reading));
    table << "\n";
  }
  return table.str();
}

// The cells run on another grid, each under its reading, beside the paper and beside the same
// cell and reading on the paper's grid.
void other_grid_section(std::ostream& md, const Grid& g) {
  const double h = 1.0 / g.cells, paper_h = 1.0 / kPaperGrid;
  md << "\n## On " << g.cells << " cells\n\nEach cell run again on " << g.cells
     << " cells (h = " << shortest(h) << ", where the paper's bar has " << kPaperGrid
     << " cells, h = " << shortest(paper_h)
     << ") at the same E, A and dt, under the reading named: eq. (108) evaluated with the "
        "coarser grid's h on the coarser grid's runs. *ratio* is ours / the paper's dt stable, "
        "compared as above; before it the same cell and reading on "
     << kPaperGrid
     << " cells. A run reported stable has its error over time / A and accuracy class beside "
        "it; the Conclusions above count its rows over every method.\n\n| method | E | A | dt "
        "| c dt/h | A/h | c T | paper's dt stable | reading | ours on "
     << kPaperGrid << " cells | ratio | ours on " << g.cells
     << " cells | ratio | error over time / A | accuracy |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Eq108Cell& cell : g.on.cells) {
    for (const Run& run : cell.runs) {
      const std::string reading = reading_of(*run.row);
      md << cell_columns(cell, *run.row) << " " << reading << " |"
         << bound_columns(cell.on_paper_grid ? run_of(*cell.on_paper_grid, reading) : nullptr)
         << bound_columns(&run) << " " << accuracy_columns(*run.row) << " |\n";
    }
  }
}

StudyReport eq108_report(const ReportContext& c) {
  const Findings f = find(c.spec, c.rows);
  std::ostringstream md;
  md << "## Results\n\nEach Table 1 cell run on the paper's grid of " << kPaperGrid
     << " cells under every reading of eq. (108) (docs/theory.md, \"The paper's bound, "
        "eq. (108)\"); *ours* is the minimum of the bound over the run, compared with the paper's "
        "dt stable where our run ended stable (a meaningless run's bound is shown, not compared) "
        "and the paper prints a number; *ratio* is ours / paper.\n\n**Reading.** ";
  for (const Reading& r : f.readings) {
    md << r.name << ": ";
    for (const auto& [method, s] : r.by_method)
      md << (method == r.by_method.begin()->first ? "" : "; ") << method << " " << span(s.ratios, 2)
         << " times the paper (" << s.within.size() << " of " << s.ratios.size()
         << " within a factor " << agreement_factor() << ")";
    md << ". ";
  }
  md << "\n\n" << eq108_table(f.cells);
  std::vector<Claim> claims = {reading_claim(f)};
  for (const Grid& g : f.grids) {
    other_grid_section(md, g);
    for (const auto& [reading, s] : g.by_reading)
      claims.push_back(grid_claim(g, reading, s));
  }
  return StudyReport{.markdown = md.str(), .claims = claims};
}

std::string eq108_index(const Spec& spec, const std::vector<ojson>& rows, const ojson&) {
  std::string grids;
  for (const Grid& g : find(spec, rows).grids)
    grids +=
        ", and on " + std::to_string(g.cells) + " cells instead of " + std::to_string(kPaperGrid);
  return "**What it shows.** Each reading of eq. (108) on the Table 1 cells" + grids +
         ", set against the paper's dt stable column: [" + spec.name + ".md](" + spec.name +
         ".md).\n\n";
}

const StudyRegistration kEq108{{
    .name = "eq108",
    .summary = "every reading of eq. (108) on the Table 1 cells, against the paper's dt stable",
    .needs_reference = true,
    .records = {.dt_stable = true},
    .report = eq108_report,
    .index = eq108_index,
}};

}  // namespace
}  // namespace mpmstab::studies::eq108
