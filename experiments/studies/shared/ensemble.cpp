#include "shared/ensemble.hpp"

#include <map>
#include <sstream>

#include "report_util.hpp"
#include "run_row.hpp"

namespace mpmstab {

using ojson = nlohmann::ordered_json;

EnsembleNeed ensemble_need(const ojson& row) {
  const RunRow r(row);
  const std::string& o = r.outcome;
  if (o == "too_short" || o.empty()) return EnsembleNeed::no_verdict;
  const double c = *r.courant;
  const bool has_limit = r.courant_spectral.has_value();
  const double limit = r.courant_spectral.value_or(0);
  EnsembleNeed need = EnsembleNeed::near;
  if (o == "unstable" && has_limit && c >= limit) need = EnsembleNeed::far_linear;
  if (o == "stable") {
    const double eot = r.error_over_time.value_or(0);
    const bool near =
        eot >= kNearErrorFraction * *r.A || (has_limit && c > limit / kNearLimitMargin);
    need = near ? EnsembleNeed::near : EnsembleNeed::far_margin;
  }
  if (need == EnsembleNeed::near && r.particle_steps() > kPaperEnsembleBudget)
    need = r.particle_steps() > kEnsembleMemberBudget ? EnsembleNeed::too_costly
                                                      : EnsembleNeed::in_studies;
  return need;
}

std::string need_text(EnsembleNeed need) {
  switch (need) {
    case EnsembleNeed::far_linear:
      return "far: fails at or above its spectral limit";
    case EnsembleNeed::far_margin:
      return "far: stable with margin";
    case EnsembleNeed::near:
      return "near its edge";
    case EnsembleNeed::in_studies:
      return "near its edge, rerun in ensembles.md (make studies)";
    case EnsembleNeed::too_costly:
      return "near its edge, not run (cost)";
    case EnsembleNeed::no_verdict:
      return "no verdict";
  }
  return "?";
}

std::vector<RunParams> ensemble_members(const RunParams& base) {
  std::vector<RunParams> out;
  for (const int k : {-2, -1, 1, 2}) {
    RunParams p = base;
    p.layout.shift = base.layout.shift + k * kEnsemblePerturbation;
    out.push_back(p);
  }
  for (const int k : {1, 2, 3, 4}) {
    RunParams p = base;
    p.layout.jitter = base.layout.jitter + k * kEnsemblePerturbation;
    out.push_back(p);
  }
  return out;
}

std::vector<FollowUp> ensemble_follow_up(const FollowUpContext& c, EnsembleNeed need) {
  std::vector<FollowUp> runs;
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    if (ensemble_need(c.rows[i]) != need) continue;
    for (auto& p : ensemble_members(c.spec.cases[i].params))
      runs.push_back({.of = i, .role = kEnsembleMember, .params = std::move(p)});
  }
  return runs;
}

std::vector<EnsembleResult> ensemble_results(const std::vector<ojson>& rows,
                                             const std::vector<ojson>& follow_up,
                                             EnsembleNeed need) {
  std::vector<EnsembleResult> out;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const EnsembleNeed n = ensemble_need(rows[i]);
    std::vector<ojson> members;
    if (n == need)
      for (const auto* m : follow_ups_of(follow_up, i, kEnsembleMember))
        members.push_back(*m);
    out.push_back(ensemble_result(rows[i], n, members));
  }
  return out;
}

EnsembleResult ensemble_result(const ojson& row, EnsembleNeed need,
                               const std::vector<ojson>& members) {
  EnsembleResult e;
  e.need = need;
  e.members = static_cast<int>(members.size());
  std::map<std::string, int> n;
  for (const auto& m : members) {
    const std::string o = outcome(m);
    ++n[o];
    e.agreeing += o == outcome(row);
    if (o == "unstable" && m["failure_step"].is_number()) {
      const long long s = m["failure_step"].get<long long>();
      if (e.first_failure < 0 || s < e.first_failure) e.first_failure = s;
      if (s > e.last_failure) e.last_failure = s;
    }
  }
  std::ostringstream counts;
  for (const auto& [o, k] : n)
    counts << (counts.tellp() > 0 ? ", " : "") << o << " " << k;
  e.counts = counts.str();
  return e;
}

std::string ensemble_text(const ojson& row, const EnsembleResult& e) {
  if (e.members == 0) return "not run: " + need_text(e.need);
  std::ostringstream s;
  s << (e.sensitive() ? "**sensitive**: " : "robust: ") << outcome(row) << " in " << e.agreeing
    << " of " << e.members;
  if (e.sensitive()) s << " (" << e.counts << ")";
  if (e.first_failure >= 0) {
    s << "; failing members stop at step " << e.first_failure;
    if (e.last_failure != e.first_failure) s << " to " << e.last_failure;
  }
  return s.str();
}

ojson ensemble_json(const ojson& row, const EnsembleResult& e) {
  return {{"need", need_text(e.need)},  {"members", e.members}, {"agreeing", e.agreeing},
          {"sensitive", e.sensitive()}, {"outcomes", e.counts}, {"label", ensemble_text(row, e)}};
}

}  // namespace mpmstab
