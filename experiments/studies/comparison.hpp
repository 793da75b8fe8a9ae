// The paper comparison: every Table 1 cell, ours beside the paper's, with a verdict and a class
// of disagreement, and a section per class with its explanation and the supporting experiment.
// The rules that give a cell its verdict and class live here, once, for every report that
// compares with the paper (the comparison and the variants study).
#pragma once

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "paper_table1.hpp"
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

struct ComparisonClass {
  const char* id;  // also the anchor of its section in comparison.md and variants.md
  const char* title;
  ClassKind kind;
};

// Every class, in the order the reports explain them.
const std::vector<ComparisonClass>& comparison_classes();
const ComparisonClass* find_class(const std::string& id);

// Per method and amplitude: the smallest Courant number of the courant scan from which on every
// run (every E) fails. Empty without the scan.
using CourantEdges = std::map<std::pair<std::string, double>, double>;
CourantEdges courant_edges(const std::vector<nlohmann::ordered_json>& courant_rows);

// One cell against the paper.
struct CellVerdict {
  std::string verdict;                    // "agree", "differ: our error 7.6x", ...
  std::string cls;                        // class id
  std::optional<double> error_ratio;      // ours / paper, both stable
  std::optional<double> dt_stable_ratio;  // ours / paper, both numbers and ours stable
  bool compared() const { return cls != "unreadable"; }
  // Both stable or both unstable.
  bool same_verdict() const;
  // Fully in agreement: same verdict, and the max errors within a factor 3 where both stable.
  bool agrees() const { return cls == "agree-stable" || cls == "agree-unstable"; }
};

// Agreement counted over a set of cells, as the comparison's summary states it.
struct AgreementCounts {
  int verdicts_compared = 0;             // cells with a readable paper value
  int verdicts_agree = 0;                // of those, with the same stability verdict
  int errors_compared = 0;               // both stable
  int errors_within = 0;                 // of those, max errors within a factor 3
  std::vector<double> error_ratios;      // ours / paper, both stable
  std::vector<double> dt_stable_ratios;  // ours / paper
  void add(const CellVerdict& v);
};

// The verdict and class of our flat result row against the paper's cell (null: not in the
// paper), with the comparator's factor-3 rule (within_factor_3).
CellVerdict classify(const nlohmann::ordered_json& row, const PaperCell* paper,
                     const CourantEdges& edges, ErrorAt error_at);

// Writes <out>/comparison.md and <out>/comparison.csv (one row per cell: verdict and class) from
// the study's inputs, by name: "table1" (required: its spec and results), the supporting
// experiments "courant", "walls", "crossing" and "eq108", and the "variants" study; an input
// without results is reported as not run. `error_at`, when given, replaces every case's own
// choice of the error compared with the paper's.
void write_comparison(const StudyInputs& inputs, const std::filesystem::path& out,
                      std::optional<ErrorAt> error_at = {});

}  // namespace mpmstab
