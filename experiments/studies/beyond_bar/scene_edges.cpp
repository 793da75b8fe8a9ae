// Scene edges: the survival and accuracy edges in dt of every scene with a free surface, method
// and small-mass treatment (docs/theory.md, "Scenes", "Small-mass nodes"), each beside the dense
// spectral limit of its body, with its verdicts at the edge and just above it rerun on perturbed
// layouts (ensemble.hpp) and every edge rerun for length (edge_length.hpp). The scenes study
// reads these rows for its table.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "base/accuracy.hpp"
#include "claims.hpp"
#include "csv.hpp"
#include "report_util.hpp"
#include "shared/by_scene.hpp"
#include "shared/edge_length.hpp"
#include "shared/ensemble.hpp"
#include "study.hpp"
#include "sweep.hpp"

namespace mpmstab::studies::scene_edges {
namespace {

using ojson = nlohmann::ordered_json;

// The margin an edge may exceed its body's dense spectral limit by and still count as at it:
// the search's own bisection tolerance is 2%.
constexpr double kLimitMargin = 1.05;

// The round-off floor of an error over time, in machine epsilons times A: a run accumulates at
// most a few epsilons of relative error per step, and the scans take at most some 1e5 steps, so
// an error below this is round-off. Where the reference's error (the smallest dt's) is below it,
// the accuracy edge's rule (within a factor of the reference's error) compares round-off with
// round-off, and no accuracy edge is read.
constexpr double kRoundOffEpsilons = 1e6;

double round_off_floor_over_A() {
  return kRoundOffEpsilons * std::numeric_limits<double>::epsilon();
}

bool reference_at_round_off(const ojson& r) {
  return has_number(r, "error_reference_over_A") &&
         r["error_reference_over_A"].get<double>() < round_off_floor_over_A();
}

// Where a row stands in the scan: an edge inside it (a dt that survives with a verdict, and a
// larger one that fails), or none: it survives to the top of the scan (a step of T), the run at
// its largest surviving dt is too short to judge, or no dt probed survives.
enum class ScanEdge { inside, survives_to_top, edge_too_short, none_survives };

ScanEdge scan_edge(const ojson& r) {
  // Runs under a wave pass are too short for a verdict: the search makes none.
  if (RunRow(r).wave_passes.value_or(0) < kMinWavePasses) return ScanEdge::edge_too_short;
  if (!has_number(r, "dt_edge")) return ScanEdge::none_survives;
  // A largest surviving run too short to judge gives no edge, whether or not a larger dt failed.
  if (outcome(r) == "too_short") return ScanEdge::edge_too_short;
  if (!has_number(r, "dt_fail")) return ScanEdge::survives_to_top;
  return ScanEdge::inside;
}

// What each follow-up run of a row is for: a member of its ensemble at dt_edge or at dt_fail, or
// a rerun of an edge for length (edge_length).
constexpr const char* kMemberAtEdge = "ensemble member at dt_edge";
constexpr const char* kMemberAtFail = "ensemble member at dt_fail";

// The ensembles of every row with both edges; the runs of every edge for length.
std::vector<FollowUp> edges_follow_up(const FollowUpContext& c) {
  std::vector<FollowUp> runs;
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    const ojson& r = c.rows[i];
    if (!has_number(r, "dt_edge") || !has_number(r, "dt_fail")) continue;
    RunParams at = c.spec.cases.at(i).params;  // at a fixed step
    at.stepping.policy = TimeStepPolicy::fixed;
    for (const char* column : {"dt_edge", "dt_fail"}) {
      at.dt = r[column].get<double>();
      for (auto& p : ensemble_members(at))
        runs.push_back({.of = i,
                        .role = column == std::string("dt_edge") ? kMemberAtEdge : kMemberAtFail,
                        .params = std::move(p)});
    }
  }
  for (auto& f : all_length_runs(c.rows, c.spec.cases))
    runs.push_back(std::move(f));
  return runs;
}

// Per row with both edges: how many of the perturbed layouts survive at dt_edge and fail at
// dt_fail.
struct Robustness {
  int survive_at_edge = 0, fail_above = 0, members = 0;
};
std::vector<std::optional<Robustness>> robustness(const std::vector<ojson>& rows,
                                                  const std::vector<ojson>& follow_up) {
  std::vector<std::optional<Robustness>> out(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (!has_number(rows[i], "dt_edge") || !has_number(rows[i], "dt_fail")) continue;
    const auto at_edge = follow_ups_of(follow_up, i, kMemberAtEdge);
    const auto at_fail = follow_ups_of(follow_up, i, kMemberAtFail);
    if (at_edge.size() != std::size_t(kEnsembleMembers) ||
        at_fail.size() != std::size_t(kEnsembleMembers))
      continue;
    Robustness r{.members = kEnsembleMembers};
    for (const ojson* m : at_edge)
      r.survive_at_edge += survived(*m);
    for (const ojson* m : at_fail)
      r.fail_above += !survived(*m);
    out[i] = r;
  }
  return out;
}

// The survival edge as the table prints it: its c dt/h (marked where the run there is
// meaningless), or why the row has none inside the scan.
std::string survival_edge_text(const ojson& r) {
  const auto edge = courant_of(r, "dt_edge");
  switch (scan_edge(r)) {
    case ScanEdge::inside:
      return opt_fixed(edge) + (outcome(r) == "meaningless" ? " (meaningless)" : "") +
             monotone_words(r);
    case ScanEdge::survives_to_top:
      return "none in the scan: it survives to its top, a step of T (c dt/h " +
             significant(*edge, 3) + ")";
    case ScanEdge::edge_too_short:
      if (const double passes = RunRow(r).wave_passes.value_or(0); passes < kMinWavePasses)
        return "none: runs of c T = " + param(passes) + " < " + shortest(kMinWavePasses) +
               " wave pass are too short for a verdict";
      return "none in the scan: the run at c dt/h " + (edge ? significant(*edge, 3) : "–") +
             (has_number(r, "dt_fail") ? "" : ", the top of the scan (a step of T),") +
             " is too short to judge";
    case ScanEdge::none_survives:
      if (const auto fail = courant_of(r, "dt_fail"))
        return "none: the smallest c dt/h tried, " + significant(*fail, 3) + ", fails" +
               monotone_words(r);
      return "none in the scan: no dt probed survives";
  }
  return "–";
}

// The run at the largest surviving dt: its outcome, with its error over time per A and, where
// it is stable, its accuracy class.
std::string run_at_edge_text(const ojson& r) {
  const std::string o = outcome(r);
  if (o == "too_short") return verdict(r);
  if (!has_number(r, "error_at_edge_over_A")) return o;
  const double e = r["error_at_edge_over_A"].get<double>();
  const std::string per_A = significant(e, 2) + " A";
  if (o == "meaningless") return "**meaningless** (" + per_A + ")";
  if (o == "stable") return verdict_with_error(r, e);
  return o + " (" + per_A + ")";
}

// "none: the reference is inaccurate (0.3 A)": a run's error over time per A in `column` where
// its class is not accurate; "" where it is accurate or not recorded.
std::string not_accurate(const ojson& r, const char* column, const char* run) {
  if (!has_number(r, column)) return "";
  const double e = r[column].get<double>();
  const Accuracy a = accuracy_class(e, 1.0);
  if (a == Accuracy::accurate) return "";
  return std::string("none: ") + run + " is " + std::string(to_string(a)) + " (" +
         significant(e, 2) + " A)";
}

// The accuracy edge as the table prints it: its c dt/h, or why there is none.
std::string accuracy_edge_text(const ojson& r) {
  if (reference_at_round_off(r))
    return "none: the reference error is at round-off (" +
           sci(r["error_reference_over_A"].get<double>()) + " A)";
  if (const auto accurate = courant_of(r, "dt_accurate")) return opt_fixed(accurate);
  for (const auto& [column, run] : {std::pair{"error_reference_over_A", "the reference"},
                                    std::pair{"error_at_accurate_over_A", "the run at it"}}) {
    const std::string why = not_accurate(r, column, run);
    if (!why.empty()) return why;
  }
  return "–";
}

// What the study finds, from its rows and their follow-up runs (none for the index, which prints
// no finding of them): how many rows have an edge inside the scan, why the others have none and
// their scenes, how many are monotone or have a reference at round-off; of the edges inside the
// scan, how many are meaningless, how they lie against the dense limit (and how long those above
// it hold), how many hold on every perturbed layout and how long they hold; where the rows each
// claim reads lie (run_row.hpp): every row, those with an edge inside the scan, those compared
// with the limit, checked on perturbed layouts and rerun for length.
struct Findings {
  int rows = 0, with_edge = 0, robust_rows = 0, checked = 0, above = 0, compared = 0;
  int monotone = 0;  // rows whose search found survival monotone in dt
  int meaningless_edges = 0;
  int above_under_a_pass = 0;  // edges above the limit whose run covered under a wave pass
  int above_tested = 0, above_held = 0;  // edges above the limit rerun for length, those that held
  // The rows without an edge inside the scan, by why, and their scenes.
  int to_top = 0, edge_too_short = 0, none_survives = 0;
  std::vector<std::string> edgeless_scenes;
  int round_off_references = 0;
  LengthTally length_tally;
  double worst = 0;
  std::vector<std::optional<Robustness>> robust;  // per row
  LengthRuns lengths;
  Coverage all_at, inside_at, compared_at, checked_at, tested_at;
};

// The findings of the rows and their follow-up runs.
Findings find(const std::vector<ojson>& rows, const std::vector<ojson>& follow_up) {
  Findings n{.robust = robustness(rows, follow_up), .lengths = read_length_runs(rows, follow_up)};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ojson& r = rows[i];
    const RunRow rr(r);
    const ScanEdge where = scan_edge(r);
    ++n.rows;
    n.all_at.add(r);
    n.monotone += survival_monotone(r);
    n.round_off_references += reference_at_round_off(r);
    n.to_top += where == ScanEdge::survives_to_top;
    n.edge_too_short += where == ScanEdge::edge_too_short;
    n.none_survives += where == ScanEdge::none_survives;
    if (where != ScanEdge::inside) {
      add_unique(n.edgeless_scenes, text(r, "scene"));
      continue;
    }
    ++n.with_edge;
    n.inside_at.add(r);
    n.meaningless_edges += rr.outcome == "meaningless";
    const Lasting lasts = lasting(n.lengths, r, "dt_edge");
    n.length_tally.add(lasts);
    if (lasts.tested) n.tested_at.add(r);
    if (rr.courant_spectral) {
      const double q = *courant_of(r, "dt_edge") / *rr.courant_spectral;
      ++n.compared;
      n.compared_at.add(r);
      n.worst = std::max(n.worst, q);
      n.above += q > kLimitMargin;
      n.above_under_a_pass += q > kLimitMargin && rr.wave_passes.value_or(0) < kMinWavePasses;
      n.above_tested += q > kLimitMargin && lasts.tested;
      n.above_held += q > kLimitMargin && lasts.holds;
    }
    if (const auto& robust = n.robust[i]) {
      ++n.checked;
      n.checked_at.add(r);
      n.robust_rows +=
          robust->survive_at_edge == robust->members && robust->fail_above == robust->members;
    }
  }
  return n;
}

std::vector<Claim> edges_claims(const Findings& n) {
  Claim edge =
      claim("every-case-has-an-edge", "Every case has a survival edge inside the scan",
            "{with} of {cases} do; of the others, {top} survive to the top of the scan (a "
            "step of T), {short} have runs too short to judge (under a wave pass or too few "
            "steps) and {none_survive} fail at the smallest dt tried");
  edge.every("with", n.with_edge, "cases", n.rows).on(n.all_at);
  edge.count("top", n.to_top)
      .count("short", n.edge_too_short)
      .count("none_survive", n.none_survives);
  Claim robust = claim("edges-survive-perturbation",
                       "Every edge inside the scan holds on every perturbed layout (all survive "
                       "at the edge, all fail just above it)",
                       "{robust} of {checked} edges do");
  robust.every("robust", n.robust_rows, "checked", n.checked).on(n.checked_at);
  Claim meaningful =
      claim("edges-meaningful", "No survival edge inside the scan is a meaningless run",
            "{meaningless} of {with} are");
  meaningful.count("meaningless", n.meaningless_edges).count("with", n.with_edge).over(n.with_edge);
  meaningful.holds = n.meaningless_edges == 0;
  meaningful.on(n.inside_at);
  Claim length = length_claim("edges-hold-for-length",
                              "Every survival edge inside the scan survives {first}x and "
                              "{second}x its run length (at most {cap} wave passes)",
                              "{held} of {tested} do", n.length_tally);
  length.on(n.tested_at);
  Claim limit = claim("edges-at-or-below-limit",
                      "No survival edge inside the scan lies above {margin} times the dense "
                      "spectral limit of its body",
                      "{above} of {compared} edges do, {short_above} of them on runs of fewer "
                      "than {passes} wave pass (the largest ratio is {worst})");
  limit.number("margin", kLimitMargin, 3).count("above", n.above).count("compared", n.compared);
  limit.count("short_above", n.above_under_a_pass).number("passes", kMinWavePasses, 3);
  limit.number("worst", n.worst, 3).over(n.compared).on(n.compared_at);
  limit.holds = n.compared > 0 && n.above == 0;
  Claim mono = claim("survival-monotone", "Survival is monotone in dt in every row",
                     "{monotone} of {rows} rows (where it is not, the edge is the lowest failure "
                     "found)");
  mono.every("monotone", n.monotone, "rows", n.rows).on(n.all_at);
  return {edge, robust, meaningful, length, limit, mono};
}

// What each column means, every number from the study's own rules.
std::string edges_intro(const ReportContext& ctx) {
  std::ostringstream md;
  md << "Each row: a scene, a method and a small-mass treatment (docs/theory.md, \"Small-mass "
        "nodes\"). *A/h, c T*: the amplitude and the run length (wave passes) every edge of "
        "the row holds for. *Survival edge*: the largest c dt/h up to which every c dt/h tried "
        "survives to T, and the lowest above it that fails (where a larger one survives again, "
        "**not monotone** and the highest that does); a row has none inside the scan where it "
        "survives to the top of the scan (a step of T), where its runs are too short to judge "
        "(under a wave pass, or too few steps), or where the smallest dt tried fails; *accuracy "
        "edge*: the largest up to which the error over time stays within the search's factor of "
        "the smallest dt's (the reference's) ("
     << edge_search_text(ctx.spec.study->edge)
     << "); none is read where the reference's error over time is at round-off, below "
     << param(kRoundOffEpsilons) << " machine epsilons (" << sci(round_off_floor_over_A())
     << ") times A, nor where the reference or the run at the edge is not accurate (its class and "
        "error over time per A are given); *dense limit*: the spectral limit of the whole body "
        "with its free surfaces (docs/theory.md, \"The spectral limit\"); *perturbed*: of "
     << kEnsembleMembers << " layouts perturbed by " << sci(kEnsemblePerturbation)
     << " of the particle spacing, how many survive at the edge and how many fail just above "
        "it; *run at the edge*: the run at the largest surviving dt, its outcome and error over "
        "time per A, with its accuracy class where it is stable (docs/studies.md, \"Accuracy "
        "classes\"; a meaningless edge is a run whose error reached A: it survives and answers "
        "nothing); *length*: each edge rerun at "
     << shortest(kLengthFactors[0]) << " and " << shortest(kLengthFactors[1])
     << " times its wave passes (at most " << shortest(kLongPasses)
     << "), holding to the longest it passed or **transient** where it failed.\n\n"
     << "| scene | method | small-mass | A/h, c T | survival edge c dt/h | fails at | run at the "
        "edge | survival edge: length | accuracy edge | accuracy edge: length | dense limit | "
        "edge / limit | perturbed: survive at edge, fail above |\n"
        "|---|---|---|---|---:|---:|---|---|---:|---|---:|---:|---|\n";
  return md.str();
}

// One row of the table.
std::string edge_row(const ojson& r, const std::optional<Robustness>& robust,
                     const LengthRuns& lengths) {
  const bool inside = scan_edge(r) == ScanEdge::inside;
  const auto edge = courant_of(r, "dt_edge"), fail = courant_of(r, "dt_fail");
  const bool accurate = !reference_at_round_off(r) && courant_of(r, "dt_accurate").has_value();
  const RunRow rr(r);
  const std::optional<double> limit = rr.courant_spectral;
  std::string perturbed = "–";
  if (robust && inside) {
    perturbed = std::to_string(robust->survive_at_edge) + " of " + std::to_string(robust->members) +
                ", " + std::to_string(robust->fail_above) + " of " +
                std::to_string(robust->members);
  }
  std::ostringstream md;
  md << "| " << text(r, "scene") << " | " << rr.method << " | " << small_mass_of(r) << " | "
     << shortest(number_or_zero(r, "A_over_h")) << ", " << shortest(rr.wave_passes.value_or(0))
     << " | " << survival_edge_text(r) << " | " << (inside ? opt_fixed(fail) : std::string("–"))
     << " | " << (edge ? run_at_edge_text(r) : std::string("–")) << " | "
     << (inside ? lasting_text(lengths, r, "dt_edge") : std::string("–")) << " | "
     << accuracy_edge_text(r) << " | "
     << (accurate ? lasting_text(lengths, r, "dt_accurate") : std::string("–")) << " | "
     << opt_fixed(limit) << " | " << (inside && limit ? fixed(*edge / *limit, 2) : "–") << " | "
     << perturbed << " |\n";
  return md.str();
}

StudyReport edges_report(const ReportContext& ctx) {
  const auto& rows = ctx.rows;
  const Findings n = find(rows, ctx.follow_up);
  std::ostringstream md;
  md << edges_intro(ctx);
  for (std::size_t i = 0; i < rows.size(); ++i)
    md << edge_row(rows[i], n.robust[i], n.lengths);
  md << "\n"
     << n.above << " edges inside the scan lie above " << shortest(kLimitMargin)
     << " times the dense limit: runs that reached T (the column A/h, c T) at a step at which "
        "the linearised map amplifies. Of the "
     << n.above_tested << " rerun for length, " << n.above_held
     << " hold to the longest length and " << n.above_tested - n.above_held << " fail. "
     << n.rows - n.with_edge << " of " << n.rows
     << " rows have no survival edge inside the scan: " << n.to_top << " survive to its top, "
     << n.edge_too_short << " have runs too short to judge (under a wave pass or too few steps), "
     << n.none_survives << " fail at the smallest dt tried";
  if (!n.edgeless_scenes.empty()) md << " (scenes: " << list_of(n.edgeless_scenes) << ")";
  md << ". " << n.round_off_references << " of " << n.rows
     << " rows have a reference error at round-off, and no accuracy edge.\n";
  return StudyReport{.markdown = md.str(), .claims = edges_claims(n)};
}

std::string edges_index(const Spec& spec, const std::vector<ojson>& rows, const ojson&) {
  const Findings n = find(rows, {});
  std::ostringstream md;
  md << "**What it shows.** The survival and accuracy edges in c dt/h of " << n.rows
     << " scene, method and small-mass cases (" << n.with_edge
     << " with a survival edge inside the scan), each beside the dense spectral limit of its body "
        "and checked on perturbed layouts. ["
     << spec.name << ".md](" << spec.name << ".md)\n";
  return md.str();
}

const StudyRegistration kSceneEdges{{
    .name = "scene_edges",
    .summary = "survival and accuracy edges of each scene, method and small-mass treatment",
    .work = CaseWork::edge_search,
    .records = {.error_over_time = true},
    .follow_up = edges_follow_up,
    .report = edges_report,
    .index = edges_index,
}};

}  // namespace
}  // namespace mpmstab::studies::scene_edges
