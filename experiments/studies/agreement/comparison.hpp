// The paper comparison: every Table 1 cell, ours beside the paper's, with a verdict and a class
// of disagreement, and a section per class with its explanation and the supporting experiment;
// then the paper's Figs. 1-3, their observables beside those of our runs. The rules that give a
// cell its verdict and class live here, once, for every report that compares with the paper (the
// comparison and the variants study).
#pragma once

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "claims.hpp"
#include "key.hpp"
#include "shared/paper_table1.hpp"
#include "spec.hpp"
#include "study.hpp"

namespace mpmstab {

// What a class of cells says about agreement with the paper.
enum class ClassKind {
  agreement,   // the cell agrees (verdict, and max error within a factor 3 where both stable)
  verdict,     // the stability verdicts differ
  error,       // both stable, the max errors differ by more than a factor 3
  unreadable,  // the paper's value is not readable
};

// A class of cells: its id, a short title, and the definition of the predicate that puts a cell
// in it (classify() and failure_class() below), in words. The one list of them,
// comparison_classes(), is what comparison.md, variants.md and docs/studies.md's generated block
// `design-comparison-classes` print.
struct ComparisonClass {
  const char* id;          // also the anchor of its section in comparison.md and variants.md
  std::string title;       // a name that says no more than the definition
  std::string definition;  // what the predicate decides, in the order classify() tests it
  ClassKind kind;
};

// "a; b; c" (items that hold commas), or "none".
std::string semicolon_list(const std::vector<std::string>& v);

// Every class, in the order the reports explain them.
const std::vector<ComparisonClass>& comparison_classes();
const ComparisonClass* find_class(const std::string& id);

// The classes as a Markdown table, one row per class: its id, its title and its definition
// (for docs/studies.md's generated block `design-comparison-classes`).
std::string comparison_classes_markdown();

// When an experiment of the comparison *explains* a cell that disagrees with the paper, in
// words: a rerun of the cell by that experiment with one documented choice changed alone agrees
// fully with the paper (CellVerdict::agrees() of its verdict by classify() against the cell's
// paper value). comparison.md counts, per class, the cells explained.
const std::string& explained_definition();

// A run's Courant number as the courant scan groups its runs: rounded to 1e-4 (the scan's dts
// are C h / c rounded to six digits, so this recovers C).
double scan_courant(const nlohmann::ordered_json& row);

// Per method and amplitude: the smallest Courant number of the courant scan from which on every
// run (every E) fails. Empty without the scan.
using CourantEdges = std::map<std::pair<std::string, Key>, double>;
CourantEdges courant_edges(const std::vector<nlohmann::ordered_json>& courant_rows);

// One cell against the paper. Whether its stability verdicts agree is cell_agreement()'s
// (shared/paper_table1.hpp), the rule table1.md counts by too: a meaningless run, or one too short
// for a verdict, agrees with neither of the paper's verdicts (classes ours-meaningless and
// ours-too-short), never counted as agreeing.
struct CellVerdict {
  std::string verdict;                    // "agree", "differ: our error 7.6x", ...
  std::string cls;                        // class id
  std::optional<double> error_ratio;      // ours / paper, both stable
  std::optional<double> dt_stable_ratio;  // ours / paper, both numbers and ours stable
  // A Table 1 cell's agreement (classify()); none for a verdict of another kind (a figure's).
  std::optional<CellAgreement> agreement;
  // The paper's verdict is readable: compared.
  bool compared() const { return agreement ? mpmstab::compared(*agreement) : cls != "unreadable"; }
  // Both stable (ours stable over a wave pass, not meaningless) or both unstable.
  bool same_verdict() const;
  // Fully in agreement: same verdict, and the max errors within a factor 3 where both stable.
  bool agrees() const { return cls == "agree-stable" || cls == "agree-unstable"; }
};

// Agreement counted over a set of cells, as the comparison's summary states it.
struct AgreementCounts {
  int verdicts_compared = 0;             // cells with a readable paper value
  int verdicts_agree = 0;                // of those, with the same stability verdict
  int meaningless = 0;                   // of those, ours meaningless (never agreeing)
  int errors_compared = 0;               // both stable
  int errors_within = 0;                 // of those, max errors within a factor 3
  std::vector<double> error_ratios;      // ours / paper, both stable
  std::vector<double> dt_stable_ratios;  // ours / paper
  void add(const CellVerdict& v);
};

// The verdict and class of our flat result row against the paper's cell (null: not in the
// paper), with the comparator's agreement-factor rule (within_agreement_factor).
CellVerdict classify(const nlohmann::ordered_json& row, const PaperCell* paper,
                     const CourantEdges& edges, ErrorAt error_at);

// The class of our failed run (a flat row whose outcome is unstable) where the paper's run goes
// on: above-spectral-limit, above-our-edge, gimp-wall-exit, mpm-crossing-failure or
// other-failure (tested in that order).
std::string failure_class(const nlohmann::ordered_json& row, const CourantEdges& edges);

// ---- The paper's Figs. 1-3 against our runs of them (comparison_figures.cpp).

// One observable of a figure as the paper states it (reference/paper/figures.csv): a number, a
// word ("survived", "unstable", "more than fig2"), or "?" where only the plot would show it.
struct PaperObservable {
  std::string quantity, value, confidence, section, evidence;
  bool stated() const { return !value.empty() && value != "?"; }
};

// A figure of the paper: the case it shows and what its text says about it.
struct PaperFigure {
  std::string name;  // "fig1": also the name of the experiment that runs it
  std::string method;
  double E = 0, A = 0, dt = 0;
  std::vector<PaperObservable> observables;  // in the order of the file
  const PaperObservable* find(const std::string& quantity) const;
};

// The transcription of the figures, in the order of the file; empty when the file is absent.
std::vector<PaperFigure> read_paper_figures(const std::filesystem::path& csv);

// What comparison.md says about the figures: a section per figure (the paper's observables
// beside ours, each with a verdict; the figure's class; the variant runs of its case), per
// figure its class for the summary, and the claims of the comparisons between two figures (a
// figure whose text says it has more or fewer crossing errors than another: its crossings and
// its error per crossing against the other run's, at the times both histories record).
struct FigureSections {
  std::string markdown;
  std::vector<std::pair<std::string, std::string>> classes;  // (figure, class id), paper order
  std::vector<Claim> claims;
};

// A Table 1 cell as a figure's section quotes it: the cell nearest to the figure's case.
struct QuotedCell {
  std::string method;
  double E = 0, A = 0, dt = 0;
  std::string paper, ours, cls;  // the paper's max error, our verdict, the cell's class
};

// The figure sections from the transcription (`transcription` is its path, as the report links
// it), the study's inputs by name (each figure's experiment, the variant runs and the courant
// scan; an input without results is reported as not run) and the Table 1 cells.
FigureSections figure_sections(const std::vector<PaperFigure>& paper,
                               const std::string& transcription, const StudyInputs& inputs,
                               const CourantEdges& edges, const std::vector<QuotedCell>& table1);

// Writes <out>/comparison.md and <out>/comparison.csv (one row per cell: verdict and class) from
// the study's inputs, by name: "table1" (required: its spec and results), "peers", the
// supporting experiments "courant", "walls", "crossing" and "eq108", the figures "fig1", "fig2",
// "fig3" and their variant runs (fig2_variants, fig3_variants), all of the paper tier; an input
// without results is reported as not run. The transcription of the figures is read from figures.csv
// beside the table1 spec's reference. `error_at`, when given, replaces every case's own
// choice of the error compared with the paper's.
void write_comparison(const StudyInputs& inputs, const std::filesystem::path& out,
                      std::optional<ErrorAt> error_at = {});

}  // namespace mpmstab
