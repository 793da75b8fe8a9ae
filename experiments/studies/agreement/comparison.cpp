// The rules that give a Table 1 cell its verdict and class against the paper, and the
// comparison study's registration. Its report (comparison.md, comparison.csv) is written in
// comparison_report.cpp.
#include "agreement/comparison.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "base/result.hpp"
#include "csv.hpp"
#include "key.hpp"
#include "report_util.hpp"
#include "run_row.hpp"
#include "study.hpp"

namespace mpmstab {

namespace studies::comparison {
namespace {
using ojson = nlohmann::ordered_json;

// The condition every run of ours that reaches T meets in the classes that compare errors.
std::string stable_ours() {
  return "ours reaches T with an error over time below A (an error over time of at least A is the "
         "class ours-meaningless)";
}

// The two classes where the verdicts agree.
std::vector<ComparisonClass> agreement_classes() {
  const std::string f = agreement_factor();
  return {
      {"agree-stable", "Agree: both stable, max errors within a factor " + f,
       "The paper gives a max error (its run stable); " + stable_ours() +
           "; the two max errors are within a factor " + f + " of each other.",
       ClassKind::agreement},
      {"agree-unstable", "Agree: both unstable",
       "The paper marks the cell `*` (unstable); ours fails before T.", ClassKind::agreement},
  };
}

// The failure classes (failure_class()), the meaningless one and the one without a verdict.
std::vector<ComparisonClass> failure_classes() {
  const std::string f = agreement_factor();
  // The failure classes (failure_class()) share their first condition.
  const std::string goes_on =
      "The paper's run lasts longer than ours, which fails before T (a Table 1 cell: the paper "
      "gives a max error, ours fails; a figure: the paper's run reaches T, or takes more than " +
      f + " times as many steps as ours before it fails)";
  const std::string below =
      ", at a c dt / h at or below the spectral limit (or with none recorded) and below the "
      "scan's edge (both as in the classes above)";
  return {
      {"above-spectral-limit", "Paper's run lasts longer; ours fails above the spectral limit",
       goes_on +
           ", at a Courant number c dt / h above the spectral limit of its scheme at its layout "
           "(the record's `courant_spectral`, spectral.md).",
       ClassKind::verdict},
      {"above-our-edge",
       "Paper's run lasts longer; ours fails at or below the spectral limit, at or above the "
       "scan's edge",
       goes_on + ", at a c dt / h at or below the spectral limit (or with none recorded) and at or "
                 "above the courant scan's edge for its method and A: the smallest c dt / h of the "
                 "scan from which on each run of the scan, at each E, fails.",
       ClassKind::verdict},
      {"gimp-wall-exit",
       "Paper's run lasts longer; ours, not mpm, fails with a particle leaving the domain",
       goes_on + below +
           ", by a method other than mpm (GIMP in Table 1), with a particle leaving the domain "
           "through a wall (`left_domain`).",
       ClassKind::verdict},
      {"mpm-crossing-failure",
       "Paper's run lasts longer; ours, mpm, fails with its particles inside the domain",
       goes_on + below +
           ", by mpm, for a reason other than a particle leaving the domain (`nonpositive_F`, "
           "for one). The predicate reads no crossing count: the word crossing in the id "
           "names no measured cause.",
       ClassKind::verdict},
      {"other-failure", "Paper's run lasts longer; ours fails, in no class above",
       goes_on + ", and the cell is not in the four classes above.", ClassKind::verdict},
      {"ours-meaningless", "Ours meaningless: reached T, error over time at least A",
       "The paper's value is readable (a max error or `*`); ours reaches T with an error over "
       "time of at least A. It agrees with neither of the paper's verdicts and its error is "
       "not compared.",
       ClassKind::verdict},
      {"ours-too-short", "Ours without a verdict: too few steps, or under a wave pass",
       "The paper's value is readable (a max error or `*`); ours reached T in fewer than " +
           std::to_string(kMinStepsToJudge) + " steps, or stable in fewer than " +
           shortest(kMinWavePasses) +
           " wave pass c T / L: too short for a stability verdict. It agrees with neither of "
           "the paper's verdicts and its error is not compared.",
       ClassKind::verdict},
  };
}

// The classes where both runs are stable and the errors differ, and the rest.
std::vector<ComparisonClass> error_classes() {
  const std::string f = agreement_factor();
  return {
      {"mpm-error-larger", "MPM: both stable, our max error more than " + f + " times the paper's",
       "The paper gives a max error; " + stable_ours() + ", by mpm, with a max error more than " +
           f + " times the paper's.",
       ClassKind::error},
      {"gimp-error-larger",
       "Not mpm (GIMP in Table 1): both stable, our max error more than " + f +
           " times the paper's",
       "The paper gives a max error; " + stable_ours() +
           ", by a method other than mpm, with a max error more than " + f + " times the paper's.",
       ClassKind::error},
      {"error-smaller", "Both stable, the paper's max error more than " + f + " times ours",
       "The paper gives a max error; " + stable_ours() + "; the paper's max error is more than " +
           f + " times ours.",
       ClassKind::error},
      {"paper-unstable-ours-stable", "Paper unstable, ours stable",
       "The paper marks the cell `*`; " + stable_ours() + ".", ClassKind::verdict},
      {"unreadable", "Paper value unreadable, or our error not recorded",
       "The paper's value is missing from the transcription (or the cell is not in it), or "
       "both runs are stable and our compared error was not recorded.",
       ClassKind::unreadable},
  };
}

}  // namespace
}  // namespace studies::comparison

const std::vector<ComparisonClass>& comparison_classes() {
  using namespace studies::comparison;
  static const std::vector<ComparisonClass> classes = [] {
    std::vector<ComparisonClass> all = agreement_classes();
    for (auto part : {failure_classes(), error_classes()})
      all.insert(all.end(), part.begin(), part.end());
    return all;
  }();
  return classes;
}

std::string semicolon_list(const std::vector<std::string>& v) {
  std::string out;
  for (const auto& x : v)
    out += (out.empty() ? "" : "; ") + x;
  return out.empty() ? std::string("none") : out;
}

const ComparisonClass* find_class(const std::string& id) {
  for (const auto& k : comparison_classes())
    if (id == k.id) return &k;
  return nullptr;
}

std::string comparison_classes_markdown() {
  std::string md = "| class | name | what its predicate decides |\n|---|---|---|\n";
  for (const auto& k : comparison_classes())
    md += std::string("| `") + k.id + "` | " + k.title + " | " + k.definition + " |\n";
  return md;
}

const std::string& explained_definition() {
  static const std::string text =
      "a cell that disagrees with the paper is explained by an experiment of this report when "
      "the experiment reruns the cell with one documented choice changed alone and the rerun "
      "agrees with the paper (class agree-stable or agree-unstable by the same rules). Of the "
      "experiments this report reads, walls reruns Table 1 cells so (periodic boundaries "
      "instead of Dirichlet walls, for the cells it holds); the variants study, of the studies "
      "tier, does the same for each documented choice and is linked, not read";
  return text;
}

double scan_courant(const nlohmann::ordered_json& row) {
  constexpr double kResolution = 1e4;  // steps per unit of c dt / h
  return std::round(RunRow(row).courant.value() * kResolution) / kResolution;
}

CourantEdges courant_edges(const std::vector<nlohmann::ordered_json>& rows) {
  std::map<std::pair<std::string, Key>, std::map<Key, bool>> all_fail;  // -> C -> all fail
  for (const auto& r : rows) {
    const auto key = std::make_pair(RunRow(r).method, Key(r["A"].get<double>(), "A"));
    auto [it, fresh] = all_fail[key].try_emplace(Key(scan_courant(r), "c dt/h"), true);
    it->second = it->second && outcome(r) == "unstable";
  }
  CourantEdges edge;
  for (const auto& [key, by_c] : all_fail) {
    double e = std::numeric_limits<double>::infinity();
    for (auto it = by_c.rbegin(); it != by_c.rend() && it->second; ++it)
      e = it->first;
    edge[key] = e;
  }
  return edge;
}

bool CellVerdict::same_verdict() const {
  if (agreement) return verdicts_agree(*agreement);
  const ComparisonClass* k = find_class(cls);
  return k && (k->kind == ClassKind::agreement || k->kind == ClassKind::error);
}

void AgreementCounts::add(const CellVerdict& v) {
  if (!v.compared()) return;
  ++verdicts_compared;
  if (v.same_verdict()) ++verdicts_agree;
  if (v.cls == "ours-meaningless") ++meaningless;
  if (v.error_ratio) {
    ++errors_compared;
    if (v.cls == "agree-stable") ++errors_within;
    error_ratios.push_back(*v.error_ratio);
  }
  if (v.dt_stable_ratio) dt_stable_ratios.push_back(*v.dt_stable_ratio);
}

std::string failure_class(const nlohmann::ordered_json& r, const CourantEdges& edges) {
  const RunRow run(r);
  const std::string& method = run.method;
  const double courant = *run.courant;
  const auto edge = edges.find({method, Key(*run.A, "A")});
  // A run without a failure (too short for a verdict, say) has no reason: it is no wall exit.
  const std::string reason = run.failure_reason.value_or("");
  if (run.above_spectral_limit()) return "above-spectral-limit";
  if (edge != edges.end() && courant >= edge->second * (1 - 1e-9)) return "above-our-edge";
  if (method != "mpm" && reason == "left_domain") return "gimp-wall-exit";
  if (method == "mpm" && reason != "left_domain") return "mpm-crossing-failure";
  return "other-failure";
}

CellVerdict classify(const nlohmann::ordered_json& r, const PaperCell* paper,
                     const CourantEdges& edges, ErrorAt error_at) {
  using enum CellAgreement;
  CellVerdict cell;
  const RunRow run(r);
  const CellAgreement agreement = cell_agreement(run, paper);
  cell.agreement = agreement;
  // The cell, given its verdict and class.
  const auto with = [&cell](std::string verdict, std::string cls) {
    cell.verdict = std::move(verdict);
    cell.cls = std::move(cls);
    return cell;
  };
  if (agreement == unreadable) return with("paper unreadable", "unreadable");
  if (paper->dt_stable.kind == PaperValue::number && r["dt_stable_min"].is_number() &&
      run.outcome == "stable") {
    cell.dt_stable_ratio = r["dt_stable_min"].get<double>() / paper->dt_stable.value;
  }
  const std::string paper_verdict = paper_says_stable(*paper) ? "paper stable" : "paper unstable";
  switch (agreement) {
    case ours_meaningless:
      // It survived, but its answer is as large as the solution: it agrees with neither verdict.
      return with(paper_verdict + ", ours meaningless", "ours-meaningless");
    case ours_too_short:
      return with(paper_verdict + ", ours too short for a verdict", "ours-too-short");
    case both_stable: {
      // Stable in both: by the factor between the max errors.
      const std::optional<double> error = compared_error(r, error_at);
      if (!error) return with("our error not recorded", "unreadable");
      const double paper_error = paper->max_error.value;
      cell.error_ratio = *error / paper_error;
      if (within_agreement_factor(*error, paper_error)) return with("agree", "agree-stable");
      const double q = *cell.error_ratio;
      const char* larger = run.method == "mpm" ? "mpm-error-larger" : "gimp-error-larger";
      return with("differ: our error " +
                      beside_thresholds(q, {kAgreementFactor, 1 / kAgreementFactor}) + "x",
                  q > 1 ? larger : "error-smaller");
    }
    case both_unstable:
      return with("agree: both unstable", "agree-unstable");
    case paper_unstable_ours_stable:
      return with("paper unstable, ours stable", "paper-unstable-ours-stable");
    default:
      return with("paper stable, ours unstable", failure_class(r, edges));
  }
}

namespace studies::comparison {
namespace {

// The study: every Table 1 cell of the table1 experiment against the paper, explained by the
// supporting experiments of the paper tier (the variants study, in the studies tier, is linked,
// not read).
void write_derived_comparison(const DerivedContext& c) {
  std::optional<ErrorAt> error_at;
  if (c.options.contains("error_at"))
    error_at = parse_error_at(c.options["error_at"].get<std::string>());
  write_comparison(c.inputs, c.out, error_at);
}

const StudyRegistration kComparison{{
    .name = "comparison",
    .summary = "every Table 1 cell and Figs. 1-3 against the paper; per class, the cells a rerun "
               "explains",
    .has_cases = false,
    .inputs = {{.name = "table1", .required = true},
               {.name = "peers"},
               {.name = "courant"},
               {.name = "walls"},
               {.name = "crossing"},
               {.name = "eq108"},
               {.name = "fig1"},
               {.name = "fig2"},
               {.name = "fig3"},
               {.name = "fig2_variants"},
               {.name = "fig3_variants"}},
    .index = [](const Spec&, const std::vector<ojson>&, const ojson&) -> std::string {
      return "**Against the paper:** [comparison.md](comparison.md) sets every Table 1 cell "
             "beside the paper's, with a verdict and a class, and says per class how many of its "
             "cells a rerun of ours explains (brings to agreement with the paper) and how many "
             "it leaves unexplained; then what the paper's text says about its Figs. 1-3 beside "
             "our runs of them.\n\n";
    },
    .write_derived = write_derived_comparison,
    .blessed = {{.file = "comparison.csv",
                 .key_columns = {"method", "E", "A", "dt"},
                 .value_columns = {"verdict", "class"},
                 .what = "comparison verdicts"}},
}};

}  // namespace
}  // namespace studies::comparison

}  // namespace mpmstab
