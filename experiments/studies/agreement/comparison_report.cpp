// The comparison's report: comparison.csv (the verdict and class of every Table 1 cell) and
// comparison.md (a summary, every cell beside the paper's, then a section per class of
// disagreement with the experiment of ours that explains it, then the paper's Figs. 1-3 beside
// our runs of them, written in comparison_figures.cpp). Everything is read from the study's
// inputs: the table1 experiment, the supporting experiments (courant, walls, crossing, eq108),
// the figures and their variant runs, all of the paper tier; a section whose experiment is not
// among the inputs (mpmstab compare with explicit specs) says so.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <ostream>
#include <set>
#include <sstream>

#include "agreement/comparison.hpp"
#include "base/accuracy.hpp"
#include "claims.hpp"
#include "csv.hpp"
#include "key.hpp"
#include "report_util.hpp"
#include "run_row.hpp"

namespace mpmstab {

namespace studies::comparison_report {
namespace {

using ojson = nlohmann::ordered_json;
namespace fs = std::filesystem;
using Rows = std::vector<ojson>;  // flat result rows, one per case

struct Cell {
  const CaseSpec* spec;
  ojson row;  // our flat result row
  const PaperCell* paper = nullptr;
  std::string paper_verdict;  // the paper's: "stable", "*", or "?" where unreadable
  CellVerdict v;
  // Its rerun with periodic boundaries (the walls experiment), if it has one, and its verdict.
  const ojson* rerun = nullptr;
  std::optional<CellVerdict> periodic;
  // explained_definition(): a rerun with one choice changed alone agrees with the paper.
  bool explained() const { return periodic && periodic->agrees(); }
};

// How many cells (of a class, or that disagree) a rerun explains, and how many it reruns at all.
struct Explained {
  std::size_t cells = 0, rerun = 0, explained = 0;
};

// Ours / the paper's dt stable over eq108 runs: the ratios, those within the agreement factor,
// and the cells beyond it with their ratio.
struct GridRatios {
  std::vector<double> ratios, within;
  std::vector<std::pair<const Cell*, double>> beyond;
};
// The eq108 runs of one grid and reading that end stable where the paper prints a dt stable, each
// against the paper's value of its Table 1 cell as eq108.md compares them: per method, over all.
struct Eq108Ratios {
  std::map<std::string, GridRatios> by_method;
  GridRatios all;
  std::vector<const nlohmann::ordered_json*> rows;
};

// What every part of the report is written from. The cells point into `paper` and `by_class`
// into `cells`, so it is built in place and never copied.
struct Comparison {
  Comparison(const Spec& table1_spec, const fs::path& out_dir, std::optional<ErrorAt> at)
      : table1(table1_spec), out(out_dir), error_at(at), paper(read_paper_table1(table1_spec)) {}
  Comparison(const Comparison&) = delete;
  Comparison& operator=(const Comparison&) = delete;

  const Spec& table1;
  const fs::path& out;
  std::optional<ErrorAt> error_at;       // --error-at: replaces every case's own choice
  std::map<Table1Key, PaperCell> paper;  // the transcribed Table 1
  std::map<std::string, Rows> support;   // the supporting experiments run, by input name
  const ojson* peers = nullptr;          // the peers study's "study" object; null: not run
  Rows peer_rows;                        // the peers experiment's cases (empty: not run)
  const ojson* ensemble = nullptr;       // table1's ensemble per cell; null: not in its results
  std::vector<Claim> claims;             // the conclusions (claims.hpp)
  CourantEdges edges;                    // from the courant scan; empty without it
  std::vector<Cell> cells;               // in the order of the table1 spec's cases
  std::map<std::string, std::vector<const Cell*>> by_class;
  AgreementCounts all, mpm, gimp;       // over every cell, MPM's and the other methods' (GIMP's)
  std::map<std::string, double> limit;  // each method's spectral limit at the paper's layout
  Explained disagreements;              // over the cells that disagree with the paper
  // eq108's runs by (cells, reading); the runs on another grid than Table 1's (the first) in the
  // reading of our Table 1 runs, and that grid (0: none).
  std::map<std::pair<int, std::string>, Eq108Ratios> eq108;
  const Eq108Ratios* coarse = nullptr;
  int coarse_cells = 0;

  bool have(const std::string& name) const { return support.count(name) > 0; }
  const Rows& rows(const std::string& name) const { return support.at(name); }
  const std::vector<const Cell*>& in_class(const std::string& cls) const {
    static const std::vector<const Cell*> none;
    const auto it = by_class.find(cls);
    return it == by_class.end() ? none : it->second;
  }
  std::size_t count(const std::string& cls) const { return in_class(cls).size(); }
  // The error of a cell compared with the paper's: --error-at, or the case's own choice.
  ErrorAt error_of(const Cell& c) const { return error_at.value_or(c.spec->error_at); }
};

// ---- Reading the inputs.

Rows case_rows(const ojson& doc) {
  if (!doc.contains("cases")) return {};
  const ojson& cases = doc.at("cases");
  return Rows(cases.begin(), cases.end());
}

// Every case of the table1 experiment (rows[i] is its case i) against its paper cell, counted
// per class and per method; the spectral limits from the Table 1 records.
void compare_cells(Comparison& cmp, const Rows& rows) {
  const Spec& table1 = cmp.table1;
  for (std::size_t i = 0; i < table1.cases.size(); ++i) {
    Cell c;
    c.spec = &table1.cases[i];
    c.row = rows.at(i);
    const auto it = cmp.paper.find(paper_key(table1.cases[i]));
    if (it != cmp.paper.end()) c.paper = &it->second;
    const auto kind = c.paper ? c.paper->max_error.kind : PaperValue::unreadable;
    c.paper_verdict = kind == PaperValue::unreadable ? "?"
                      : kind == PaperValue::number   ? "stable"
                                                     : "*";
    c.v = classify(c.row, c.paper, cmp.edges, cmp.error_of(c));
    cmp.cells.push_back(std::move(c));
  }
  for (const auto& c : cmp.cells) {
    cmp.by_class[c.v.cls].push_back(&c);
    cmp.all.add(c.v);
    const RunRow r(c.row);
    (r.method == "mpm" ? cmp.mpm : cmp.gimp).add(c.v);
    if (r.courant_spectral) cmp.limit[r.method] = *r.courant_spectral;
  }
}

// ---- Formatting and looking up cells and runs.

std::string distribution(const std::vector<double>& v) {
  if (v.empty()) return "no cells";
  std::ostringstream s;
  s << "min " << ratio(quantile(v, 0)) << ", quartiles " << ratio(quantile(v, 0.25)) << " / "
    << ratio(quantile(v, 0.5)) << " / " << ratio(quantile(v, 0.75)) << ", max "
    << ratio(quantile(v, 1)) << " (" << v.size() << " cells)";
  return s.str();
}

// Whether a row of another experiment runs the cell's case: its method, E, A and dt on the same
// particles per cell and, unless `any_grid`, the same grid (its boundaries or another choice may
// differ).
bool same_cell(const ojson& a, const CaseSpec& c, bool any_grid = false) {
  const auto& p = c.params;
  auto same_int = [&](const char* key, int v) {
    return !a.contains(key) || !a[key].is_number() || a[key].get<int>() == v;
  };
  return RunRow(a).method == std::string(to_string(p.method)) && a["E"].get<double>() == p.E &&
         a["A"].get<double>() == p.A && a["dt"].get<double>() == p.dt &&
         (any_grid || same_int("cells", p.cells)) && same_int("ppc", p.ppc);
}

std::string cell_name(const Cell& c) {
  const auto& p = c.spec->params;
  return std::string(to_string(p.method)) + " E=" + shortest(p.E) + " A=" + shortest(p.A) +
         " dt=" + param(p.dt);
}

// The cells of a class (only those a rerun explains, with `explained`), named; "" for none.
std::string cell_list(const Comparison& cmp, const std::string& cls, bool explained = false) {
  std::string s;
  for (const Cell* c : cmp.in_class(cls))
    if (!explained || c->explained()) s += (s.empty() ? "" : "; ") + cell_name(*c);
  return s;
}

// Whether a class holds cells that disagree with the paper (a verdict or an error class).
bool disagreeing(const std::string& cls) {
  const ComparisonClass* k = find_class(cls);
  return k && (k->kind == ClassKind::verdict || k->kind == ClassKind::error);
}

// Each cell's rerun with periodic boundaries (its run in the walls experiment), classified
// against the cell's paper value by the same rules: where it agrees, the walls experiment
// explains the cell (explained_definition()). Then how many of the cells that disagree it
// explains.
void rerun_cells(Comparison& cmp) {
  const Rows none;
  const Rows& walls = cmp.have("walls") ? cmp.rows("walls") : none;
  for (auto& c : cmp.cells) {
    for (const auto& r : walls)
      if (!c.rerun && text(r, "bc") == "periodic" && same_cell(r, *c.spec)) c.rerun = &r;
    if (c.rerun) c.periodic = classify(*c.rerun, c.paper, cmp.edges, cmp.error_of(c));
    if (!disagreeing(c.v.cls)) continue;
    ++cmp.disagreements.cells;
    cmp.disagreements.explained += c.explained();
  }
}

// A reading of eq. (108) as the tables name it: "sigma scaled, ||v|| l2".
std::string reading(const ojson& r) {
  return "sigma " + text(r, "dt_stable_sigma") + ", ||v|| " + text(r, "dt_stable_vnorm");
}

// Every eq108 run against the paper's dt stable of its Table 1 cell, on whichever grid.
void eq108_ratios(Comparison& cmp) {
  if (!cmp.have("eq108") || cmp.cells.empty()) return;
  for (const auto& r : cmp.rows("eq108")) {
    const RunRow run(r);
    for (const Cell& c : cmp.cells) {
      if (!has_number(r, "dt_stable_min") || run.outcome != "stable" ||
          !same_cell(r, *c.spec, true) || !c.paper || c.paper->dt_stable.kind != PaperValue::number)
        continue;
      const int grid = static_cast<int>(run.cells.value_or(c.spec->params.cells));
      Eq108Ratios& e = cmp.eq108[{grid, reading(r)}];
      e.rows.push_back(&r);
      const double q = r["dt_stable_min"].get<double>() / c.paper->dt_stable.value;
      for (GridRatios* m : {&e.all, &e.by_method[run.method]}) {
        m->ratios.push_back(q);
        if (within_agreement_factor(q, 1)) {
          m->within.push_back(q);
        } else {
          m->beyond.emplace_back(&c, q);
        }
      }
    }
  }
  for (const auto& [key, e] : cmp.eq108)
    if (!cmp.coarse && key.first != cmp.cells.front().spec->params.cells &&
        key.second == reading(cmp.cells.front().row)) {
      cmp.coarse = &e;
      cmp.coarse_cells = key.first;
    }
}

// "transcribed with medium confidence", and with `evidence` its evidence: ": \"dt_stable ...\"".
std::string transcription(const PaperCell& p, bool evidence = true) {
  return "transcribed with " + p.confidence + " confidence" +
         (evidence && !p.evidence.empty() ? ": \"" + p.evidence + "\"" : "");
}

// How many cells of a class a rerun explains, and how many it reruns at all.
Explained explained_in(const Comparison& cmp, const std::string& cls) {
  Explained e;
  for (const Cell* c : cmp.in_class(cls)) {
    ++e.cells;
    e.rerun += c->periodic.has_value();
    e.explained += c->explained();
  }
  return e;
}

// ---- comparison.csv

// The verdict and class of every cell: make check compares them with the blessed expectations.
void write_verdicts_csv(const Comparison& cmp) {
  std::ostringstream csv;
  csv << "# experiment: comparison of " << cmp.table1.name << " with "
      << cmp.table1.reference.generic_string()
      << "\n# verdict and class of every cell; make check compares them with "
         "reference/regression/comparison_verdicts.csv\n"
      << "method,E,A,dt,verdict,class,confidence\n";
  for (const auto& c : cmp.cells) {
    const auto& p = c.spec->params;
    csv << to_string(p.method) << ',' << shortest(p.E) << ',' << shortest(p.A) << ','
        << shortest(p.dt) << ',' << csv_field(c.v.verdict) << ',' << c.v.cls << ','
        << (c.paper ? c.paper->confidence : "") << '\n';
  }
  write_if_changed(cmp.out / "comparison.csv", csv.str());
}

// ---- comparison.md: the summary and the table of every cell.

// What the peers experiment covered, counted from its cases: per method and dt, how many runs,
// how many compared at the table's T and how many only up to an earlier time.
std::string peer_coverage(const Comparison& cmp) {
  const double table_T = cmp.table1.cases.front().params.T;
  std::map<std::pair<std::string, Key>, std::vector<double>> runs;  // -> the T of each run
  for (const auto& r : cmp.peer_rows)
    runs[{RunRow(r).method, Key(r["dt"].get<double>(), "dt")}].push_back(r["T"].get<double>());
  std::ostringstream s;
  s << "Our solver was run beside independent code (Uintah's 1D MPM code) on "
    << cmp.peer_rows.size() << " cases of the paper's bar (" << coverage_of(cmp.peer_rows).text()
    << "), and agrees on " << (*cmp.peers)["agree"].dump() << " of " << (*cmp.peers)["cases"].dump()
    << " (same outcome and failure step, errors within the stated tolerances: "
       "[peers.md](peers.md)). Those cases cover only:";
  std::set<std::string> methods;
  for (const auto& [k, Ts] : runs) {
    methods.insert(k.first);
    std::vector<double> shorter;  // the runs the peer stopped before the table's T
    std::copy_if(Ts.begin(), Ts.end(), std::back_inserter(shorter),
                 [&](double T) { return T < table_T; });
    s << (k == runs.begin()->first ? " " : "; ") << k.first << " at dt = " << param(k.second)
      << ": " << Ts.size() << " runs, " << Ts.size() - shorter.size()
      << " compared at T = " << shortest(table_T);
    if (!shorter.empty())
      s << " and " << shorter.size() << " only up to T = " << span(shorter)
        << " (the peer run stopped there)";
  }
  std::vector<std::string> missing;  // Table 1's methods the peer did not run
  for (const auto& c : cmp.table1.cases)
    if (const std::string m(to_string(c.params.method)); methods.insert(m).second)
      missing.push_back(m);
  s << ". Table 1's methods not among them: " << (missing.empty() ? "none" : list_of(missing))
    << ".";
  return s.str();
}

// What the report is and how its verdicts are kept.
void introduction(std::ostream& md, const Comparison& cmp) {
  const std::string reference = link(cmp.out, cmp.table1.reference);
  md << "# Our results against the paper, cell by cell\n\n";
  if (cmp.peers && !cmp.peer_rows.empty()) {
    md << "**What independent code covered.** " << peer_coverage(cmp)
       << " Where we disagree with the paper below outside that coverage, the solver has not been "
          "checked against independent code on that method or step; a disagreement there may "
          "come from the paper's choices, the paper's values, or ours.\n\n";
  } else {
    md << "The check against independent code (peers.md) has not been run into this folder.\n\n";
  }
  const Explained& d = cmp.disagreements;
  md << "Each cell of the paper's Table 1 (as transcribed in [" << reference << "](" << reference
     << ")) beside ours ([" << cmp.table1.name << ".md](" << cmp.table1.name
     << ".md)), each put in one class by a predicate (the class's definition opens its section "
        "below; the outcomes are defined in [docs/studies.md](../docs/studies.md) and the "
        "quantities in [docs/theory.md](../docs/theory.md)). "
        "The paper's text does not fix every choice its code made. In this report, "
     << explained_definition() << ". Of the " << d.cells
     << " cells that disagree with the paper, a rerun explains " << d.explained << " and leaves "
     << d.cells - d.explained
     << " unexplained; the class table of the summary counts them per class, and no parameter "
        "is tuned to move a cell. Low-confidence transcriptions are labelled in the table. This "
        "report does not fail CI; each cell's verdict is stored in "
        "[`reference/regression/comparison_verdicts.csv`](../reference/regression/"
        "comparison_verdicts.csv) and a changed verdict fails `make check` until it is "
        "blessed (`make bless REASON=...`).\n\n";
}

// Which of our errors the cells compare with the paper's Max Error.
std::string compared_error_text(const Comparison& cmp) {
  std::set<ErrorAt> compared;
  for (const auto& c : cmp.cells)
    compared.insert(cmp.error_of(c));
  return compared.size() > 1 ? "per case (error_at): at T, or the largest over the run"
         : *compared.begin() == ErrorAt::T
             ? "max error at T (`max_error`)"
             : "max error over the run (`max_error_over_time`, chosen with --error-at or error_at)";
}

// Our verdict in a few words: "stable (0.0043 A, accurate)", "meaningless" or "\* reason at step
// n (t = ...)".
std::string short_verdict(const ojson& row) {
  return outcome(row) == "meaningless" ? outcome(row) : verdict(row);
}

// How many cells have each pair of verdicts: the paper's (rows) against ours (columns).
void verdict_table(std::ostream& md, const Comparison& cmp) {
  std::map<std::string, std::map<std::string, int>> n;
  for (const auto& c : cmp.cells)
    ++n[c.paper_verdict][outcome(c.row)];
  md << "| cells by verdict | ours stable | ours meaningless | ours unstable (`*`) |\n"
        "|---|---|---|---|\n";
  for (const auto& [p, name] : {std::pair{"stable", "paper stable"},
                                {"*", "paper unstable (`*`)"},
                                {"?", "paper unreadable"}}) {
    if (n.count(p))
      md << "| " << name << " | " << n[p]["stable"] << " | " << n[p]["meaningless"] << " | "
         << n[p]["unstable"] << " |\n";
  }
  md << "\nA cell's stability verdicts are the same on the diagonal of this table only: a "
        "meaningless run (it reached T, but its error over time reached A) matches neither of "
        "the paper's verdicts.\n\n";
}

// The agreement in numbers, and how many cells each class holds.
void summary(std::ostream& md, const Comparison& cmp, const FigureSections& figures) {
  const AgreementCounts& all = cmp.all;
  md << "## Summary\n\n"
     << "| | |\n|---|---|\n"
     << "| cells | " << cmp.cells.size() << " (" << cmp.count("unreadable")
     << " with an unreadable paper value) |\n"
     << "| stability verdicts agreeing | " << all.verdicts_agree << " of " << all.verdicts_compared
     << " (every cell with a readable paper value, the sensitive ones by their verdict as run: "
        "the cells table1.md counts) |\n"
     << "| ours meaningless (agreeing with neither verdict) | " << all.meaningless << " of "
     << all.verdicts_compared << " |\n"
     << "| max errors within a factor " << agreement_factor() << " (both stable) | "
     << all.errors_within << " of " << all.errors_compared << " |\n"
     << "| our error compared with the paper's Max Error | " << compared_error_text(cmp) << " |\n"
     << "| our dt_stable / paper's, MPM | " << distribution(cmp.mpm.dt_stable_ratios) << " |\n"
     << "| our dt_stable / paper's, GIMP | " << distribution(cmp.gimp.dt_stable_ratios) << " |\n";
  if (const Eq108Ratios* g = cmp.coarse)
    md << "| our dt_stable / paper's on a grid of " << cmp.coarse_cells
       << " cells (h = " << shortest(1.0 / cmp.coarse_cells)
       << ", [eq108.md](eq108.md)) | within a factor " << agreement_factor() << " in "
       << g->all.within.size() << " of " << g->all.ratios.size()
       << " cells ([below](#dt-stable)) |\n";
  if (!figures.classes.empty()) {
    md << "| Figs. 1-3, class of each ([below](#figures)) | ";
    for (std::size_t i = 0; i < figures.classes.size(); ++i) {
      const auto& [fig, cls] = figures.classes[i];
      md << (i ? "; " : "") << "[" << fig << "](#" << fig << "): " << cls;
    }
    md << " |\n";
  }
  md << "\n";
  verdict_table(md, cmp);
  md << "Per class, its cells and, for a class of disagreement, how many of them a rerun "
        "explains (the rule is in the introduction) and how many the walls experiment reruns at "
        "all:\n\n| class | cells | explained by a rerun | unexplained | rerun |\n"
        "|---|---|---|---|---|\n";
  for (const auto& k : comparison_classes()) {
    md << "| [" << k.title << "](#" << k.id << ") | " << cmp.count(k.id) << " | ";
    if (disagreeing(k.id)) {
      const Explained e = explained_in(cmp, k.id);
      md << e.explained << " of " << e.cells << " | " << e.cells - e.explained << " | " << e.rerun
         << " of " << e.cells << " |\n";
    } else {
      md << "– | – | – |\n";
    }
  }
  md << "\n";
}

// Every cell: the paper's dt_stable and max error beside ours, the ratios, verdict and class.
void cell_table(std::ostream& md, const Comparison& cmp) {
  md << "## The cells\n\nRatios are ours / paper. `*`: unstable; meaningless: reached T, but "
        "the error over time reached A (its errors are shown, not compared). Confidence: of the "
        "transcription.\n\n"
        "Each cell is placed in the coordinates that fix a run: c dt/h, A/h and the wave passes "
        "c T (E and T enter only through c T).\n\n"
        "| E | A | dt | method | c dt/h | A/h | c T | verdict paper | ours | dt_stable paper | "
        "ours | ratio | max error paper | ours | ratio | verdict | class | confidence |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& c : cmp.cells) {
    const auto& p = c.spec->params;
    const ojson& r = c.row;
    const RunRow rr(r);
    const auto error = compared_error(r, cmp.error_of(c));
    const bool stable = rr.survived();
    // Ours: unstable, meaningless, or a stable run with its error over time per A and accuracy.
    const std::string ours = rr.outcome == "unstable" ? R"(\*)"
                             : rr.outcome == "stable" ? verdict(r)
                                                      : rr.outcome;
    md << "| " << shortest(p.E) << " | " << shortest(p.A) << " | " << param(p.dt)
       << (c.spec->dt_inferred ? " (inferred)" : "") << " | " << to_string(p.method) << " | "
       << sci(*rr.courant) << " | " << significant(amplitude_per_cell(p), 3) << " | "
       << significant(wave_passes(p), 3) << " | "
       << (c.paper_verdict == "*" ? "\\*" : c.paper_verdict) << " | " << ours << " | "
       << (c.paper ? show(c.paper->dt_stable) : "–") << " | "
       << (stable ? opt_sci(r["dt_stable_min"]) : "\\*") << " | "
       << (c.v.dt_stable_ratio ? ratio(*c.v.dt_stable_ratio) : "–") << " | "
       << (c.paper ? show(c.paper->max_error) : "–") << " | " << (stable ? opt_sci(error) : "\\*")
       << " | "
       << (c.v.error_ratio
               ? beside_thresholds(*c.v.error_ratio, {kAgreementFactor, 1 / kAgreementFactor})
               : "–")
       << " | " << c.v.verdict << " | [" << c.v.cls << "](#" << c.v.cls << ") | "
       << (c.paper ? (c.paper->confidence == "high" ? "high" : "**" + c.paper->confidence + "**")
                   : "–")
       << " |\n";
  }
  md << "\n## Classes of disagreement\n\n";
}

// ---- comparison.md: the sections of the classes of disagreement.

// A class's heading (its anchor is the class id the tables link to), its cell count and its
// definition.
void class_heading(std::ostream& md, const Comparison& cmp, const std::string& id) {
  if (const ComparisonClass* k = find_class(id))
    md << "<a id=\"" << id << "\"></a>\n### " << k->title << " (" << cmp.count(id) << ")\n\n"
       << "**Definition** (`" << id << "`): " << k->definition << "\n\n";
}

// The heading of a class section, its cells, how many of them a rerun explains, and where the
// variants study (in the studies tier, which this report does not read) runs them under each
// implementation choice.
void class_opening(std::ostream& md, const Comparison& cmp, const std::string& id) {
  class_heading(md, cmp, id);
  const std::string cells = cell_list(cmp, id);
  md << "Cells (" << cmp.count(id) << ")" << (cells.empty() ? "" : ": " + cells) << ".\n\n";
  if (cmp.count(id) > 0) {
    const Explained e = explained_in(cmp, id);
    md << "**Explained by a rerun:** " << e.explained << " of " << e.cells << " ("
       << e.cells - e.explained << " unexplained; the walls experiment reruns " << e.rerun << " of "
       << e.cells << " with periodic boundaries)";
    const std::string listed = cell_list(cmp, id, true);
    md << (listed.empty() ? std::string(".") : ": " + listed + ".") << "\n\n";
  }
  const std::string anchor = "variants.md#" + id;
  md << "**Implementation choices:** these cells under each documented choice, changed alone "
        "and in pairs, are in the studies tier (`make studies`): ["
     << anchor << "](" << anchor << ").\n\n";
}

// Whether the supporting experiment `name` has been run; where it has not, the section says so.
bool ran(std::ostream& md, const Comparison& cmp, const char* name) {
  if (!cmp.have(name))
    md << "*The supporting experiment `" << name << "` has not been run: `make reproduce` runs "
       << "it.*\n\n";
  return cmp.have(name);
}

// The courant scan: per Courant number, how many values of E reach T, per method and amplitude.
void courant_scan_table(std::ostream& md, const Comparison& cmp) {
  // Courant -> (method, A) -> survived, runs
  std::map<Key, std::map<std::pair<std::string, Key>, std::pair<int, int>>> by_c;
  std::set<std::pair<std::string, Key>> groups;
  std::set<Key> Es;  // the scan's values of E: Table 1's
  std::int64_t worst_step = 0;
  int above_failed = 0;
  double above_survivor_ratio = 0;  // the largest c dt/h over the limit of a scan run reaching T
  std::vector<const ojson*> above_survivors;
  std::set<std::string> survivor_methods;
  for (const auto& r : cmp.rows("courant")) {
    const double c = scan_courant(r);
    const auto g = std::make_pair(RunRow(r).method, Key(r["A"].get<double>(), "A"));
    groups.insert(g);
    Es.insert(Key(r["E"].get<double>(), "E"));
    auto& [ok, n] = by_c[Key(c, "c dt/h")][g];
    ++n;
    if (survived(r)) ++ok;
    const RunRow run(r);
    // Above the limit at the scan's c dt / h (the row's, rounded: scan_courant()).
    const bool above = run.courant_spectral && c > *run.courant_spectral;
    if (above && run.outcome == "unstable") {
      ++above_failed;
      worst_step = std::max(worst_step, run.failure_step.value_or(0));
    }
    if (above && run.survived()) {
      above_survivors.push_back(&r);
      survivor_methods.insert(run.method);
      above_survivor_ratio = std::max(above_survivor_ratio, *run.courant / *run.courant_spectral);
    }
  }
  md << "**Experiment** ([courant.md](courant.md)): each E of Table 1 for each method and A, "
        "dt = C h / c. Runs reaching T out of the "
     << Es.size() << " values of E:\n\n| c dt/h |";
  for (const auto& g : groups)
    md << " " << g.first << " A=" << shortest(g.second) << " |";
  md << "\n|---|" << rule_cells(groups.size()) << "\n";
  for (const auto& [c, per] : by_c) {
    md << "| " << shortest(c) << " |";
    for (const auto& g : groups)
      md << " " << per.at(g).first << " |";
    md << "\n";
  }
  md << "\nOf the scan's runs above their scheme's spectral limit, " << above_failed
     << " fail, the last of them at step " << worst_step << ", and " << above_survivors.size()
     << " reach T";
  if (!above_survivors.empty()) {
    md << " (" << list_of({survivor_methods.begin(), survivor_methods.end()}) << "; "
       << coverage_of(above_survivors).text() << "), at a c dt / h of at most "
       << fixed(above_survivor_ratio, 3)
       << " times the limit: at these run lengths the scan's survival edge can lie above the "
          "limit (courant.md reruns each edge for length)";
  }
  md << ". The Table 1 cells run above the limit, and how many of them fail here, are counted "
        "by the first conclusion above.\n\n";
}

// Paper stable (its run goes on) where ours fails above the scheme's spectral limit.
void above_spectral_limit_section(std::ostream& md, const Comparison& cmp) {
  class_opening(md, cmp, "above-spectral-limit");
  md << "Linearised about rest, the step of each scheme amplifies some mode above its spectral "
        "limit (spectral.md; USL with FLIP at the paper's "
     << shortest(cmp.cells.empty() ? 0.0 : cmp.cells.front().row["ppc"].get<double>())
     << " particles per cell: the limit on each record, in the table above). For this problem E "
        "and dt enter the discrete dynamics only through c dt / h and the run length c T (the "
        "manufactured solution and the scheme are invariant when t is scaled by c): at a fixed T a "
        "larger E is the same Courant number run for more wave passes, so an outcome at one C can "
        "change with E, and the scan runs each E of Table 1. ";
  if (ran(md, cmp, "courant")) courant_scan_table(md, cmp);
}

// Paper stable (its run goes on) where ours fails at or below the spectral limit but at or above
// the scan's edge for its method and amplitude.
void above_our_edge_section(std::ostream& md, const Comparison& cmp) {
  class_opening(md, cmp, "above-our-edge");
  if (!ran(md, cmp, "courant")) return;
  md << "The scan's edges per method and A over its runs ("
     << coverage_of(cmp.rows("courant")).text()
     << "), and their ratio to the scheme's spectral limit (below an edge runs can fail too; "
        "courant.md gives per case where survival stops): ";
  int edges = 0, above = 0;
  for (const auto& [k, c] : cmp.edges) {
    md << (k == cmp.edges.begin()->first ? "" : ", ") << k.first << " A=" << shortest(k.second)
       << ": " << (std::isfinite(c) ? shortest(c) : std::string("no edge in the scan"));
    const auto l = cmp.limit.find(k.first);
    if (std::isfinite(c) && l != cmp.limit.end()) {
      md << " (" << fixed(c / l->second, 3) << "x)";
      ++edges;
      above += c > l->second;
    }
  }
  md << ". " << above << " of " << edges
     << " of these edges lie above the spectral limit; a cell failing above the limit is in the "
        "previous class whatever the edge.\n\n";
}

// GIMP runs ending with a particle pushed out through a wall: the walls experiment reruns them
// with periodic boundaries.
void gimp_wall_exit_section(std::ostream& md, const Comparison& cmp) {
  class_opening(md, cmp, "gimp-wall-exit");
  if (!ran(md, cmp, "walls")) return;
  int reached = 0, n = 0, meaningless = 0;
  std::vector<double> paper_rel, in_cells, rerun_dt;
  std::map<Accuracy, int> paper_class;  // the paper's error at T per A, by accuracy class
  Coverage runs;
  for (const Cell* c : cmp.in_class("gimp-wall-exit")) {
    const RunParams& p = c->spec->params;
    runs.add(c->row);
    in_cells.push_back(p.A * p.cells);
    if (c->paper && c->paper->max_error.kind == PaperValue::number) {
      paper_rel.push_back(c->paper->max_error.value / p.A);
      ++paper_class[accuracy_class(paper_rel.back(), 1)];
    }
    if (const ojson* r = c->rerun) {
      ++n;
      reached += survived(*r);
      meaningless += outcome(*r) == "meaningless";
      rerun_dt.push_back(p.dt);
    }
  }
  md << "Their runs: " << runs.text() << " (A/h = " << listing(in_cells)
     << ": displacements of that many cells). The paper's own max errors for them are "
     << distribution(paper_rel)
     << " times A (by this project's classes, docs/studies.md \"Accuracy classes\", applied to "
        "its error at T: "
     << paper_class[Accuracy::meaningless] << " meaningless, " << paper_class[Accuracy::inaccurate]
     << " inaccurate, " << paper_class[Accuracy::accurate]
     << " accurate; the paper gives no error over time). "
        "**Experiment** ([walls.md](walls.md)): the same cells with periodic boundaries, "
     << n << " of " << cmp.count("gimp-wall-exit") << " (dt = " << listing(rerun_dt)
     << "): " << reached << " of " << n << " reach T, " << meaningless << " of those with an error "
     << "over time of at least A (meaningless, so not agreeing with the paper). With Dirichlet "
        "walls our GIMP drops the weight of the nodes beyond a wall (the design's default); the "
        "periodic reruns have no wall.\n\n";
}

// MPM failing inside the domain, at or below the spectral limit and below the scan's edge: what
// the runs record of each failure, and their reruns with periodic boundaries.
void mpm_crossing_failure_section(std::ostream& md, const Comparison& cmp) {
  class_opening(md, cmp, "mpm-crossing-failure");
  const auto& cells = cmp.in_class("mpm-crossing-failure");
  if (cells.empty()) return;
  md << "What our runs record of each failure, and the rerun with periodic boundaries "
        "([walls.md](walls.md)); the Table 1 runs do not record grid crossings of a run that "
        "fails, and the crossing experiment of the next class does not rerun these cells.\n\n"
        "| cell | c dt/h | failure | at t / T | error over time / A before it | with periodic "
        "boundaries |\n|---|---|---|---|---|---|\n";
  for (const Cell* c : cells) {
    const ojson& r = c->row;
    const RunRow rr(r);
    md << "| " << cell_name(*c) << " | " << sci(*rr.courant) << " | "
       << rr.failure_reason.value_or("") << " | "
       << (rr.failure_time ? ratio(*rr.failure_time / r["T"].get<double>()) : std::string("–"))
       << " | " << (rr.error_over_A() ? ratio(*rr.error_over_A()) : std::string("–")) << " | "
       << (c->rerun ? short_verdict(*c->rerun) : std::string("not rerun")) << " |\n";
  }
  md << "\n";
}

// The crossing experiment: MPM's and GIMP's error over time per E and amplitude.
void crossing_table(std::ostream& md, const Comparison& cmp) {
  const Rows& rows = cmp.rows("crossing");
  md << "Linear MPM's shape-function gradient jumps when a particle crosses a cell boundary "
        "(the grid-crossing error of the literature); GIMP's weights are C1 and their gradient "
        "does not jump. The experiment measures the error against the number of crossings, not "
        "the force at a crossing. **Experiment** ([crossing.md](crossing.md)): E = "
     << listing(rows, "E") << ", dt = " << listing(rows, "dt") << ", amplitude "
     << span(numbers(rows, "A"))
     << ".\n\n| E | A | crossings MPM | MPM error over time / A | GIMP error over time / A |\n"
        "|---|---|---|---|---|\n";
  auto rel = [](const ojson& x) {
    const RunRow run(x);
    return run.survived() ? ratio(*run.error_over_A()) : "\\* " + run.failure_reason.value_or("");
  };
  for (const auto& r : rows) {
    if (RunRow(r).method != "mpm") continue;
    const ojson* g = nullptr;
    for (const auto& q : rows)
      if (RunRow(q).method == "gimp" && q["E"] == r["E"] && q["A"] == r["A"]) g = &q;
    md << "| " << shortest(r["E"].get<double>()) << " | " << shortest(r["A"].get<double>()) << " | "
       << (r["crossings"].is_null() ? std::string("–") : r["crossings"].dump()) << " | " << rel(r)
       << " | " << (g ? rel(*g) : "–") << " |\n";
  }
}

// Our MPM errors at T per A in this class and the paper's (its measure: the paper publishes no
// error over time), and the cell of the widest gap.
void crossing_summary(std::ostream& md, const Comparison& cmp) {
  std::vector<double> paper_rel, ours_rel;
  const Cell* widest = nullptr;  // the cell of the class with the largest ours / paper
  for (const Cell* c : cmp.in_class("mpm-error-larger")) {
    paper_rel.push_back(c->paper->max_error.value / c->spec->params.A);
    ours_rel.push_back(*compared_error(c->row, cmp.error_of(*c)) / c->spec->params.A);
    if (!widest || *c->v.error_ratio > *widest->v.error_ratio) widest = c;
  }
  md << "\nErrors at T per A, the paper's measure: in the cells of this class ours are "
     << distribution(ours_rel) << ", the paper's " << distribution(paper_rel);
  if (widest) {
    md << " (the widest gap, " << cell_name(*widest) << ": ours "
       << sci(*compared_error(widest->row, cmp.error_of(*widest))) << ", the paper's "
       << show(widest->paper->max_error) << ")";
  }
  md << ".\n\n";
}

// MPM's max error more than 3 times the paper's, beside the crossing experiment.
void mpm_error_larger_section(std::ostream& md, const Comparison& cmp) {
  class_opening(md, cmp, "mpm-error-larger");
  if (!ran(md, cmp, "crossing")) return;
  crossing_table(md, cmp);
  crossing_summary(md, cmp);
}

// GIMP's max error more than 3 times the paper's: the cells the walls explain, from the same cells
// rerun with periodic boundaries.
void gimp_error_larger_section(std::ostream& md, const Comparison& cmp) {
  class_opening(md, cmp, "gimp-error-larger");
  if (!ran(md, cmp, "walls")) return;
  std::vector<double> dirichlet, periodic;
  std::string helped;
  int meaningless = 0, within = 0;
  for (const Cell* c : cmp.in_class("gimp-error-larger")) {
    const ojson* r = c->rerun;
    if (r && outcome(*r) == "meaningless") ++meaningless;
    const bool stable = r && outcome(*r) == "stable";
    const auto periodic_error = stable ? compared_error(*r, cmp.error_of(*c)) : std::nullopt;
    if (!periodic_error) continue;
    const double ours = *periodic_error;
    dirichlet.push_back(*c->v.error_ratio);
    periodic.push_back(ours / c->paper->max_error.value);
    if (within_agreement_factor(ours, c->paper->max_error.value)) {
      ++within;
      helped += (helped.empty() ? "" : "; ") + cell_name(*c);
    }
  }
  md << "Near a Dirichlet wall our GIMP keeps only the nodes inside the domain, so a particle "
        "whose support reaches past the wall loses part of its weight (the design's default). "
        "**Experiment** ([walls.md](walls.md)): the cells of this class that the walls experiment "
        "holds, rerun with periodic boundaries: ours / paper goes from "
     << distribution(dirichlet) << " to " << distribution(periodic)
     << " over the periodic runs that are stable (" << meaningless
     << " meaningless, not compared). Within a factor " << agreement_factor()
     << " with periodic boundaries: " << within << " of " << dirichlet.size()
     << (helped.empty() ? std::string() : " (" + helped + ")")
     << ". Those are the cells of this class the walls experiment explains; the other cells of "
        "the class are not explained here. What the other documented implementation choices "
        "(position update, velocity transfer, stress-update order and the others) do to this "
        "class is in the variants study (linked above).\n\n";
}

// Our runs that reached T with an error over time of at least A: a class of their own, never
// counted as agreeing with either of the paper's verdicts.
void ours_meaningless_section(std::ostream& md, const Comparison& cmp) {
  class_opening(md, cmp, "ours-meaningless");
  const auto& cells = cmp.in_class("ours-meaningless");
  if (cells.empty()) return;
  md << "These runs reached T, but at some step their error was at least the amplitude A of "
        "the solution: their answer is meaningless, so the cell matches neither of the paper's "
        "verdicts, whatever its error at T.\n\n"
        "| cell | paper max error | ours at T | ours over time / A | with periodic boundaries "
        "([walls.md](walls.md)) |\n|---|---|---|---|---|\n";
  int mpm = 0;
  for (const Cell* c : cells) {
    const ojson& r = c->row;
    mpm += RunRow(r).method == "mpm";
    md << "| " << cell_name(*c) << " | " << (c->paper ? show(c->paper->max_error) : "–") << " | "
       << opt_sci(r["max_error"]) << " | "
       << (RunRow(r).error_over_A() ? ratio(*RunRow(r).error_over_A()) : std::string("–")) << " | "
       << (c->rerun ? short_verdict(*c->rerun) : std::string("–")) << " |\n";
  }
  md << "\n"
     << mpm << " of " << cells.size()
     << " of these cells are MPM cells; the crossing experiment of the [MPM error "
        "class](#mpm-error-larger) measures MPM's error over time against amplitude and "
        "crossings, not these cells.\n\n";
}

// The remaining failures; how many runs of the scan reach T at each one's c dt / h is in the
// scan's table of the first class.
void other_failure_section(std::ostream& md, const Comparison& cmp) {
  class_opening(md, cmp, "other-failure");
  if (cmp.have("courant") && !cmp.in_class("other-failure").empty())
    md << "How many runs of the scan reach T at each cell's c dt/h, per method and A: the table of "
          "[the first class](#above-spectral-limit).\n\n";
}

// Our dt_stable against the paper's in the cells where ours is stable, and the readings of
// eq. (108) that the eq108 experiment tries.
void dt_stable_section(std::ostream& md, const Comparison& cmp) {
  const std::vector<double>& mpm = cmp.mpm.dt_stable_ratios;
  const std::vector<double>& gimp = cmp.gimp.dt_stable_ratios;
  const auto smaller = std::count_if(mpm.begin(), mpm.end(), [](double x) { return x < 1; }) +
                       std::count_if(gimp.begin(), gimp.end(), [](double x) { return x < 1; });
  std::vector<const ojson*> compared;
  for (const Cell& c : cmp.cells)
    if (c.v.dt_stable_ratio) compared.push_back(&c.row);
  md << "<a id=\"dt-stable\"></a>\n### dt_stable: ours against the paper's\n\n"
        "Over the cells where the paper gives a dt_stable and our run is stable (reached T with "
        "an error over time below A; the cell table gives its error over time per A and its "
        "accuracy class; "
     << coverage_of(compared).text() << "), our eq. (108) bound is smaller than the paper's in "
     << smaller << " of " << mpm.size() + gimp.size() << ": ours / paper is " << distribution(mpm)
     << " for MPM and " << distribution(gimp) << " for GIMP. ";
  if (!ran(md, cmp, "eq108")) return;
  const Rows& eq108 = cmp.rows("eq108");
  md << "**Experiment** ([eq108.md](eq108.md)): the cells at dt = " << listing(eq108, "dt")
     << " under the four readings of the two ambiguities of eq. (108), stress divided by "
        "sqrt(E) or not and the Euclidean or maximum norm of the nodal velocity. Ours / paper "
        "per reading:\n\n| reading | MPM | GIMP |\n|---|---|---|\n";
  double largest = 0, widest_mpm_spread = 0;
  std::size_t mpm_cells = 0;
  for (const auto& [key, e] : cmp.eq108) {
    if (key.first != cmp.cells.front().spec->params.cells) continue;
    const auto& by_method = e.by_method;  // a lambda may not name a structured binding
    auto of = [&](const char* m) {
      const auto it = by_method.find(m);
      return it == by_method.end() ? std::vector<double>{} : it->second.ratios;
    };
    md << "| " << key.second << " | " << distribution(of("mpm")) << " | "
       << distribution(of("gimp")) << " |\n";
    largest = std::max(largest, *std::max_element(e.all.ratios.begin(), e.all.ratios.end()));
    if (const auto m = of("mpm"); !m.empty()) {
      mpm_cells = std::max(mpm_cells, m.size());
      const auto [lo, hi] = std::minmax_element(m.begin(), m.end(), TotalLess());
      widest_mpm_spread = std::max(widest_mpm_spread, *hi / *lo);
    }
  }
  md << "\nThe largest ratio under any reading is " << ratio(largest)
     << (largest < 1 ? " (under each reading our bound is the smaller in each cell compared). "
                     : " (under some reading our bound is at least the paper's in some cell). ")
     << "Under each reading MPM's ratio varies by at most a factor " << ratio(widest_mpm_spread)
     << " over the " << mpm_cells
     << " MPM cells compared (eq108.md lists them; GIMP's spread is in the table).";
  if (const Eq108Ratios* g = cmp.coarse) {
    md << " **On " << cmp.coarse_cells << " cells** (h = " << shortest(1.0 / cmp.coarse_cells)
       << ", [eq108.md](eq108.md)), in the reading of our Table 1 runs, eq. (108) gives the "
          "paper's column within a factor "
       << agreement_factor() << " in " << g->all.within.size() << " of " << g->all.ratios.size()
       << " cells where both are measured (" << coverage_of(g->rows).text() << "): ours / paper "
       << span(g->all.ratios, 2) << ", " << span(g->all.within, 2) << " in those within it.";
    std::vector<std::string> beyond;
    for (const auto& [c, q] : g->all.beyond)
      beyond.push_back(cell_name(*c) + ", " + ratio(q) + " times the paper's " +
                       show(c->paper->dt_stable) + ", " + transcription(*c->paper));
    if (!beyond.empty()) md << " Beyond it: " << list_of(beyond) << ".";
  }
  md << " The paper's text does not say on which grid or in which reading it evaluated eq. (108); "
        "this report keeps the printed formula on the paper's grid, in its documented default "
        "reading.\n\n";
}

// Cells whose paper value is missing from the transcription, and where the transcription's
// evidence is.
void unreadable_section(std::ostream& md, const Comparison& cmp) {
  class_heading(md, cmp, "unreadable");
  md << "Cells: " << cell_list(cmp, "unreadable")
     << ". Their paper values are missing from the text copy "
        "of the paper; see the evidence column of the transcription.\n\n";
  const std::string reference = link(cmp.out, cmp.table1.reference);
  md << "Paper values marked **medium** or **low** are transcriptions with the evidence in ["
     << reference << "](" << reference << "); they are compared like the others but labelled.\n";
}

// The paper's dt stable column of a method's cells in units of h/c on `grid` cells, against the
// spectral limit: how many lie at or below it, and "41 of 42 cells do (7.9e-3 to 27.2 h/c against
// a limit of 0.756)" with the cells above it, when fewer than half, named with the confidence and
// (`evidence`) the evidence of their transcription.
std::pair<long long, std::string> column_in_cells(const std::vector<const Cell*>& cells, int grid,
                                                  double lim, bool evidence) {
  std::vector<double> v;
  std::vector<std::string> above;
  for (const Cell* c : cells) {
    v.push_back(c->paper->dt_stable.value * std::sqrt(c->spec->params.E) * grid);
    if (v.back() > lim)
      above.push_back(cell_name(*c) + " (" + significant(v.back(), 3) + " h/c, " +
                      transcription(*c->paper, evidence) + ")");
  }
  const auto below = static_cast<long long>(v.size() - above.size());
  std::string s = std::to_string(below) + " of " + std::to_string(v.size()) + " cells do (" +
                  span(v, 3) + " h/c against a limit of " + significant(lim, 3) + ")";
  if (!above.empty() && 2 * above.size() < v.size()) s += "; above it: " + list_of(above);
  return {below, s};
}

// The paper's dt stable column for one method, in units of h/c on the paper's grid, against its
// spectral limit; beside it, the same on eq108's coarser grid, where eq. (108) comes near it.
Claim dt_stable_claim(const Comparison& cmp, const std::string& m,
                      const std::vector<const Cell*>& cells) {
  const double lim = cmp.limit.at(m);
  const int grid = cells.front()->spec->params.cells;
  const auto [below, paper_grid] = column_in_cells(cells, grid, lim, true);
  const GridRatios* coarse = nullptr;  // the method's runs on the coarser grid
  if (cmp.coarse && cmp.coarse->by_method.count(m)) coarse = &cmp.coarse->by_method.at(m);
  Claim b = claim("paper-dt-stable-vs-limit-" + m,
                  "Every cell of the paper's dt stable column for {method}, in units of h/c on "
                  "the paper's {cells} cells, lies at or below the scheme's spectral limit",
                  std::string("{paper_grid}") +
                      (coarse ? "; on {coarse} cells, where eq. (108) gives this column within "
                                "a factor {k} in {within} of {n} cells (eq108.md), {coarse_grid}"
                              : ""));
  b.value("method", m).count("cells", grid).value("paper_grid", paper_grid);
  if (coarse)
    b.count("coarse", cmp.coarse_cells)
        .value("k", agreement_factor())
        .count("within", static_cast<long long>(coarse->within.size()))
        .count("n", static_cast<long long>(coarse->ratios.size()))
        .value("coarse_grid", column_in_cells(cells, cmp.coarse_cells, lim, false).second);
  b.over(static_cast<long long>(cells.size()));
  b.holds = below == static_cast<long long>(cells.size());
  return b.on(
      "the paper's dt stable column as transcribed; the spectral limit of the Table 1 "
      "records");
}

// Every disagreeing cell explained by a rerun of this report.
Claim explained_claim(const Comparison& cmp) {
  const long long disagree = cmp.disagreements.cells, explained = cmp.disagreements.explained;
  std::vector<const ojson*> rows;  // the cells that disagree and their reruns
  for (const Cell& c : cmp.cells) {
    if (!disagreeing(c.v.cls)) continue;
    rows.push_back(&c.row);
    if (c.rerun) rows.push_back(c.rerun);
  }
  Claim x = claim("every-disagreement-explained",
                  "Every Table 1 cell that disagrees with the paper is explained by a rerun of "
                  "this report (the rerun, with one documented choice changed alone, agrees "
                  "with the paper)",
                  "{explained} of {cells} such cells are; {unexplained} are not");
  x.every("explained", explained, "cells", disagree);
  x.count("unexplained", disagree - explained);
  return x.on(coverage_of(rows));
}

// The comparison's conclusions, each decided by the cells.
std::vector<Claim> comparison_claims(const Comparison& cmp) {
  std::vector<Claim> claims;
  int above_fail = 0;
  std::vector<const ojson*> above, rerun;  // the cells above the limit; those rerun as ensembles
  std::map<std::string, std::vector<const Cell*>> paper_dt_stable;  // method -> its cells
  int sensitive = 0, sensitive_paper_stable = 0;
  for (std::size_t i = 0; i < cmp.cells.size(); ++i) {
    const Cell& c = cmp.cells[i];
    const ojson& r = c.row;
    const RunRow run(r);
    if (!run.courant_spectral) continue;
    if (run.above_spectral_limit()) {
      above.push_back(&r);
      above_fail += outcome(r) == "unstable";
    }
    if (c.paper && c.paper->dt_stable.kind == PaperValue::number)
      paper_dt_stable[run.method].push_back(&c);
    const ojson* e = cmp.ensemble && i < cmp.ensemble->size() ? &(*cmp.ensemble)[i] : nullptr;
    if (e && e->is_object() && number_or_zero(*e, "members") > 0) rerun.push_back(&r);
    if (e && (*e)["sensitive"] == true) {
      ++sensitive;
      sensitive_paper_stable += c.paper && c.paper->max_error.kind == PaperValue::number;
    }
  }
  Claim a = claim("above-limit-fails",
                  "Every Table 1 cell run above its scheme's spectral limit fails here",
                  "{fail} of {above} such cells fail");
  a.every("fail", above_fail, "above", static_cast<long long>(above.size()));
  claims.push_back(a.on(coverage_of(above)));
  for (const auto& [m, cells] : paper_dt_stable)
    claims.push_back(dt_stable_claim(cmp, m, cells));
  claims.push_back(explained_claim(cmp));
  if (cmp.ensemble) {
    Claim e = claim("no-sensitive-cell",
                    "No cell this tier reruns as an ensemble changes its verdict when its layout "
                    "is perturbed far below the discretisation error",
                    "{sensitive} of {rerun} cells rerun are sensitive ({paper_stable} of them "
                    "stable in the paper); table1.md counts each by its verdict as run, as this "
                    "report does, and names it; the cells near their edge too costly for this tier "
                    "are rerun in ensembles.md (make studies), which this tier does not read");
    e.count("sensitive", sensitive).count("rerun", static_cast<long long>(rerun.size()));
    e.count("paper_stable", sensitive_paper_stable);
    e.holds = sensitive == 0;
    claims.push_back(e.on(coverage_of(rerun)));
  }
  return claims;
}

// comparison.md: the summary, every cell, then the classes of disagreement in the order of
// comparison_classes(), with the dt_stable gap before the unreadable cells, then the figures.
void write_markdown(const Comparison& cmp, const FigureSections& figures) {
  std::ostringstream md;
  introduction(md, cmp);
  md << claims_markdown(cmp.claims);
  summary(md, cmp, figures);
  cell_table(md, cmp);
  above_spectral_limit_section(md, cmp);
  above_our_edge_section(md, cmp);
  gimp_wall_exit_section(md, cmp);
  mpm_crossing_failure_section(md, cmp);
  mpm_error_larger_section(md, cmp);
  gimp_error_larger_section(md, cmp);
  other_failure_section(md, cmp);
  ours_meaningless_section(md, cmp);
  class_opening(md, cmp, "error-smaller");
  class_opening(md, cmp, "paper-unstable-ours-stable");
  dt_stable_section(md, cmp);
  unreadable_section(md, cmp);
  md << "\n<a id=\"figures\"></a>\n" << figures.markdown;
  write_if_changed(cmp.out / "comparison.md", md.str());
}

}  // namespace
}  // namespace studies::comparison_report

void write_comparison(const StudyInputs& inputs, const std::filesystem::path& out,
                      std::optional<ErrorAt> error_at) {
  using namespace studies::comparison_report;
  const auto table1 = inputs.find("table1");
  if (table1 == inputs.end() || !table1->second.spec || !table1->second.present()) {
    const std::string name = table1 != inputs.end() && table1->second.spec
                                 ? table1->second.spec->name
                                 : std::string("table1");
    throw MissingInput((out / (name + ".json")).string() + " not found: run the sweep first");
  }
  Comparison cmp(*table1->second.spec, out, error_at);
  for (const auto& [name, input] : inputs)
    if (name != "table1" && name != "peers" && input.present())
      cmp.support[name] = case_rows(input.doc);
  if (const auto p = inputs.find("peers"); p != inputs.end() && p->second.present()) {
    cmp.peer_rows = case_rows(p->second.doc);
    if (p->second.doc.contains("study")) cmp.peers = &p->second.doc.at("study");
  }
  if (const nlohmann::ordered_json& t = table1->second.doc;
      t.contains("study") && t["study"].contains("ensemble"))
    cmp.ensemble = &t["study"]["ensemble"];
  if (cmp.have("courant")) cmp.edges = courant_edges(cmp.rows("courant"));
  compare_cells(cmp, case_rows(table1->second.doc));
  rerun_cells(cmp);
  eq108_ratios(cmp);
  // The transcription of the figures lies beside that of Table 1.
  const std::filesystem::path figures_csv = cmp.table1.reference.parent_path() / "figures.csv";
  std::vector<QuotedCell> quoted;
  for (const auto& c : cmp.cells) {
    const auto& p = c.spec->params;
    quoted.push_back({std::string(to_string(p.method)), p.E, p.A, p.dt,
                      c.paper ? show(c.paper->max_error) : "–", short_verdict(c.row), c.v.cls});
  }
  const FigureSections figures = figure_sections(read_paper_figures(figures_csv),
                                                 link(out, figures_csv), inputs, cmp.edges, quoted);
  cmp.claims = comparison_claims(cmp);
  cmp.claims.insert(cmp.claims.end(), figures.claims.begin(), figures.claims.end());
  write_claims(out, "comparison", cmp.claims, "# experiment: comparison\n");
  write_verdicts_csv(cmp);
  write_markdown(cmp, figures);
}

}  // namespace mpmstab
