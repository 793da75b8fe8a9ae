// Scene edges: the survival and accuracy edges in dt of every scene with a free surface, method
// and small-mass treatment (docs/design.md, "Scenes", "Small-mass nodes"), each beside the dense
// spectral limit of its body, with its verdicts at the edge and just above it rerun on perturbed
// layouts (ensemble.hpp) and every edge rerun for length (edge_length.hpp). The scenes study
// reads these rows for its table.
#include <cmath>
#include <sstream>

#include "claims.hpp"
#include "edge_length.hpp"
#include "ensemble.hpp"
#include "report_util.hpp"
#include "scenes.hpp"
#include "study.hpp"
#include "sweep.hpp"

namespace mpmstab {

namespace {

using ojson = nlohmann::ordered_json;

// The margin an edge may exceed its body's dense spectral limit by and still count as at it:
// the search's own bisection tolerance is 2%.
constexpr double kLimitMargin = 1.05;

RunParams at_dt(RunParams p, double dt) {
  p.stepping.policy = TimeStepPolicy::fixed;
  p.dt = dt;
  return p;
}

// The ensembles of every row with both edges, in row order; then the runs of every edge for
// length.
std::vector<RunParams> edges_follow_up(const FollowUpContext& c) {
  std::vector<RunParams> runs;
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    const ojson& r = c.rows[i];
    if (!has_number(r, "dt_edge") || !has_number(r, "dt_fail")) continue;
    const RunParams& base = c.spec.cases.at(i).params;
    for (const char* column : {"dt_edge", "dt_fail"})
      for (auto& p : ensemble_members(at_dt(base, r[column].get<double>())))
        runs.push_back(std::move(p));
  }
  for (auto& p : all_length_runs(c.rows, c.spec.cases))
    runs.push_back(std::move(p));
  return runs;
}

// Per row with both edges: how many of the perturbed layouts survive at dt_edge and fail at
// dt_fail.
struct Robustness {
  int survive_at_edge = 0, fail_above = 0, members = 0;
};
std::vector<std::optional<Robustness>> robustness(const std::vector<ojson>& rows,
                                                  const std::vector<ojson>& follow_up,
                                                  std::size_t& next) {
  std::vector<std::optional<Robustness>> out(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (!has_number(rows[i], "dt_edge") || !has_number(rows[i], "dt_fail")) continue;
    if (next + 2 * kEnsembleMembers > follow_up.size()) break;
    Robustness r;
    r.members = kEnsembleMembers;
    for (int k = 0; k < kEnsembleMembers; ++k)
      r.survive_at_edge += survived(follow_up[next++]);
    for (int k = 0; k < kEnsembleMembers; ++k)
      r.fail_above += !survived(follow_up[next++]);
    out[i] = r;
  }
  return out;
}

// What the rows and their follow-ups found, over every row.
struct EdgeCounts {
  int rows = 0, with_edge = 0, robust_rows = 0, checked = 0, above = 0, compared = 0;
  int all_survived = 0, meaningless_edges = 0;
  LengthTally length_tally;
  double worst = 0;
};

// The length runs follow every ensemble; none are read when the ensembles are incomplete.
LengthRuns length_runs_of(const std::vector<ojson>& rows, const std::vector<ojson>& follow_up,
                          std::size_t next) {
  std::size_t after = 0;
  for (const auto& r : rows)
    after += has_number(r, "dt_edge") && has_number(r, "dt_fail") ? 2 * kEnsembleMembers : 0;
  return next == after ? read_length_runs(rows, follow_up, next) : LengthRuns{};
}

// One row of the table, counted into `n`.
std::string edge_row(const ojson& r, const std::optional<Robustness>& robust,
                     const LengthRuns& lengths, EdgeCounts& n) {
  ++n.rows;
  const auto edge = courant_of(r, "dt_edge"), fail = courant_of(r, "dt_fail"),
             accurate = courant_of(r, "dt_accurate");
  // Every dt of the scan survives (a step of T itself): no edge to compare with a limit.
  const bool all_survive = edge && !fail;
  n.all_survived += all_survive;
  const std::optional<double> limit = has_number(r, "courant_spectral")
                                          ? std::optional(r["courant_spectral"].get<double>())
                                          : std::nullopt;
  n.with_edge += edge.has_value();
  std::string ratio_text = "–";
  if (edge && limit && !all_survive) {
    ++n.compared;
    const double q = *edge / *limit;
    n.worst = std::max(n.worst, q);
    n.above += q > kLimitMargin;
    ratio_text = fixed(q, 2);
  }
  std::string perturbed = "–";
  if (robust) {
    ++n.checked;
    n.robust_rows +=
        robust->survive_at_edge == robust->members && robust->fail_above == robust->members;
    perturbed = std::to_string(robust->survive_at_edge) + " of " + std::to_string(robust->members) +
                ", " + std::to_string(robust->fail_above) + " of " +
                std::to_string(robust->members);
  }
  std::string at_edge = "–";
  if (edge) {
    const bool meaningless = outcome(r) == "meaningless";
    n.meaningless_edges += meaningless;
    at_edge = (meaningless ? "**meaningless**" : outcome(r)) +
              (has_number(r, "error_at_edge_over_A")
                   ? " (" + significant(r["error_at_edge_over_A"].get<double>(), 2) + " A)"
                   : std::string());
    n.length_tally.add(lasting(lengths, r, "dt_edge"));
  }
  std::ostringstream md;
  md << "| " << text(r, "scene") << " | " << text(r, "method") << " | " << small_mass_of(r) << " | "
     << edge_text(r) << " | " << opt_fixed(fail) << " | " << at_edge << " | "
     << (edge ? lasting_text(lengths, r, "dt_edge") : std::string("–")) << " | "
     << opt_fixed(accurate) << " | "
     << (accurate ? lasting_text(lengths, r, "dt_accurate") : std::string("–")) << " | "
     << opt_fixed(limit) << " | " << ratio_text << " | " << perturbed << " |\n";
  return md.str();
}

std::vector<Claim> edges_claims(const EdgeCounts& n) {
  Claim edge = claim("every-case-has-an-edge",
                     "Every case has a survival edge inside the scan: {with} of {cases}.");
  edge.every("with", n.with_edge, "cases", n.rows);
  Claim robust = claim("edges-survive-perturbation",
                       "Every edge holds on every perturbed layout (all survive at the edge, all "
                       "fail just above it): {robust} of {checked} edges.");
  robust.every("robust", n.robust_rows, "checked", n.checked);
  Claim meaningful = claim("edges-meaningful",
                           "No survival edge is a meaningless run: {meaningless} of {with} are.");
  meaningful.count("meaningless", n.meaningless_edges).count("with", n.with_edge).over(n.with_edge);
  meaningful.holds = n.meaningless_edges == 0;
  const Claim length = length_claim("edges-hold-for-length",
                                    "Every survival edge survives {first}x and {second}x its run "
                                    "length (at most {cap} wave passes): {held} of {tested} do.",
                                    "", n.length_tally);
  Claim limit = claim("edges-at-or-below-limit",
                      "No survival edge lies above {margin} times the dense spectral limit of "
                      "its body: {above} of {compared} with an edge do (the largest ratio is "
                      "{worst}).");
  limit.number("margin", kLimitMargin, 3).count("above", n.above).count("compared", n.compared);
  limit.number("worst", n.worst, 3).over(n.compared);
  limit.holds = n.compared > 0 && n.above == 0;
  return {edge, robust, meaningful, length, limit};
}

// What each column means, every number from the study's own rules.
std::string edges_intro(const ReportContext& ctx) {
  std::ostringstream md;
  md << "Each row: a scene, a method and a small-mass treatment (docs/design.md, \"Small-mass "
        "nodes\"). *Survival edge*: the largest c dt/h probed that survives to T, and the "
        "smallest above it that fails; *accuracy edge*: the largest up to which the error over "
        "time stays within the search's factor of the smallest dt's ("
     << edge_search_text(ctx.spec.study->edge)
     << "); *dense limit*: the spectral limit of the whole body with its free surfaces "
        "(docs/design.md, \"The spectral limit\"); *perturbed*: of "
     << kEnsembleMembers << " layouts perturbed by " << sci(kEnsemblePerturbation)
     << " of the particle spacing, how many survive at the edge and how many fail just above "
        "it; *run at the edge*: its outcome and error over time per A (a meaningless edge is a "
        "run whose error reached A: it survives and answers nothing); *length*: each edge rerun "
        "at "
     << shortest(kLengthFactors[0]) << " and " << shortest(kLengthFactors[1])
     << " times its wave passes (at most " << shortest(kLongPasses)
     << "), holding to the longest it passed or **transient** where it failed.\n\n"
     << "| scene | method | small-mass | survival edge c dt/h | fails at | run at the edge | "
        "survival edge: length | accuracy edge | accuracy edge: length | dense limit | edge / "
        "limit | perturbed: survive at edge, fail above |\n"
        "|---|---|---|---:|---:|---|---|---:|---|---:|---:|---|\n";
  return md.str();
}

StudyReport edges_report(const ReportContext& ctx) {
  const auto& rows = ctx.rows;
  std::size_t next = 0;
  const auto robust = robustness(rows, ctx.follow_up, next);
  const LengthRuns lengths = length_runs_of(rows, ctx.follow_up, next);
  EdgeCounts n;
  std::ostringstream md;
  md << edges_intro(ctx);
  for (std::size_t i = 0; i < rows.size(); ++i)
    md << edge_row(rows[i], robust[i], lengths, n);
  md << "\nAn edge above the dense limit is one at which the growth the limit predicts has "
        "not reached a failure by T (c T is given per scene in the scenes report); every dt up "
        "to T survives where nothing grows at all (the block: no stress). "
     << n.all_survived << " of " << n.rows << " rows survive every dt.\n";
  return StudyReport{.markdown = md.str(), .claims = edges_claims(n)};
}

std::string edges_index(const Spec& spec, const std::vector<ojson>& rows) {
  int with_edge = 0;
  for (const auto& r : rows)
    with_edge += has_number(r, "dt_edge");
  std::ostringstream md;
  md << "**What it shows.** The survival and accuracy edges in c dt/h of " << rows.size()
     << " scene, method and small-mass cases (" << with_edge
     << " with an edge in the scan), each beside the dense spectral limit of its body and "
        "checked on perturbed layouts. ["
     << spec.name << ".md](" << spec.name << ".md)\n";
  return md.str();
}

const StudyRegistration kSceneEdges{{
    .name = "scene_edges",
    .summary = "survival and accuracy edges of every scene, method and small-mass treatment",
    .work = CaseWork::edge_search,
    .records = {.error_over_time = true},
    .follow_up = edges_follow_up,
    .report = edges_report,
    .index = edges_index,
}};

}  // namespace

}  // namespace mpmstab
