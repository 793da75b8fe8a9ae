// The one rule by which a study recommends a setting (a method, a grid and a time step), used by
// every study that advises (methods, tradeoff, edge): docs/design.md, "Advice". A setting is
// recommended only if
//   (a) its Courant number c dt / h is at most the scheme's spectral limit at its layout divided
//       by limit_margin,
//   (b) its error over time (the largest error after any step, never the error at one instant)
//       is at most the target divided by error_margin, in a run that ends stable, and
//   (c) its confirming runs -- the same setting on a grid `refine` times finer at the same c dt/h,
//       on a layout jittered by `jitter`, at an amplitude `amplitude_factor` times smaller (the
//       target scaled with A: the same relative accuracy) and on a run `length_factor` times as
//       long -- all meet (a) and (b) as well.
// The rule, its margins and the confirming runs are printed with every recommendation, with the
// setting's margin in its own scan: the distance to the first larger step the scan ran that is
// unstable or meaningless.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "base/params.hpp"
#include "claims.hpp"

namespace mpmstab {

struct AdviceRule {
  double limit_margin = 1.25;     // (a): c dt / h <= limit / limit_margin
  double error_margin = 2;        // (b): error over time <= target / error_margin
  int refine = 2;                 // (c): cells x refine, dt / refine (same c dt / h)
  double jitter = 0.05;           // (c): each particle moved by up to jitter / 2 of its spacing
  double amplitude_factor = 100;  // (c): A / amplitude_factor, the target likewise
  double length_factor = 4;       // (c): T x length_factor
};
// The confirming runs of one setting, in confirming_runs() order.
inline constexpr std::size_t kConfirmingRuns = 4;
inline constexpr AdviceRule kAdviceRule{};

// (a) on a record: its courant against its courant_spectral (the uniform layout's limit; a
// jittered confirming run is held to the limit of the layout it perturbs). False where either
// is not measured.
bool within_limit(const nlohmann::ordered_json& row, double uniform_limit,
                  const AdviceRule& rule = kAdviceRule);
// (b) on a record: stable (not meaningless, not too short) and max_error_over_time at most
// target / error_margin.
bool meets_target(const nlohmann::ordered_json& row, double target,
                  const AdviceRule& rule = kAdviceRule);
// (a) and (b): a candidate before its confirming runs.
bool candidate(const nlohmann::ordered_json& row, double target,
               const AdviceRule& rule = kAdviceRule);

// The confirming runs of (c) for a setting: [0] the finer grid, [1] the jittered layout, [2] the
// smaller amplitude, [3] the longer run (kConfirmingRuns).
std::vector<RunParams> confirming_runs(const RunParams& p, const AdviceRule& rule = kAdviceRule);

// A setting judged by the whole rule.
struct Advice {
  const nlohmann::ordered_json* row = nullptr;     // the setting
  std::vector<nlohmann::ordered_json> confirming;  // its confirming runs' records, in order
  bool limit_ok = false, error_ok = false, confirmed = false;
  bool recommended() const { return limit_ok && error_ok && confirmed; }
};
Advice judge(const nlohmann::ordered_json& row, double target,
             const std::vector<nlohmann::ordered_json>& confirming,
             const AdviceRule& rule = kAdviceRule);

// "c dt/h <= limit / 1.25; error over time <= target / 2; confirmed on 2x the cells and on a
// layout jittered by 0.5": the rule in words, printed with every recommendation.
std::string describe_rule(const AdviceRule& rule = kAdviceRule);
// One confirming run of `setting` in a few words, named by what it changes: "200 cells: error
// over time 3.1e-5, c dt/h 0.4", "A = 1.5e-4: ...", "T = 4: ...", or its verdict where it did
// not end stable.
std::string describe_confirming(const nlohmann::ordered_json& row,
                                const nlohmann::ordered_json& setting);
// Every confirming run of an advice, "; "-separated.
std::string describe_confirming(const struct Advice& a);

// The setting's margin in its own scan: among `scan`, the runs of the same setting but for its
// step parameter (dt for the fixed policy, C for cfl, s for the others), the first with a larger
// parameter that is unstable or meaningless. "the first failing step of the scan: C = 0.8 (1.6x),
// unstable"; "no larger step of the scan fails (run up to C = 1, 2x)"; "no larger step was run".
std::string margin_text(const nlohmann::ordered_json& setting,
                        const std::vector<nlohmann::ordered_json>& scan);
// The ratio of that first failing parameter to the setting's (nullopt where none fails).
std::optional<double> margin_ratio(const nlohmann::ordered_json& setting,
                                   const std::vector<nlohmann::ordered_json>& scan);

// The setting of a record as a spec case (experiments/*.json): the parameters of
// parameter_names() it sets, so that a test or a user can rerun it and its confirming runs.
nlohmann::ordered_json setting_case(const nlohmann::ordered_json& row);
// A recommended setting as a study stores it in its JSON ("recommended"): the target, the case
// and its own numbers (c dt/h, its spectral limit, its error over time).
nlohmann::ordered_json recommended_json(const Advice& a, double target);

// The claim every advising study makes of its recommendations: each recommended setting meets
// the rule in its own run and in both confirming runs (a property of the records, so a
// recommendation whose confirming run misses the target shows as not holding).
Claim recommendations_claim(const std::vector<Advice>& recommended, double target,
                            const AdviceRule& rule = kAdviceRule);

}  // namespace mpmstab
