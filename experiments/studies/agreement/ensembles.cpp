// The ensembles study: the Table 1 cells near their edge whose ensemble members cost more than
// Table 1's budget in the paper tier (kPaperEnsembleBudget: the cells at dt = 1e-6, 2e8
// particle-steps a member), rerun in the studies tier as ensembles of kEnsembleMembers perturbed
// layouts (ensemble.hpp; docs/studies.md, "Ensembles"). Its cases are Table 1's (cases_from), so
// a run of both tiers computes them once.
#include <sstream>

#include "claims.hpp"
#include "csv.hpp"
#include "report_util.hpp"
#include "run_row.hpp"
#include "shared/ensemble.hpp"
#include "study.hpp"

namespace mpmstab::studies::ensembles {
namespace {

using ojson = nlohmann::ordered_json;

// Findings: the cells rerun here and their ensembles, in row order.
struct EnsembleCell {
  std::size_t row = 0;
  EnsembleResult result;
};

std::vector<EnsembleCell> rerun_cells(const std::vector<ojson>& rows,
                                      const std::vector<ojson>& follow_up) {
  const std::vector<EnsembleResult> all =
      ensemble_results(rows, follow_up, EnsembleNeed::in_studies);
  std::vector<EnsembleCell> cells;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (all[i].need == EnsembleNeed::in_studies) cells.push_back({i, all[i]});
  return cells;
}

// Claims: a sensitive cell is counted, never hidden; none rerun is vacuous, not holding.
std::vector<Claim> ensembles_claims(const std::vector<ojson>& rows,
                                    const std::vector<EnsembleCell>& cells) {
  int sensitive = 0;
  Coverage rerun;
  for (const auto& c : cells) {
    sensitive += c.result.sensitive();
    rerun.add(rows[c.row]);
  }
  Claim a = claim("costly-verdicts-robust",
                  "The verdict of every Table 1 cell near its edge whose ensemble the paper tier "
                  "leaves out survives a perturbation of its layout by a few {unit} of the "
                  "particle spacing",
                  "{sensitive} of {tested} cells rerun as an ensemble of {members} are sensitive");
  a.value("unit", sci(kEnsemblePerturbation, 1))
      .count("sensitive", sensitive)
      .count("tested", static_cast<long long>(cells.size()))
      .count("members", kEnsembleMembers)
      .over(static_cast<long long>(cells.size()));
  a.holds = !cells.empty() && sensitive == 0;
  return {a.on(rerun)};
}

// Rendering: one row per cell rerun.
std::string ensembles_markdown(const std::vector<ojson>& rows,
                               const std::vector<EnsembleCell>& cells) {
  std::ostringstream md;
  md << "## Results\n\nThe Table 1 cells near their edge (the rule of [table1.md](table1.md)) "
        "whose members cost more than "
     << sci(kPaperEnsembleBudget, 2) << " and at most " << sci(kEnsembleMemberBudget, 2)
     << " particle-steps each, which `make reproduce` leaves out, each rerun with "
     << kEnsembleMembers << " layouts shifted or jittered by a few "
     << sci(kEnsemblePerturbation, 1)
     << " of the particle spacing. *robust*: every member ends as the cell does; "
        "**sensitive**: not, with the members' outcomes.\n\n"
        "| E | A | dt | method | c dt/h | A/h | c T | ours: verdict | particle-steps per member | "
        "ensemble |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& c : cells) {
    const ojson& r = rows[c.row];
    md << "| " << shortest(r["E"].get<double>()) << " | " << shortest(r["A"].get<double>()) << " | "
       << param(r["dt"].get<double>()) << " | " << RunRow(r).method << " | "
       << sci(RunRow(r).courant.value()) << " | " << significant(r["A_over_h"].get<double>(), 3)
       << " | " << significant(*RunRow(r).wave_passes, 3) << " | " << verdict(r) << " | " << work(r)
       << " | " << ensemble_text(r, c.result) << " |\n";
  }
  if (cells.empty()) md << "| – | | | | | | | no such cell | | |\n";
  return md.str();
}

const StudyRegistration kEnsembles{{
    .name = "ensembles",
    .summary = "Table 1's costly cells near their edge, rerun as ensembles of perturbed layouts",
    .records = {.error_over_time = true, .dt_stable = true},
    .follow_up =
        [](const FollowUpContext& c) { return ensemble_follow_up(c, EnsembleNeed::in_studies); },
    .report =
        [](const ReportContext& c) {
          const auto cells = rerun_cells(c.rows, c.follow_up);
          ojson json = {{"ensemble", ojson::array()}};
          for (const auto& cell : cells) {
            ojson e = ensemble_json(c.rows[cell.row], cell.result);
            e["case"] = cell.row;
            json["ensemble"].push_back(e);
          }
          return StudyReport{.markdown = ensembles_markdown(c.rows, cells),
                             .json = json,
                             .claims = ensembles_claims(c.rows, cells)};
        },
    .index = [](const Spec& spec, const std::vector<ojson>&, const ojson&) -> std::string {
      return "**What it shows.** Whether the verdicts of Table 1's cells near their edge at the "
             "smallest steps survive a perturbed layout: [" +
             spec.name + ".md](" + spec.name + ".md).\n\n";
    },
}};

}  // namespace
}  // namespace mpmstab::studies::ensembles
