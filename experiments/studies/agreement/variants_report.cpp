// The variants study's report: variants.md (a reading computed from the numbers, the tables per
// variant and per method, and what can account for each class of disagreement), the figure's
// data, and the line comparison.md prints for each class.
#include <algorithm>
#include <ostream>
#include <sstream>

#include "agreement/variants.hpp"
#include "csv.hpp"
#include "report_util.hpp"

namespace mpmstab {

namespace studies::variants_report {
namespace {

using ojson = nlohmann::ordered_json;

std::string of(int k, int n) {
  return std::to_string(k) + " of " + std::to_string(n);
}

// "3 of 5 agree; the verdict in 4, 1 of them meaningless; ours / paper 1.2 to 122": the cells
// in full agreement, then those with the paper's verdict, and their error ratios to the paper.
std::string agree_text(const VariantClassOutcome& o, int n) {
  std::string s = of(o.agree, n) + " agree";
  if (o.verdict_agree != o.agree || o.meaningless) {
    s += "; the verdict in " + std::to_string(o.verdict_agree);
    if (o.meaningless) s += ", " + std::to_string(o.meaningless) + " of them meaningless";
  }
  if (!o.error_ratios.empty()) s += "; ours / paper " + span(o.error_ratios, 2);
  if (!o.agreeing_error_over_A.empty())
    s += "; the agreeing stable runs' error over time " + span(o.agreeing_error_over_A, 2) +
         " A, " + of(o.agreeing_not_accurate, int(o.agreeing_error_over_A.size())) +
         " not accurate";
  return s;
}

std::string cells_word(int n) {
  return std::to_string(n) + (n == 1 ? " cell" : " cells");
}

// A variant's name as the reports show it.
std::string named(const VariantOutcome& v) {
  return "`" + v.name + "`";
}

// The variants (other than the default) sorted by what they make of one class of n cells, each
// as the reading names it.
struct ClassVerdicts {
  std::vector<std::string> yes, partly, no, not_run;
  std::vector<std::string> mostly_meaningless;  // of yes: most agreeing runs are meaningless
};

ClassVerdicts class_verdicts(const VariantsStudy& s, const ComparisonClass& k, int n) {
  ClassVerdicts c;
  for (const auto& v : s.variants) {
    if (v.baseline) continue;
    const VariantClassOutcome o = class_outcome(v, k.id);
    const std::string breaks = v.breaks ? ", breaking " + cells_word(v.breaks) +
                                              (v.breaks == 1 ? " that agrees" : " that agree") +
                                              " under the default"
                                        : "";
    switch (o.accounts) {
      case Accounts::yes:
        c.yes.push_back(named(v) + " (" + agree_text(o, n) + breaks + ")");
        if (o.mostly_meaningless)
          c.mostly_meaningless.push_back(named(v) + " (" + of(o.meaningless, o.verdict_agree) +
                                         ")");
        break;
      case Accounts::partly:
        c.partly.push_back(named(v) + " (" + agree_text(o, n) + breaks + ")");
        break;
      case Accounts::no:
        c.no.push_back(named(v));
        break;
      case Accounts::not_applicable:
        c.not_run.push_back(named(v));
        break;
    }
  }
  return c;
}

// The plain-words reading of one class, generated from the numbers.
std::string class_reading(const VariantsStudy& s, const ComparisonClass& k) {
  const int n = class_cell_count(s, k.id);
  if (n == 0) return "No cell of Table 1 is in this class under the default run.";
  const ClassVerdicts c = class_verdicts(s, k, n);
  const std::string what =
      k.kind == ClassKind::verdict
          ? "the paper's stability verdict and, where both are stable, a max error within a "
            "factor " +
                agreement_factor() + " of the paper's"
          : "a max error within a factor " + agreement_factor() + " of the paper's";
  std::ostringstream md;
  if (!c.yes.empty()) {
    md << "Can account for this class (at least half of its " << cells_word(n) << " reach " << what
       << "): " << list_of(c.yes) << ". ";
    if (!c.mostly_meaningless.empty()) {
      md << "But most of the runs that survive under " << list_of(c.mostly_meaningless)
         << " are meaningless (their error over time reached A): they match the paper's verdict, "
            "not an answer of the size of its Max Error. ";
    }
  } else {
    md << "No variant accounts for this class: none brings half of its " << cells_word(n) << " to "
       << what << ". ";
  }
  if (!c.partly.empty()) md << "Partly (some, fewer than half): " << list_of(c.partly) << ". ";
  if (!c.no.empty())
    md << "Cannot account for it (no cell reaches " << what << "): " << list_of(c.no) << ". ";
  if (!c.not_run.empty())
    md << "Not applicable (ran none of its cells): " << list_of(c.not_run) << ".";
  std::string text = md.str();
  while (!text.empty() && text.back() == ' ')
    text.pop_back();
  return text;
}

// The reading: the variant that brings the most cells into full agreement beyond those that
// already agree under the default, if any does.
void write_largest_gain(std::ostream& md, const VariantsStudy& s) {
  if (!s.largest_gain) return;
  const VariantOutcome& gain = s.variants[*s.largest_gain];
  if (gain.agreeing > gain.agreeing_under_default) {
    md << "The largest net gain over the default is " << named(gain) << " (" << gain.change
       << "): " << gain.agreeing << " of its " << gain.cells << " cells agree, against "
       << gain.agreeing_under_default << " under the default (" << gain.breaks << " broken). ";
  } else {
    md << "No variant raises the number of cells in full agreement above the default's. ";
  }
}

// The reading: the variants that change no cell's agreement (every cell of an agreement class
// still agrees, none of a disagreement class does).
void write_unchanged(std::ostream& md, const VariantsStudy& s) {
  std::vector<std::string> unchanged;
  for (const std::size_t j : s.unchanged)
    unchanged.push_back(named(s.variants[j]));
  if (!unchanged.empty())
    md << "Neither fixing nor breaking any cell: " << list_of(unchanged) << ". ";
}

// The reading: each class of disagreement with cells, with the variants that account for it.
void write_accounted_classes(std::ostream& md, const VariantsStudy& s) {
  std::vector<std::string> accounted, not_accounted;
  for (const ComparisonClass* k : variants_disagreement_classes()) {
    if (class_cell_count(s, k->id) == 0) continue;
    std::string by;
    for (const auto& v : s.variants)
      if (!v.baseline && class_outcome(v, k->id).accounts == Accounts::yes)
        by += (by.empty() ? "" : ", ") + named(v);
    const std::string cls = "[" + std::string(k->id) + "](#" + k->id + ")";
    if (by.empty()) {
      not_accounted.push_back(cls);
    } else {
      accounted.push_back(cls + " by " + by);
    }
  }
  md << "Classes of disagreement that a variant accounts for (criterion below): "
     << semicolon_list(accounted)
     << ". Classes that none accounts for: " << semicolon_list(not_accounted) << ".\n\n";
}

// The report's opening paragraph: what the tables below say, in sentences computed from them.
void write_reading(std::ostream& md, const VariantsStudy& s) {
  const VariantOutcome& def = s.variants.at(s.baseline);
  md << "**Reading** (computed from the rows). Under the default, " << of(def.agreeing, def.cells)
     << " cells agree fully with the paper (the same stability verdict and, where both are "
        "stable, max errors within a factor "
     << agreement_factor() << "). ";
  write_largest_gain(md, s);
  write_unchanged(md, s);
  write_accounted_classes(md, s);
}

// How a row is compared with the paper, what the medians and wall times are over, and the
// figure.
void write_method(std::ostream& md, const Spec& spec, bool have_courant) {
  md << "**How the cells are read.** Every row is compared with the paper cell of its base case "
        "by the rules of [comparison.md](comparison.md): the stability verdict (the paper's `*` "
        "against ours), and where both are stable the max error within a factor "
     << agreement_factor()
     << " (the comparator's rule |a − b| <= ((k − 1) / k) max(|a|, |b|) with k = "
     << agreement_factor()
     << ", `experiments/engine/compare.hpp`). Cells whose paper value is unreadable are not "
        "compared. A variant that changes the method (cpGIMP) is still compared with the paper's "
        "GIMP column. Our error is the max error at T unless the variant's `error_at` says "
        "otherwise. Medians are over the cells where both are stable (max error) or where ours is "
        "stable and the paper prints dt_stable. Work: the particle-steps (particles x steps) of "
        "the variant's runs, summed; runs with the same parameters in two variants (the `error_at` "
        "variant and the default, for example) are computed once and counted in both. Wall times "
        "are in [performance.md](performance.md). A meaningless run (it survived, but its error "
        "over time reached A) never agrees with a stable cell of the paper. A cell's class is its "
        "class in comparison.md, that is under the default run"
     << (have_courant ? ""
                      : " (the Courant scan, courant.json, was not available: the class "
                        "above-our-edge could not be told apart)")
     << ". Variants were chosen before any was run; none is tuned to a cell.\n\n";
  md << "![" << spec.title << "](" << spec.name << ".png)\n\nVector version: [" << spec.name
     << ".svg](" << spec.name << ".svg); data: [" << spec.name << "_data.csv](" << spec.name
     << "_data.csv).\n\n";
}

// One row per variant: its full agreement with the paper, what it breaks, and its cost.
void write_every_variant(std::ostream& md, const VariantsStudy& s) {
  md << "### Every variant\n\n"
        "| variant | change | what it is | cells in full agreement | agreeing under the default "
        "that it breaks | particle-steps |\n|---|---|---|---|---|---|\n";
  for (const auto& v : s.variants) {
    md << "| " << named(v) << " | " << v.change << " | " << v.description << " | "
       << of(v.agreeing, v.cells) << " | " << of(v.breaks, v.agreeing_under_default) << " | "
       << sci(v.particle_steps) << " |\n";
  }
}

// One row per variant and column of the paper: verdicts and errors against the paper's.
void write_per_method(std::ostream& md, const VariantsStudy& s) {
  md << "\n### Per variant and method\n\nVerdicts: cells whose stability verdict agrees with the "
        "paper's, of the cells with a readable paper value. Within "
     << agreement_factor() << "x: of the cells where both are stable. Ratios are ours / paper.\n\n"
     << "| variant | method | cells | verdicts agree | max error within " << agreement_factor()
     << "x | median max error "
        "ratio | median dt_stable ratio | particle-steps |\n|---|---|---|---|---|---|---|---|\n";
  auto opt_ratio = [](const std::optional<double>& r) { return r ? ratio(*r) : "–"; };
  for (const auto& v : s.variants) {
    for (const char* column : {"mpm", "gimp"}) {
      const auto it = v.by_method.find(column);
      if (it == v.by_method.end()) continue;
      const auto& m = it->second;
      md << "| " << named(v) << " | " << (column == std::string("mpm") ? "MPM" : "GIMP") << " | "
         << m.cells << " | " << of(m.counts.verdicts_agree, m.counts.verdicts_compared) << " | "
         << of(m.counts.errors_within, m.counts.errors_compared) << " | "
         << opt_ratio(m.median_error_ratio) << " | " << opt_ratio(m.median_dt_stable_ratio) << " | "
         << sci(m.particle_steps) << " |\n";
    }
  }
}

// One class of disagreement: what each variant makes of its cells, and the reading.
void write_class(std::ostream& md, const VariantsStudy& s, const ComparisonClass& k) {
  const int n = class_cell_count(s, k.id);
  md << "<a id=\"" << k.id << "\"></a>\n### " << k.title << " (" << cells_word(n) << ")\n\n"
     << "Cells listed in [comparison.md](comparison.md#" << k.id << ").\n\n";
  if (n > 0) {
    md << "| variant | change | cells run | agree with the paper | breaks |\n"
          "|---|---|---|---|---|\n";
    for (const auto& v : s.variants) {
      if (v.baseline) continue;
      const VariantClassOutcome o = class_outcome(v, k.id);
      md << "| " << named(v) << " | " << v.change << " | " << o.covered << " | "
         << (o.covered ? agree_text(o, o.covered) : std::string("–")) << " | " << v.breaks
         << " |\n";
    }
    md << "\n";
  }
  md << class_reading(s, k) << "\n\n";
}

// Which implementation choices can account for each class of disagreement, and the criterion.
void write_classes(std::ostream& md, const VariantsStudy& s) {
  md << "\n## What can account for each class of disagreement\n\n"
        "For each class of [comparison.md](comparison.md) and each variant: how many of the "
        "class's cells agree with the paper under the variant: the same stability verdict and, "
        "where both are stable, max errors within a factor "
     << agreement_factor()
     << " (a variant that only brings the verdict is shown with its error ratios to the paper, and "
        "does not count), and how many cells that agree fully under the default it breaks (over "
        "all its cells). **Criterion:** a variant *accounts* for a class when at least half of the "
        "class's cells agree under it, and *partly* accounts when it brings some, but fewer than "
        "half, into agreement. As in comparison.md, a run that reaches T with an error over time "
        "of A or more is *meaningless*, never stable: such runs are counted apart, beside the "
        "agreeing cells. The sentences below are generated from the tables.\n\n";
  for (const ComparisonClass* k : variants_disagreement_classes())
    write_class(md, s, *k);
}

// The columns of variants_data.csv coded as numbers, in the order of their codes.
const std::vector<std::string> kMethods = {"mpm", "gimp"};
const std::vector<std::string> kKinds = {"one cell (both stable)",
                                         "the median of the variant's cells",
                                         "the tic of the variant (ratio one, not drawn)"};
constexpr int kOneCell = 0, kMedian = 1, kTic = 2;
constexpr double kTicRatio = 1;  // where a tic's label sits on the ratio axis

int method_code(const std::string& column) {
  return int(std::find(kMethods.begin(), kMethods.end(), column) - kMethods.begin());
}

}  // namespace
}  // namespace studies::variants_report

std::string variants_markdown(const Spec& spec, const VariantsStudy& s, bool have_courant) {
  using namespace studies::variants_report;
  std::ostringstream md;
  md << "## Results\n\n";
  write_reading(md, s);
  write_method(md, spec, have_courant);
  write_every_variant(md, s);
  write_per_method(md, s);
  write_classes(md, s);
  return md.str();
}

std::string variants_data_csv(const VariantsStudy& s, const std::string& header_lines) {
  using namespace studies::variants_report;
  std::ostringstream csv;
  csv << header_lines << "# x: the variant's position; method: " << codes(kMethods)
      << "; kind: " << codes(kKinds) << "\nx,method,kind,ratio,variant\n";
  for (std::size_t j = 0; j < s.variants.size(); ++j) {
    const auto& v = s.variants[j];
    for (const auto& [column, r] : v.error_ratios)
      csv << j + 1 << ',' << method_code(column) << ',' << kOneCell << ',' << shortest(r) << ','
          << v.name << "\n";
    for (const auto& [column, m] : v.by_method) {
      if (const auto& med = m.median_error_ratio)
        csv << j + 1 << ',' << method_code(column) << ',' << kMedian << ',' << shortest(*med) << ','
            << v.name << "\n";
    }
  }
  // The tics last: gnuplot keeps the last label given at a position.
  for (std::size_t j = 0; j < s.variants.size(); ++j)
    csv << j + 1 << ',' << method_code("gimp") << ',' << kTic << ',' << kTicRatio << ','
        << s.variants[j].name << "\n";
  return csv.str();
}

}  // namespace mpmstab
