// The eq108 study: every reading of eq. (108) that its two documented ambiguities allow (the
// stress scaled by 1/sqrt(E) or not, the nodal velocity norm Euclidean or maximum) on the Table 1
// cells, each set against the paper's dt stable column.
#include <algorithm>
#include <map>
#include <sstream>

#include "claims.hpp"
#include "csv.hpp"
#include "paper_table1.hpp"
#include "report_util.hpp"
#include "study.hpp"

namespace mpmstab {

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
Eq108Cells eq108_cells(const ReportContext& c, const std::map<Table1Key, PaperCell>& paper) {
  Eq108Cells out;
  std::vector<std::string>& readings = out.readings;
  std::vector<Eq108Cell>& cells = out.cells;
  std::map<Table1Key, std::size_t> index;
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
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
          << " | " << param(p.dt) << " | " << sci(first["courant"].get<double>()) << " | "
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

// The best reading over all cells.
struct BestReading {
  std::string name;
  int within = -1, n = 0;
  std::vector<double> ratios;
};

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
    if (within > best.within) best = BestReading{reading, within, n, all};
  }
  return best;
}

StudyReport eq108_report(const ReportContext& c) {
  const auto paper = read_paper_table1(c.spec);
  const Eq108Cells cells = eq108_cells(c, paper);
  std::map<std::pair<std::string, std::string>, ReadingStats> stats;
  const std::string table = eq108_table(cells, stats);
  std::ostringstream md;
  md << "## Results\n\nEach Table 1 cell run under every reading of eq. (108) (docs/design.md, "
        "\"The paper's bound, eq. (108)\"); *ours* is the minimum of the bound over the run, "
        "compared with the paper's dt stable where our run ended stable (a meaningless run's "
        "bound is shown, not compared) and the paper prints a number; *ratio* is ours / "
        "paper.\n\n**Reading.** ";
  const BestReading best = eq108_reading(md, cells.readings, stats);
  md << "\n\n" << table;
  Claim claim_ = claim("a-reading-gives-the-paper",
                       "Some reading of eq. (108) gives the paper's dt stable column within a "
                       "factor {k} in every cell where both are measured",
                       "the best reading ({best}) is within it in {within} of {n} cells; its "
                       "ratios {span}");
  claim_.value("k", agreement_factor())
      .value("best", best.name)
      .every("within", std::max(best.within, 0), "n", best.n)
      .value("span", span(best.ratios, 2));
  return StudyReport{.markdown = md.str(), .claims = {claim_}};
}

std::string eq108_index(const Spec& spec, const std::vector<ojson>&) {
  return "**What it shows.** Each reading of eq. (108) on the Table 1 cells, set against the "
         "paper's dt stable column: [" +
         spec.name + ".md](" + spec.name + ".md).\n\n";
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

}  // namespace mpmstab
