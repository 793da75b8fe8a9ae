// The eq108 study: every reading of eq. (108) that its two documented ambiguities allow (the
// stress scaled by 1/sqrt(E) or not, the nodal velocity norm Euclidean or maximum) on the Table 1
// cells, each set against the paper's dt stable column; and the same cells run on another grid
// than the paper's bar (h = 1 / cells), each set against the same column.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
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

StudyReport eq108_report(const ReportContext& c);
std::string eq108_index(const Spec& spec, const std::vector<ojson>& rows);

const StudyRegistration kEq108{{
    .name = "eq108",
    .summary = "every reading of eq. (108) on the Table 1 cells, against the paper's dt stable",
    .needs_reference = true,
    .records = {.dt_stable = true},
    .report = eq108_report,
    .index = eq108_index,
}};

// A reading of eq. (108): "scaled, l2".
std::string reading_of(const ojson& r) {
  return text(r, "dt_stable_sigma") + ", " + text(r, "dt_stable_vnorm");
}

// One run of a cell: our flat row, and our bound / the paper's dt stable where they are compared
// (bound_ratio()).
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

// Our bound / the paper's dt stable where both are numbers and our run ended stable (a
// meaningless run's bound is shown, not compared), as the comparison counts it.
std::optional<double> bound_ratio(const Eq108Cell& c, const ojson& r) {
  if (!c.paper || c.paper->dt_stable.kind != PaperValue::number || outcome(r) != "stable" ||
      !has_number(r, "dt_stable_min"))
    return std::nullopt;
  return r["dt_stable_min"].get<double>() / c.paper->dt_stable.value;
}

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
    if (std::find(out.readings.begin(), out.readings.end(), reading) == out.readings.end())
      out.readings.push_back(reading);
    const Table1Key key = paper_key(spec.cases[i]);
    auto [it, fresh] = index.try_emplace(key, out.cells.size());
    if (fresh) {
      const auto p = paper.find(key);
      out.cells.push_back({&spec.cases[i], p == paper.end() ? nullptr : &p->second, {}});
    }
    Eq108Cell& cell = out.cells[it->second];
    cell.runs.push_back({&rows[i], bound_ratio(cell, rows[i])});
  }
  return out;
}

// The grid of the paper's bar (Table 1's runs): the default cells.
const int kPaperGrid = RunParams{}.cells;

// The cells of the cases on another grid than the paper's, in the order the spec first has them.
std::vector<int> other_grids(const Spec& spec) {
  std::vector<int> grids;
  for (const CaseSpec& c : spec.cases)
    if (c.params.cells != kPaperGrid &&
        std::find(grids.begin(), grids.end(), c.params.cells) == grids.end())
      grids.push_back(c.params.cells);
  return grids;
}

// The run of a cell under `reading`, if the cell has one.
const Run* run_of(const Eq108Cell& cell, const std::string& reading) {
  const auto run = std::find_if(cell.runs.begin(), cell.runs.end(),
                                [&](const Run& r) { return reading_of(*r.row) == reading; });
  return run == cell.runs.end() ? nullptr : &*run;
}

// The same Table 1 cell (method, E, A, dt) among `cells`.
const Eq108Cell* same_cell(const std::vector<Eq108Cell>& cells, const Eq108Cell& cell) {
  const RunParams& p = cell.spec->params;
  const auto it = std::find_if(cells.begin(), cells.end(), [&](const Eq108Cell& c) {
    const RunParams& q = c.spec->params;
    return q.method == p.method && q.E == p.E && q.A == p.A && q.dt == p.dt;
  });
  return it == cells.end() ? nullptr : &*it;
}

// A compared cell beyond the agreement factor, with the paper's value and the confidence of its
// transcription: "E = 4, A = 0.05, dt = 1.2e-3 (0.08 times the paper's 5.0e-2, transcribed with
// low confidence)".
std::string outside_text(const Eq108Cell& cell, double q) {
  const RunParams& p = cell.spec->params;
  return "E = " + shortest(p.E) + ", A = " + shortest(p.A) + ", dt = " + param(p.dt) + " (" +
         ratio(q) + " times the paper's " + show(cell.paper->dt_stable) + ", transcribed with " +
         cell.paper->confidence + " confidence)";
}

// Per reading and method: ours / paper over the cells where both are measured, how many within
// the factor and the cells beyond it; on another grid, the same reading's ratios on the paper's.
struct Stats {
  std::vector<double> ratios, paper_grid_ratios;
  int within = 0;
  std::vector<std::string> outside;
};

// Adds a compared run of `cell` to `s`.
void add(Stats& s, const Eq108Cell& cell, const Run& run) {
  s.ratios.push_back(*run.ratio);
  const bool within = within_agreement_factor((*run.row)["dt_stable_min"].get<double>(),
                                              cell.paper->dt_stable.value);
  s.within += within;
  if (!within) s.outside.push_back(outside_text(cell, *run.ratio));
}

// One reading on the paper's grid: per method, and over every method (the cells within the
// factor, their ratios and the mean |ln(ours / paper)|).
struct Reading {
  std::string name;
  std::map<std::string, Stats> by_method;
  int within = 0;
  std::vector<double> ratios;
  double mean_log_distance = 0;
};

double reading_log_distance(const std::vector<double>& ratios) {
  double sum = 0;
  int n = 0;
  for (const double r : ratios)
    if (r > 0) {
      sum += std::abs(std::log(r));
      ++n;
    }
  return n ? sum / n : std::numeric_limits<double>::infinity();
}

// Another grid than the paper's: its cells, and per (reading, method) its Stats.
struct Grid {
  int cells = 0;
  Eq108Cells on;
  std::map<std::pair<std::string, std::string>, Stats> stats;
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
    for (const Eq108Cell& cell : f.cells.cells)
      if (const Run* run = run_of(cell, name); run && run->ratio)
        add(r.by_method[std::string(to_string(cell.spec->params.method))], cell, *run);
    for (const auto& [method, s] : r.by_method) {
      r.within += s.within;
      r.ratios.insert(r.ratios.end(), s.ratios.begin(), s.ratios.end());
    }
    r.mean_log_distance = reading_log_distance(r.ratios);
    const Reading* best = f.readings.empty() ? nullptr : &f.readings[f.best];
    if (best && (r.within > best->within ||
                 (r.within == best->within && r.mean_log_distance < best->mean_log_distance)))
      f.best = f.readings.size();
    f.readings.push_back(std::move(r));
  }
  // Each other grid: each run set against the paper, beside the same cell and reading on the
  // paper's grid.
  for (const int grid : other_grids(spec)) {
    Grid& g = f.grids.emplace_back(Grid{grid, eq108_cells(spec, rows, f.paper, grid), {}});
    for (Eq108Cell& cell : g.on.cells) {
      cell.on_paper_grid = same_cell(f.cells.cells, cell);
      for (const Run& run : cell.runs) {
        const std::string reading = reading_of(*run.row);
        Stats& s = g.stats[{reading, std::string(to_string(cell.spec->params.method))}];
        const Run* paper_run = cell.on_paper_grid ? run_of(*cell.on_paper_grid, reading) : nullptr;
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
  Claim c = claim("a-reading-gives-the-paper",
                  "Some reading of eq. (108) on the paper's {cells} cells gives the paper's "
                  "dt stable column within a factor {k} in every cell where both are measured",
                  "the best reading ({best}: the most cells within it, ties broken by the "
                  "smallest mean absolute natural log of ours / paper, here {distance}) is within "
                  "it in {within} of {n} cells; its ratios {span}");
  c.count("cells", kPaperGrid)
      .value("k", agreement_factor())
      .value("best", best.name)
      .every("within", best.within, "n", static_cast<long long>(best.ratios.size()))
      .value("span", span(best.ratios, 2))
      .number("distance", best.mean_log_distance, 3);
  return c;
}

// The claim of one (reading, method) on `grid` cells: every compared cell within the factor.
Claim grid_claim(int grid, const std::pair<std::string, std::string>& key, const Stats& s) {
  const double h = 1.0 / grid;
  const std::string evidence =
      "{within} of {n} cells; ratios {span} (on {paper_cells} cells {paper_span} in {paper_n} "
      "cells)";
  Claim c = claim("grid-" + std::to_string(grid) + "-" + key.second + "-gives-the-paper",
                  "On {cells} cells (h = {h}) instead of the paper's {paper_cells}, eq. (108) "
                  "({reading}) gives the paper's {method} dt stable within a factor {k} in "
                  "every cell where both are measured",
                  s.outside.empty() ? evidence : evidence + "; beyond it: {outside}");
  if (!s.outside.empty()) c.value("outside", list_of(s.outside));
  c.count("cells", grid)
      .value("h", shortest(h))
      .count("paper_cells", kPaperGrid)
      .value("reading", key.first)
      .value("method", key.second == "mpm"    ? "MPM"
                       : key.second == "gimp" ? "GIMP"
                                              : key.second)
      .value("k", agreement_factor())
      .every("within", s.within, "n", static_cast<long long>(s.ratios.size()))
      .value("span", s.ratios.empty() ? std::string("–") : span(s.ratios, 2))
      .value("paper_span",
             s.paper_grid_ratios.empty() ? std::string("–") : span(s.paper_grid_ratios, 2))
      .count("paper_n", static_cast<long long>(s.paper_grid_ratios.size()));
  return c;
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

// The table of every cell of the paper's grid under every reading.
std::string eq108_table(const Eq108Cells& e) {
  std::ostringstream table;
  table << "| method | E | A | dt | c dt/h | A/h | c T | paper's dt stable |";
  for (const auto& r : e.readings)
    table << " ours (" << r << ") | ratio |";
  table << "\n|---|---|---|---|---|---|---|---|";
  for (std::size_t k = 0; k < e.readings.size(); ++k)
    table << "---|---|";
  table << "\n";
  for (const auto& cell : e.cells) {
    const RunParams& p = cell.spec->params;
    table << "| " << to_string(p.method) << " | " << shortest(p.E) << " | " << shortest(p.A)
          << " | " << param(p.dt) << " | " << sci(RunRow(*cell.runs.front().row).courant.value())
          << " | " << significant(amplitude_per_cell(p), 3) << " | "
          << significant(wave_passes(p), 3) << " | "
          << (cell.paper ? show(cell.paper->dt_stable) : "–") << " |";
    for (const auto& reading : e.readings) {
      const Run* run = run_of(cell, reading);
      table << " " << (run ? bound_text(*run->row) : "–") << " | "
            << (run && run->ratio ? ratio(*run->ratio) : "–") << " |";
    }
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
        "compared as above; beside it the same cell and reading on "
     << kPaperGrid
     << " cells. A run reported stable has its error over time / A and accuracy class beside "
        "it.\n\n**Reading.** ";
  for (const auto& [key, s] : g.stats) {
    md << key.second << " (" << key.first << ") on " << g.cells
       << " cells: " << (s.ratios.empty() ? std::string("no cell compared") : span(s.ratios, 2))
       << " times the paper (" << s.within << " of " << s.ratios.size() << " within a factor "
       << agreement_factor() << "; on " << kPaperGrid << " cells "
       << (s.paper_grid_ratios.empty() ? std::string("no cell compared")
                                       : span(s.paper_grid_ratios, 2))
       << ", " << s.paper_grid_ratios.size() << " cells)"
       << (s.outside.empty() ? std::string("") : "; beyond the factor: " + list_of(s.outside))
       << ". ";
  }
  md << "\n\n| method | E | A | dt | c dt/h | A/h | paper's dt stable | reading | ours on "
     << kPaperGrid << " cells | ratio | ours on " << g.cells
     << " cells | error over time / A | accuracy | ratio |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Eq108Cell& cell : g.on.cells) {
    const RunParams& p = cell.spec->params;
    for (const Run& run : cell.runs) {
      const std::string reading = reading_of(*run.row);
      const Run* paper_run = cell.on_paper_grid ? run_of(*cell.on_paper_grid, reading) : nullptr;
      md << "| " << to_string(p.method) << " | " << shortest(p.E) << " | " << shortest(p.A) << " | "
         << param(p.dt) << " | " << sci(RunRow(*run.row).courant.value()) << " | "
         << significant(amplitude_per_cell(p), 3) << " | "
         << (cell.paper ? show(cell.paper->dt_stable) : "–") << " | " << reading << " | "
         << (paper_run ? bound_text(*paper_run->row) : "–") << " | "
         << (paper_run && paper_run->ratio ? ratio(*paper_run->ratio) : "–") << " | "
         << bound_text(*run.row) << " | " << accuracy_columns(*run.row) << " | "
         << (run.ratio ? ratio(*run.ratio) : "–") << " |\n";
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
         << " times the paper (" << s.within << " of " << s.ratios.size() << " within a factor "
         << agreement_factor() << ")";
    md << ". ";
  }
  md << "\n\n" << eq108_table(f.cells);
  std::vector<Claim> claims = {reading_claim(f)};
  for (const Grid& g : f.grids) {
    other_grid_section(md, g);
    for (const auto& [key, s] : g.stats)
      claims.push_back(grid_claim(g.cells, key, s));
  }
  return StudyReport{.markdown = md.str(), .claims = claims};
}

std::string eq108_index(const Spec& spec, const std::vector<ojson>& rows) {
  std::string grids;
  for (const Grid& g : find(spec, rows).grids)
    grids +=
        ", and on " + std::to_string(g.cells) + " cells instead of " + std::to_string(kPaperGrid);
  return "**What it shows.** Each reading of eq. (108) on the Table 1 cells" + grids +
         ", set against the paper's dt stable column: [" + spec.name + ".md](" + spec.name +
         ".md).\n\n";
}

}  // namespace
}  // namespace mpmstab::studies::eq108
