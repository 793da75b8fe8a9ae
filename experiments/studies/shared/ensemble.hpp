// Verdicts that are robust or say they are not (docs/studies.md, "Ensembles"). Near an edge a
// run's verdict can flip with the last bits of its layout. A cell near its edge is rerun as an
// ensemble of kEnsembleMembers layouts perturbed far below the discretisation error (shifted or
// jittered by a few 1e-9 of the particle spacing); its verdict is robust when every member
// agrees with it, and *sensitive* otherwise, with the count ("stable in 5 of 8").
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/params.hpp"
#include "study.hpp"

namespace mpmstab {

inline constexpr int kEnsembleMembers = 8;
// The perturbation unit, as a fraction of the particle spacing h / ppc.
inline constexpr double kEnsemblePerturbation = 1e-9;
// Which cells need an ensemble, from their distance to the edge:
// - unstable at c dt/h at or above the scheme's spectral limit: linear growth decides it (far);
// - unstable below the limit, and meaningless: nonlinear growth near a threshold (near);
// - stable with an error over time of at least kNearErrorFraction A, or c dt/h above the limit /
//   kNearLimitMargin: near; other stable runs: far;
// - too short to judge: no verdict to test.
// Table 1 (the paper tier, make reproduce) reruns the near cells whose members cost at most
// kPaperEnsembleBudget particle-steps each; the ensembles study (the studies tier, make studies)
// reruns those between that and kEnsembleMemberBudget (the cells at dt = 1e-6: 1e6 steps of 200
// particles a member); a near cell above that is not run, and says so.
inline constexpr double kNearErrorFraction = 0.1;
inline constexpr double kNearLimitMargin = 1.25;
inline constexpr double kPaperEnsembleBudget = 2.5e7;
inline constexpr double kEnsembleMemberBudget = 2.5e8;

// in_studies: near, rerun by the ensembles study rather than by Table 1 (its members cost more
// than kPaperEnsembleBudget each).
enum class EnsembleNeed { far_linear, far_margin, near, in_studies, too_costly, no_verdict };
// What a Table 1 cell needs: near only within kPaperEnsembleBudget.
EnsembleNeed ensemble_need(const nlohmann::ordered_json& row);
// "far: c dt/h >= limit", "near", ...: why a cell was or was not rerun.
std::string need_text(EnsembleNeed need);

// The members of a cell's ensemble: shifts of -2, -1, 1, 2 and jitters of 1..4 units.
std::vector<RunParams> ensemble_members(const RunParams& base);

// A cell's verdict against its ensemble.
struct EnsembleResult {
  EnsembleNeed need = EnsembleNeed::far_margin;
  int members = 0;     // run (0 where not run)
  int agreeing = 0;    // members whose outcome is the cell's
  std::string counts;  // "unstable 5, stable 3" (outcomes of the members)
  long long first_failure = -1, last_failure = -1;  // failing members' steps, -1 if none
  bool sensitive() const { return members > 0 && agreeing < members; }
};
// members: the flat rows of the cell's ensemble, in ensemble_members order.
EnsembleResult ensemble_result(const nlohmann::ordered_json& row, EnsembleNeed need,
                               const std::vector<nlohmann::ordered_json>& members);
// The role of an ensemble's member among a study's follow-up runs.
inline constexpr const char* kEnsembleMember = "ensemble member";
// The follow-up runs of a study that reruns its cells of need `need` as ensembles: the members
// of each such cell, each asked for its cell.
std::vector<FollowUp> ensemble_follow_up(const FollowUpContext& c, EnsembleNeed need);
// Every row's ensemble, the members of the rows of need `need` being the follow-up runs asked
// for that row (ensemble_follow_up), the other rows' without members.
std::vector<EnsembleResult> ensemble_results(const std::vector<nlohmann::ordered_json>& rows,
                                             const std::vector<nlohmann::ordered_json>& follow_up,
                                             EnsembleNeed need);
// "robust: 8 of 8 unstable (steps 3754-3811)", "sensitive: stable in 5 of 8", "not run: far
// (c dt/h >= limit)": the cell's label in a report.
std::string ensemble_text(const nlohmann::ordered_json& row, const EnsembleResult& e);
nlohmann::ordered_json ensemble_json(const nlohmann::ordered_json& row, const EnsembleResult& e);

}  // namespace mpmstab
