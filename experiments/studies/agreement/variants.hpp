// The variants study: Table 1's cells under each documented implementation choice, one at a
// time and in a few pairs, read against the paper with the comparison's rules (classify() in
// comparison.hpp): which choices can, and which cannot, account for each class of disagreement.
// The numbers are computed in variants_analysis.cpp, the report is written in
// variants_report.cpp, and variants.cpp registers the study.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "agreement/comparison.hpp"
#include "spec.hpp"

namespace mpmstab {

// One variant, one column of the paper (its base cases' method: "mpm" or "gimp").
struct VariantMethodSummary {
  int cells = 0;
  AgreementCounts counts;
  double particle_steps = 0;  // work summed over the variant's runs of this column
  std::optional<double> median_error_ratio, median_dt_stable_ratio;  // of the counts' ratios
};

// Which of the study's verdicts a variant earns for a class (criterion stated in variants.md):
// accounts when at least half of the class's cells agree under it, partly when some but fewer
// do, not at all when none does; not applicable when it ran none of them.
enum class Accounts { yes, partly, no, not_applicable };

// One variant, one class of disagreement (the cells' class under the default run).
struct VariantClassOutcome {
  int covered = 0;  // cells of the class that the variant ran
  // Of those, in agreement with the paper under the variant: the verdict and, where both are
  // stable, the max error within the agreement factor (CellVerdict::agrees). Only these count
  // towards accounting for the class.
  int agree = 0;
  int verdict_agree = 0;  // of the covered, with the paper's stability verdict (whatever the error)
  int meaningless = 0;    // of the verdict_agree, stable but meaningless: error over time reached A
  std::vector<double> error_ratios;  // ours / paper where both stable, of the verdict_agree
  // Of the agree, the runs that end stable: their error over time / A, and how many are not
  // accurate (core/base/accuracy.hpp): agreeing with the paper's max error is not accuracy.
  std::vector<double> agreeing_error_over_A;
  int agreeing_not_accurate = 0;
  Accounts accounts = Accounts::not_applicable;  // accounts_for() the class
  bool mostly_meaningless = false;               // most of the verdict_agree are meaningless
};

struct VariantOutcome {
  std::string name, description, change;
  int changes = 0;
  bool baseline = false;
  std::map<std::string, VariantMethodSummary> by_method;
  std::map<std::string, VariantClassOutcome> by_class;
  int cells = 0;                   // cells it ran
  int agreeing = 0;                // of those, fully in agreement (CellVerdict::agrees)
  int agreeing_under_default = 0;  // of its cells, those fully in agreement under the default
  int breaks = 0;                  // of those, no longer in agreement under this variant
  double particle_steps = 0;       // work summed over its runs (shared runs count in each)
  std::vector<std::pair<std::string, double>> error_ratios;  // (column, ours / paper) per cell
};

namespace studies::variants {
// Every variant's tallies, and what the report, the index and the figure's subtitle say of them.
struct Findings {
  std::vector<VariantOutcome> variants;    // in spec order
  std::size_t baseline = 0;                // index of the default variant
  int cells = 0;                           // cells of the default variant
  std::map<std::string, int> class_cells;  // class id -> cells of that class under the default
  // The variant (not the default) with the largest net gain in cells in full agreement over the
  // default, and those that change no cell's agreement (indices in `variants`).
  std::optional<std::size_t> largest_gain;
  std::vector<std::size_t> unchanged;
  // The runs, and those the figure draws: the paper and ours both stable, the paper's error
  // readable.
  std::size_t runs = 0, drawn = 0;
};
}  // namespace studies::variants
using VariantsStudy = studies::variants::Findings;

Accounts accounts_for(const VariantClassOutcome& o, int class_cells);

// The findings from the flat result rows of a variants spec (rows[i] is spec.cases[i]), the
// paper's table and the Courant edges of the courant scan (empty without it).
VariantsStudy study_variants(const Spec& spec, const std::vector<nlohmann::ordered_json>& rows,
                             const std::map<Table1Key, PaperCell>& paper,
                             const CourantEdges& edges);

// The study in numbers, stored as "study" in <name>.json (the comparison does not read it: its
// classes link variants.md's sections).
nlohmann::ordered_json study_to_json(const VariantsStudy& s);

// The report's body (after the spec's title and description) and the figure's data.
std::string variants_markdown(const Spec& spec, const VariantsStudy& s, bool have_courant);
std::string variants_data_csv(const VariantsStudy& s, const std::string& header_lines);

// Shared by the study's numbers (variants_analysis.cpp) and its report (variants_report.cpp).

// The classes of disagreement the study reads (the verdict and error classes), in report order.
std::vector<const ComparisonClass*> variants_disagreement_classes();

// The cells of a class under the default run (0 when none is in it).
int class_cell_count(const VariantsStudy& s, const std::string& class_id);

// A variant's outcome for a class (all zero when it ran none of the class's cells).
VariantClassOutcome class_outcome(const VariantOutcome& v, const std::string& class_id);

}  // namespace mpmstab
