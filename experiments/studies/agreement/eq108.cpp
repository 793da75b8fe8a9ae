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

namespace mpmstab {

namespace studies::eq108 {
namespace {

using ojson = nlohmann::ordered_json;

// A reading of eq. (108): "scaled, l2".
std::string reading_of(const ojson& r) {
  return text(r, "dt_stable_sigma") + ", " + text(r, "dt_stable_vnorm");
}

// One Table 1 cell: the paper's value and our run under each reading (in the spec's order).
struct Eq108Cell {
  const CaseSpec* spec = nullptr;  // the first case of the cell
  const PaperCell* paper = nullptr;
  std::vector<const ojson*> runs;
};

// Our bound / the paper's dt stable where both are numbers and our run ended stable (a
// meaningless run's bound is shown, not compared), as the comparison counts it.
std::optional<double> bound_ratio(const Eq108Cell& c, const ojson& r) {
  if (!c.paper || c.paper->dt_stable.kind != PaperValue::number || outcome(r) != "stable" ||
      !has_number(r, "dt_stable_min"))
    return std::nullopt;
  return r["dt_stable_min"].get<double>() / c.paper->dt_stable.value;
}

struct ReadingStats {
  std::string method;
  std::vector<double> ratios;
  int within = 0;
};

// The cells of the study: each Table 1 cell with its paper row and its run under each reading,
// and the readings in the order the rows give them.
struct Eq108Cells {
  std::vector<std::string> readings;
  std::vector<Eq108Cell> cells;
};
// Only the cases on `grid` cells.
Eq108Cells eq108_cells(const ReportContext& c, const std::map<Table1Key, PaperCell>& paper,
                       int grid) {
  Eq108Cells out;
  std::vector<std::string>& readings = out.readings;
  std::vector<Eq108Cell>& cells = out.cells;
  std::map<Table1Key, std::size_t> index;
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    if (c.spec.cases[i].params.cells != grid) continue;
    const std::string reading = reading_of(c.rows[i]);
    if (std::find(readings.begin(), readings.end(), reading) == readings.end())
      readings.push_back(reading);
    const Table1Key key = paper_key(c.spec.cases[i]);
    auto [it, fresh] = index.try_emplace(key, cells.size());
    if (fresh) {
      const auto p = paper.find(key);
      cells.push_back({&c.spec.cases[i], p == paper.end() ? nullptr : &p->second, {}});
    }
    cells[it->second].runs.push_back(&c.rows[i]);
  }
  return out;
}

// The table of every cell under every reading; `stats` gets, per reading and method, ours /
// paper over the cells where both are measured.
std::string eq108_table(const Eq108Cells& e,
                        std::map<std::pair<std::string, std::string>, ReadingStats>& stats) {
  const auto& readings = e.readings;
  const auto& cells = e.cells;
  std::ostringstream table;
  table << "| method | E | A | dt | c dt/h | A/h | c T | paper's dt stable |";
  for (const auto& r : readings)
    table << " ours (" << r << ") | ratio |";
  table << "\n|---|---|---|---|---|---|---|---|";
  for (std::size_t k = 0; k < readings.size(); ++k)
    table << "---|---|";
  table << "\n";
  for (const auto& cell : cells) {
    const RunParams& p = cell.spec->params;
    const ojson& first = *cell.runs.front();
    table << "| " << to_string(p.method) << " | " << shortest(p.E) << " | " << shortest(p.A)
          << " | " << param(p.dt) << " | " << sci(RunRow(first).courant.value()) << " | "
          << significant(amplitude_per_cell(p), 3) << " | " << significant(wave_passes(p), 3)
          << " | " << (cell.paper ? show(cell.paper->dt_stable) : "–") << " |";
    for (const auto& reading : readings) {
      const auto run = std::find_if(cell.runs.begin(), cell.runs.end(),
                                    [&](const ojson* r) { return reading_of(*r) == reading; });
      if (run == cell.runs.end()) {
        table << " – | – |";
        continue;
      }
      const auto q = bound_ratio(cell, **run);
      const std::string o = outcome(**run);
      table << " "
            << (o == "stable"        ? opt_sci((**run)["dt_stable_min"])
                : o == "meaningless" ? opt_sci((**run)["dt_stable_min"]) + " (meaningless)"
                                     : verdict(**run))
            << " | " << (q ? ratio(*q) : "–") << " |";
      if (q) {
        ReadingStats& s = stats[{reading, std::string(to_string(p.method))}];
        s.ratios.push_back(*q);
        s.within += within_agreement_factor((**run)["dt_stable_min"].get<double>(),
                                            cell.paper->dt_stable.value);
      }
    }
    table << "\n";
  }
  return table.str();
}

// The best reading over all cells: the most cells within the agreement factor, ties broken by
// the smallest mean |ln(ours / paper)|.
struct BestReading {
  std::string name;
  int within = -1, n = 0;
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

// The reading per method, written to `md`; the best reading.
BestReading eq108_reading(
    std::ostream& md, const std::vector<std::string>& readings,
    const std::map<std::pair<std::string, std::string>, ReadingStats>& stats) {
  BestReading best;
  for (const auto& reading : readings) {
    int within = 0, n = 0;
    std::vector<double> all;
    md << reading << ": ";
    bool first = true;
    for (const auto& [key, s] : stats) {
      if (key.first != reading) continue;
      md << (first ? "" : "; ") << key.second << " " << span(s.ratios, 2) << " times the paper ("
         << s.within << " of " << s.ratios.size() << " within a factor " << agreement_factor()
         << ")";
      first = false;
      within += s.within;
      n += static_cast<int>(s.ratios.size());
      all.insert(all.end(), s.ratios.begin(), s.ratios.end());
    }
    md << ". ";
    const double distance = reading_log_distance(all);
    if (within > best.within || (within == best.within && distance < best.mean_log_distance))
      best = BestReading{reading, within, n, all, distance};
  }
  return best;
}

// The grid of the paper's bar (Table 1's runs): the default cells.
int paper_grid() {
  return RunParams{}.cells;
}

// The cells of the cases on another grid than the paper's, in the order the spec first has them.
std::vector<int> other_grids(const Spec& spec) {
  std::vector<int> grids;
  for (const CaseSpec& c : spec.cases)
    if (c.params.cells != paper_grid() &&
        std::find(grids.begin(), grids.end(), c.params.cells) == grids.end())
      grids.push_back(c.params.cells);
  return grids;
}

// The run of a cell under `reading`, if the cell has one.
const ojson* run_of(const Eq108Cell& cell, const std::string& reading) {
  const auto run = std::find_if(cell.runs.begin(), cell.runs.end(),
                                [&](const ojson* r) { return reading_of(*r) == reading; });
  return run == cell.runs.end() ? nullptr : *run;
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

// A compared cell beyond the agreement factor, with the paper's value and the confidence of its
// transcription: "E = 4, A = 0.05, dt = 1.2e-3 (0.08 times the paper's 5.0e-2, transcribed with
// low confidence)".
std::string outside_text(const Eq108Cell& cell, double q) {
  const RunParams& p = cell.spec->params;
  return "E = " + shortest(p.E) + ", A = " + shortest(p.A) + ", dt = " + param(p.dt) + " (" +
         ratio(q) + " times the paper's " + show(cell.paper->dt_stable) + ", transcribed with " +
         cell.paper->confidence + " confidence)";
}

// Per reading and method on another grid: ours / paper, how many within the factor, and the
// same reading's ratios on the paper's grid.
struct GridStats {
  std::vector<double> ratios, paper_grid_ratios;
  int within = 0;
  std::vector<std::string> outside;  // the compared cells beyond the factor
};

// The claim of one (reading, method) on `grid` cells: every compared cell within the factor.
Claim grid_claim(int grid, const std::pair<std::string, std::string>& key, const GridStats& s) {
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
      .count("paper_cells", paper_grid())
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

// The cells run on `grid` cells, each under its reading, beside the paper and beside the same
// cell and reading on the paper's grid; a claim per method: that reading on this grid gives the
// paper's dt stable within the agreement factor in every cell where both are measured.
void other_grid_section(std::ostream& md, const Eq108Cells& grid_cells,
                        const Eq108Cells& paper_cells, int grid, std::vector<Claim>& claims) {
  const double h = 1.0 / grid, paper_h = 1.0 / paper_grid();
  std::map<std::pair<std::string, std::string>, GridStats> stats;
  std::ostringstream table;
  table << "| method | E | A | dt | c dt/h | A/h | paper's dt stable | reading | ours on "
        << paper_grid() << " cells | ratio | ours on " << grid
        << " cells | error over time / A | accuracy | ratio |\n"
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Eq108Cell& cell : grid_cells.cells) {
    const RunParams& p = cell.spec->params;
    const Eq108Cell* on_paper_grid = same_cell(paper_cells.cells, cell);
    for (const ojson* run : cell.runs) {
      const std::string reading = reading_of(*run);
      const ojson* paper_run = on_paper_grid ? run_of(*on_paper_grid, reading) : nullptr;
      const auto q = bound_ratio(cell, *run);
      const auto q_paper = paper_run ? bound_ratio(*on_paper_grid, *paper_run) : std::nullopt;
      table << "| " << to_string(p.method) << " | " << shortest(p.E) << " | " << shortest(p.A)
            << " | " << param(p.dt) << " | " << sci(RunRow(*run).courant.value()) << " | "
            << significant(amplitude_per_cell(p), 3) << " | "
            << (cell.paper ? show(cell.paper->dt_stable) : "–") << " | " << reading << " | "
            << (paper_run ? bound_text(*paper_run) : "–") << " | "
            << (q_paper ? ratio(*q_paper) : "–") << " | " << bound_text(*run) << " | "
            << accuracy_columns(*run) << " | " << (q ? ratio(*q) : "–") << " |\n";
      GridStats& s = stats[{reading, std::string(to_string(p.method))}];
      if (q_paper) s.paper_grid_ratios.push_back(*q_paper);
      if (q) {
        s.ratios.push_back(*q);
        const bool within = within_agreement_factor((*run)["dt_stable_min"].get<double>(),
                                                    cell.paper->dt_stable.value);
        s.within += within;
        if (!within) s.outside.push_back(outside_text(cell, *q));
      }
    }
  }
  md << "\n## On " << grid << " cells\n\nEach cell run again on " << grid
     << " cells (h = " << shortest(h) << ", where the paper's bar has " << paper_grid()
     << " cells, h = " << shortest(paper_h)
     << ") at the same E, A and dt, under the reading named: eq. (108) evaluated with the "
        "coarser grid's h on the coarser grid's runs. *ratio* is ours / the paper's dt stable, "
        "compared as above; beside it the same cell and reading on "
     << paper_grid()
     << " cells. A run reported stable has its error over time / A and accuracy class beside "
        "it.\n\n**Reading.** ";
  for (const auto& [key, s] : stats) {
    md << key.second << " (" << key.first << ") on " << grid
       << " cells: " << (s.ratios.empty() ? std::string("no cell compared") : span(s.ratios, 2))
       << " times the paper (" << s.within << " of " << s.ratios.size() << " within a factor "
       << agreement_factor() << "; on " << paper_grid() << " cells "
       << (s.paper_grid_ratios.empty() ? std::string("no cell compared")
                                       : span(s.paper_grid_ratios, 2))
       << ", " << s.paper_grid_ratios.size() << " cells)"
       << (s.outside.empty() ? std::string("") : "; beyond the factor: " + list_of(s.outside))
       << ". ";
    claims.push_back(grid_claim(grid, key, s));
  }
  md << "\n\n" << table.str();
}

StudyReport eq108_report(const ReportContext& c) {
  const auto paper = read_paper_table1(c.spec);
  const Eq108Cells cells = eq108_cells(c, paper, paper_grid());
  std::map<std::pair<std::string, std::string>, ReadingStats> stats;
  const std::string table = eq108_table(cells, stats);
  std::ostringstream md;
  md << "## Results\n\nEach Table 1 cell run on the paper's grid of " << paper_grid()
     << " cells under every reading of eq. (108) (docs/theory.md, "
        "\"The paper's bound, eq. (108)\"); *ours* is the minimum of the bound over the run, "
        "compared with the paper's dt stable where our run ended stable (a meaningless run's "
        "bound is shown, not compared) and the paper prints a number; *ratio* is ours / "
        "paper.\n\n**Reading.** ";
  const BestReading best = eq108_reading(md, cells.readings, stats);
  md << "\n\n" << table;
  Claim claim_ =
      claim("a-reading-gives-the-paper",
            "Some reading of eq. (108) on the paper's {cells} cells gives the paper's "
            "dt stable column within a factor {k} in every cell where both are "
            "measured",
            "the best reading ({best}: the most cells within it, ties broken by the "
            "smallest mean absolute natural log of ours / paper, here {distance}) is within it in "
            "{within} of {n} cells; its ratios {span}");
  claim_.count("cells", paper_grid())
      .value("k", agreement_factor())
      .value("best", best.name)
      .every("within", std::max(best.within, 0), "n", best.n)
      .value("span", span(best.ratios, 2))
      .number("distance", best.mean_log_distance, 3);
  std::vector<Claim> claims = {claim_};
  for (const int grid : other_grids(c.spec))
    other_grid_section(md, eq108_cells(c, paper, grid), cells, grid, claims);
  return StudyReport{.markdown = md.str(), .claims = claims};
}

std::string eq108_index(const Spec& spec, const std::vector<ojson>&) {
  std::string grids;
  for (const int grid : other_grids(spec))
    grids +=
        ", and on " + std::to_string(grid) + " cells instead of " + std::to_string(paper_grid());
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
}  // namespace studies::eq108

}  // namespace mpmstab
