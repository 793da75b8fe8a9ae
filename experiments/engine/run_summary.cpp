#include "run_summary.hpp"

#include <cstdio>
#include <optional>
#include <sstream>
#include <type_traits>

#include "base/accuracy.hpp"
#include "base/failure.hpp"
#include "base/params.hpp"
#include "observers/energy.hpp"
#include "run_row.hpp"

namespace mpmstab {

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

namespace {

// A measurement that may be absent: "-" when it is.
template <class T>
std::string fmt(const std::optional<T>& v) {
  if (!v) return "-";
  if constexpr (std::is_floating_point_v<T>) {
    return mpmstab::fmt(*v);
  } else {
    return std::to_string(*v);
  }
}

}  // namespace

std::string text_summary(const RunResult& r, bool with_timing) {
  const RunParams& p = r.params;
  std::ostringstream s;
  const bool fixed = p.stepping.policy == TimeStepPolicy::fixed;
  s << "mpmstab run: " << to_string(p.method) << ", E = " << fmt(p.E) << ", A = " << fmt(p.A)
    << (fixed ? ", dt = " + fmt(p.dt) : ", policy " + std::string(to_string(p.stepping.policy)))
    << ", T = " << fmt(p.T) << ", " << p.cells << " cells x " << p.ppc << " ppc, "
    << to_string(p.bc) << nondefault_choices(p) << "\n";
  // A stable run of fewer than kMinWavePasses wave passes is named as every report names it.
  const bool under_a_pass = stable_under_a_wave_pass(r.outcome == Outcome::stable, wave_passes(p));
  std::string verdict(under_a_pass ? under_a_wave_pass_word(wave_passes(p))
                      : r.outcome  ? to_string(*r.outcome)
                                   : "survived (error over time not measured)");
  if (r.failure) {
    verdict += " (" + std::string(to_string(r.failure->reason)) + " at step " +
               std::to_string(r.failure->step) + ", t = " + fmt(r.failure->time) +
               (r.failure->particle >= 0 ? ", particle " + std::to_string(r.failure->particle)
                                         : std::string()) +
               ")";
  }
  if (r.outcome == Outcome::meaningless) verdict += " (the error over time reached A)";
  if (r.outcome == Outcome::stable && r.max_error_over_time && p.A > 0) {
    const double e = *r.max_error_over_time;
    verdict += ", " + std::string(to_string(accuracy_class(e, p.A))) + " (error over time " +
               fmt(e / p.A) + " A)";
  }
  auto line = [&](std::string_view key, const std::string& value) {
    s << "  " << key << std::string(key.size() < 22 ? 22 - key.size() : 1, ' ') << value << "\n";
  };
  line("verdict", verdict);
  line("steps", std::to_string(r.steps) +
                    (r.steps_planned ? " of " + std::to_string(r.steps_planned) : std::string()) +
                    "  (policy " + std::string(to_string(p.stepping.policy)) + ", dt " +
                    (r.steps ? fmt(r.dt_min) + " to " + fmt(r.dt_max) + ", mean " + fmt(r.dt_mean)
                             : std::string("-")) +
                    ")");
  line("max_error", fmt(r.max_error));
  line("max_error_over_time", fmt(r.max_error_over_time));
  if (p.observe.error_l2) line("error_l2_time", fmt(r.error_l2_time));
  line("dt_stable_min", fmt(r.dt_stable_min) + "  (eq. 108, sigma " +
                            std::string(to_string(p.stable.sigma)) + ", ||v|| " +
                            std::string(to_string(p.stable.vnorm)) + ")");
  line("crossings", fmt(r.crossings));
  if (p.observe.energy) {
    line("energy_error_max", fmt(r.energy_error_max) + "  (balance, per the initial energy)");
    line("energy_exact_error_max", fmt(r.energy_exact_error_max) + "  (against the exact K + U)");
    line("energy_drift", fmt(r.energy_drift) + "  (per period of the exact solution)");
    line("energy_warning_step",
         r.energy_warning_step ? std::to_string(*r.energy_warning_step)
                               : std::string("-  (balance within ") + fmt(kEnergyWarning) + ")");
  }
  line("dt_cfl = h/c", fmt(r.dt_cfl));
  line("dt_sound = 1/c", fmt(r.dt_sound));
  line("courant = c dt/h", fmt(r.courant) + (r.dt_min != r.dt_max ? "  (largest dt)" : ""));
  line("A_over_h = A / h", fmt(amplitude_per_cell(p)));
  line("cT = wave passes", fmt(wave_passes(p)));
  line("particle-steps", std::to_string(r.particles * r.steps));
  if (with_timing) {
    line("wall_seconds", fmt(r.wall_seconds));
    line("ns/particle-step", r.steps ? fmt(r.ns_per_particle_step) : std::string("-"));
  }
  return s.str();
}

}  // namespace mpmstab
