#include "publish/verdicts.hpp"

#include <sstream>

#include "base/params.hpp"
#include "csv.hpp"
#include "report_util.hpp"

namespace mpmstab {

std::string definition(Outcome o) {
  switch (o) {
    case Outcome::unstable:
      return "the run stopped before T with a failure (its reason, step and time are recorded): "
             "the paper's `*`";
    case Outcome::meaningless:
      return "the run reached T, but its error over time reached the amplitude A "
             "(`max_error_over_time >= A`): its answer is as large as the solution; never counted "
             "as stable, nor as agreeing with a stable cell of the paper";
    case Outcome::stable:
      return "the run reached T in at least " + std::to_string(kMinStepsToJudge) +
             " steps with an error over time below A (its accuracy class says how far below)";
    case Outcome::too_short:
      return "the run reached T in fewer than " + std::to_string(kMinStepsToJudge) +
             " steps (`kMinStepsToJudge`), whatever its error: so few steps judge nothing; no "
             "verdict, counted apart with its step count";
  }
  return "";
}

std::string definition(FailureReason r) {
  switch (r) {
    case FailureReason::non_finite:
      return "a state value is not a finite number";
    case FailureReason::nonpositive_F:
      return "some F_p is not positive";
    case FailureReason::collapsed_F:
      return "some F_p below the smallest normal double (" + sci(kSmallestNormalF) +
             "): the particle's volume has collapsed and F_p has lost significant bits";
    case FailureReason::support_too_wide:
      return "cpGIMP: a particle wider than two cells (its half-width above h)";
    case FailureReason::left_domain:
      return "a particle left the grid's domain under Dirichlet walls";
    case FailureReason::step_limit:
      return "a state-dependent time step needed more steps than the cap";
    case FailureReason::dt_collapse:
      return "an adaptive or min policy asked for a step below " + value_text(kDtCollapseFraction) +
             " h / c: the policy itself has failed";
  }
  return "";
}

std::string definition(Accuracy a) {
  const std::string f = shortest(kAccurateFraction);
  switch (a) {
    case Accuracy::accurate:
      return "error over time e < " + f + " A (`kAccurateFraction`)";
    case Accuracy::inaccurate:
      return f +
             " A <= e < A: the run reached T, but its answer is off by a large fraction of "
             "the solution";
    case Accuracy::meaningless:
      return "e >= A: the outcome meaningless";
  }
  return "";
}

namespace studies::verdicts {
namespace {

// Every value of an enum whose values run from 0 and whose definition() covers each of them
// (a switch without a default: the compiler names a value that has none).
template <typename E>
std::vector<E> enum_values() {
  std::vector<E> out;
  for (int i = 0;; ++i) {
    const E e = static_cast<E>(i);
    if (definition(e).empty()) return out;
    out.push_back(e);
  }
}

template <typename E>
std::string verdict_table(const char* header, const std::vector<E>& values) {
  std::ostringstream md;
  md << "| " << header << " | what it means |\n|---|---|\n";
  for (const E e : values)
    md << "| `" << to_string(e) << "` | " << definition(e) << " |\n";
  return md.str();
}

}  // namespace
}  // namespace studies::verdicts

std::vector<Outcome> all_outcomes() {
  return studies::verdicts::enum_values<Outcome>();
}
std::vector<FailureReason> all_failure_reasons() {
  return studies::verdicts::enum_values<FailureReason>();
}
std::vector<Accuracy> all_accuracy_classes() {
  return studies::verdicts::enum_values<Accuracy>();
}

std::string outcomes_table() {
  return studies::verdicts::verdict_table("outcome", all_outcomes());
}
std::string failure_reasons_table() {
  return studies::verdicts::verdict_table("reason", all_failure_reasons());
}
std::string accuracy_classes_table() {
  return studies::verdicts::verdict_table("class", all_accuracy_classes());
}

}  // namespace mpmstab
