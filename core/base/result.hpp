// Everything one run measures (docs/theory.md, "Measured quantities").
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "base/failure.hpp"
#include "base/params.hpp"

namespace mpmstab {

// One row per recorded step. A field whose observer is off holds nullopt.
// How a spectral limit was computed: the dense map of every particle (walls included), or the
// Bloch symbol of the interior of a uniform layout (bloch.hpp).
enum class SpectralAnalysis { dense, bloch };
constexpr std::string_view to_string(SpectralAnalysis a) {
  return a == SpectralAnalysis::bloch ? "bloch" : "dense";
}

struct HistoryRow {
  std::int64_t step = 0;
  double time = 0;
  std::optional<double> error;            // max_p |u_p - u(X_p, t)| after this step
  std::optional<double> dt_stable;        // eq. (108) from the state after this step
  std::optional<std::int64_t> crossings;  // cumulative
  // The energy observer's values (energy.hpp) and the exact ones at this time.
  std::optional<double> kinetic, strain, work, energy_balance;
  std::optional<double> kinetic_exact, strain_exact, work_exact;
  // Observe::tip: x_p - X_p of the body's last particle and the exact u(X_p, t) there.
  std::optional<double> tip_u, tip_u_exact;
};

// The particles at the end of the run (at T, or at the failure) with the exact solution there.
// Values are as the solver left them; a failed run may hold non-finite values.
struct FinalState {
  double time = 0;
  Eigen::ArrayXd X, x, v, F, sigma;              // reference position and state
  Eigen::ArrayXd u_exact, v_exact, sigma_exact;  // exact solution at (X_p, time)
};

// The verdict of a run (docs/studies.md, "Outcomes"): unstable (it stopped with a failure),
// meaningless (it survived to T but its error over time reached the amplitude A: the answer is as
// large as the solution), stable (survived, error over time below A), or too_short (it reached T
// in fewer than kMinStepsToJudge steps: so few steps judge nothing, whatever its error).
enum class Outcome { unstable, meaningless, stable, too_short };

// A run that reaches T in fewer steps than this gets no verdict but too_short.
inline constexpr long long kMinStepsToJudge = 10;
// A run that reached T in fewer wave passes c T / L than this is too short to show an
// instability that takes a wave across the body: whatever its outcome says, it is not called
// stable, and an edge search over runs this short finds no edge (docs/studies.md, "Outcomes").
inline constexpr double kMinWavePasses = 1;

std::string_view to_string(Outcome o);

struct RunResult {
  RunParams params;
  std::int64_t particles = 0;
  std::int64_t steps_planned = 0;  // fixed-step policies; 0 when the policy adapts dt
  std::int64_t steps = 0;          // steps completed (the failing step included)
  // Smallest and largest dt used; the last step, shortened to land on T, is not counted unless
  // it is the only one.
  double dt_min = 0;
  double dt_max = 0;
  double dt_mean = 0;  // time reached / steps (T / steps for a run that reached T); 0 if no step

  bool stable = false;
  std::optional<Failure> failure;  // set when !stable
  bool interrupted = false;        // cancelled before the end: incomplete, no verdict

  // Table 1's "Max Error": max_p |u_p(T) - u(X_p, T)|, stable runs only.
  std::optional<double> max_error;
  // Largest error over all steps completed before a failure (observer error_over_time).
  std::optional<double> max_error_over_time;
  // The root mean square of the displacement error over the body and the steps completed before
  // a failure (observer error_l2, error_l2.hpp).
  std::optional<double> error_l2_time;
  // The energy observer's summary (observer energy, energy.hpp): the largest balance error and
  // the largest difference from the exact energy, both per the initial energy, the balance
  // error's drift per period of the exact solution, and the first step whose balance error
  // exceeds kEnergyWarning.
  std::optional<double> energy_error_max;
  std::optional<double> energy_exact_error_max;
  std::optional<double> energy_drift;
  std::optional<std::int64_t> energy_warning_step;
  // The run survived but its error over time reached A: the answer is as large as the solution.
  // Unset when the run failed or error_over_time was not observed.
  std::optional<bool> meaningless;
  // unstable, meaningless or stable; unset only for a run that survived without observing its
  // error over time (the edge search's probes), whose meaningfulness is unknown.
  std::optional<Outcome> outcome;
  std::optional<std::int64_t> crossings;
  std::optional<double> dt_stable_min;  // min of eq. (108) over the steps (observer dt_stable)
  // The same under each StableDtOptions, by option_index (observe.dt_stable_every_option).
  std::array<std::optional<double>, kStableDtOptionCount> dt_stable_min_of_option;
  // The spectral limit of the scheme at the initial layout (observe.spectral; none when the
  // state is too large for the dense solver or nothing amplifies up to kMaxSpectralCourant):
  // c dt / h, and dt for this E.
  std::optional<double> courant_spectral;
  std::optional<double> dt_spectral;
  std::optional<SpectralAnalysis> spectral_analysis;  // how courant_spectral was computed

  double c = 0;         // wave speed sqrt(E / rho0)
  double dt_cfl = 0;    // h / c, the classical speed-of-sound limit
  double dt_sound = 0;  // 1 / c, Table 2's "dt_sound" column
  double courant = 0;   // c dt / h: dt the fixed step, or the largest adaptive one (0 if none)

  double wall_seconds = 0;
  double ns_per_particle_step = 0;

  std::vector<HistoryRow> history;        // only when params.observe.history
  std::optional<FinalState> final_state;  // only when params.observe.final_state
};

}  // namespace mpmstab
