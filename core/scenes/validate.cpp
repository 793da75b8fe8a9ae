#include "scenes/validate.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include "scenes/scene_registry.hpp"

namespace mpmstab {

namespace {

// The issues found so far, each naming its key.
struct Issues {
  std::vector<ParamIssue> list;
  void operator()(std::string key, std::string message) {
    list.push_back({std::move(key), std::move(message)});
  }
};

constexpr int kMaxCells = 10'000'000;
constexpr int kMaxPpc = 64;

bool positive_finite(double v) {
  return std::isfinite(v) && v > 0;
}

// 1. The physical values and the time: E, A, T, dt, and the factors of the policies.
void check_values(const RunParams& p, Issues& bad) {
  if (!positive_finite(p.E)) bad("E", "must be a finite number > 0, got " + exact_text(p.E));
  if (!std::isfinite(p.A) || !(p.A >= 0))
    bad("A", "must be a finite number >= 0, got " + exact_text(p.A));
  if (!positive_finite(p.T)) bad("T", "must be a finite number > 0, got " + exact_text(p.T));
  const bool fixed = p.stepping.policy == TimeStepPolicy::fixed;
  if (fixed && !positive_finite(p.dt)) {
    bad("dt", "must be a finite number > 0, got " + exact_text(p.dt));
  } else if (fixed && positive_finite(p.T) && p.dt > p.T) {
    bad("dt", "must not exceed T = " + exact_text(p.T) + ", got " + exact_text(p.dt));
  }
  if (!positive_finite(p.stepping.cfl_factor)) {
    bad("cfl_factor", "must be a finite number > 0, got " + exact_text(p.stepping.cfl_factor));
  }
  if (!positive_finite(p.stepping.safety)) {
    bad("safety", "must be a finite number > 0, got " + exact_text(p.stepping.safety));
  }
}

// 2. The grid and the particles, and the memory they take.
void check_resolution(const RunParams& p, Issues& bad) {
  if (p.cells < 1 || p.cells > kMaxCells) {
    bad("cells", "must be an integer in [1, " + std::to_string(kMaxCells) + "], got " +
                     std::to_string(p.cells));
  }
  if (p.ppc < 1 || p.ppc > kMaxPpc) {
    bad("ppc",
        "must be an integer in [1, " + std::to_string(kMaxPpc) + "], got " + std::to_string(p.ppc));
  }
  if (p.cells >= 1 && p.ppc >= 1 && run_bytes(p) > kMaxRunBytes) {
    bad("cells", "cells * ppc = " + exact_text(double(p.cells) * p.ppc) + " particles need about " +
                     exact_text(std::round(run_bytes(p) / double(1 << 20))) + " MiB (" +
                     std::to_string(kBytesPerParticle) + " bytes per particle); the limit is " +
                     std::to_string(kMaxRunBytes >> 20) + " MiB (" +
                     exact_text(std::floor(double(kMaxRunBytes) / kBytesPerParticle)) +
                     " particles)");
  }
}

// 3. The transfer's own parameters.
void check_transfer(const RunParams& p, Issues& bad) {
  if (p.transfer == Transfer::blend &&
      (!std::isfinite(p.flip_fraction) || !(p.flip_fraction > 0) || !(p.flip_fraction < 1))) {
    bad("flip_fraction",
        "must be a number in (0, 1) for transfer = blend, got " + exact_text(p.flip_fraction));
  }
  for (const auto& [key, order, transfer] :
       {std::tuple{"xpic_order", p.xpic_order, Transfer::xpic},
        std::tuple{"fmpm_order", p.fmpm_order, Transfer::fmpm}}) {
    if (p.transfer == transfer && (order < 1 || order > kMaxTransferOrder)) {
      bad(key, "must be an integer in [1, " + std::to_string(kMaxTransferOrder) +
                   "] for transfer = " + std::string(to_string(transfer)) + ", got " +
                   std::to_string(order));
    }
  }
}

// 4. The particles' layout in their cells.
void check_layout(const RunParams& p, Issues& bad) {
  if (!std::isfinite(p.layout.shift) || !(p.layout.shift > -0.5) || !(p.layout.shift < 0.5)) {
    bad("shift", "must be a number in (-0.5, 0.5) (a fraction of the particle spacing), got " +
                     exact_text(p.layout.shift));
  }
  if (!std::isfinite(p.layout.jitter) || !(p.layout.jitter >= 0) || !(p.layout.jitter < 1)) {
    bad("jitter", "must be a number in [0, 1) (a fraction of the particle spacing), got " +
                      exact_text(p.layout.jitter));
  }
  if (p.layout.jitter > 0 && std::abs(p.layout.shift) + p.layout.jitter / 2 >= 0.5) {
    bad("jitter",
        "|shift| + jitter / 2 must stay below 0.5, so that every particle keeps its "
        "cell; got shift " +
            brief_text(p.layout.shift) + ", jitter " + brief_text(p.layout.jitter));
  }
}

// 5. The wall treatment against the method and the boundaries.
void check_walls(const RunParams& p, Issues& bad) {
  if (p.walls == Walls::modified) {
    if (!is_bspline(p.method)) {
      bad("walls", "the boundary-modified splines apply to bspline2 and bspline3 only, not " +
                       std::string(to_string(p.method)));
    } else if (p.bc != Boundary::dirichlet) {
      bad("walls",
          "boundary-modified splines apply to bc = dirichlet only (a periodic grid has "
          "no walls)");
    } else if (p.cells < 4) {
      bad("cells",
          "boundary-modified splines need cells >= 4 (two modified nodes at each "
          "wall), got " +
              std::to_string(p.cells));
    }
  }
  if (p.walls == Walls::ghost && p.bc != Boundary::dirichlet) {
    bad("walls", "ghost nodes apply to bc = dirichlet only (a periodic grid has no walls)");
  }
  if (!has_eq108(p.method) && is_bspline(p.method) && p.walls == Walls::ghost) {
    bad("walls",
        "a B-spline eliminates its node beyond each wall (linear extrapolation); free "
        "ghost nodes apply to mpm, gimp and cpgimp");
  }
}

// 6. The time-step policy against the method and the size of the spectral problem.
void check_policy(const RunParams& p, Issues& bad) {
  const TimeStepPolicy policy = p.stepping.policy;
  if (p.start == VelocityStart::half_step) {
    if (policy != TimeStepPolicy::fixed && policy != TimeStepPolicy::cfl)
      bad("start", "half_step needs the first dt before the first step: the fixed or cfl policy");
    if (p.scene != SceneKind::bar && p.scene != SceneKind::steffen)
      bad("start", "half_step is defined for the bar and the steffen scene");
  }
  if (!has_eq108(p.method) &&
      (policy == TimeStepPolicy::adaptive || policy == TimeStepPolicy::min)) {
    bad("policy", "the " + std::string(to_string(policy)) +
                      " policy steps by eq. (108), which is derived for mpm, gimp and cpgimp "
                      "only; use fixed or cfl with " +
                      std::string(to_string(p.method)));
  }
  if (policy == TimeStepPolicy::spectral && p.cells >= 1 && p.ppc >= 1 &&
      spectral_state_size(p) > kMaxSpectralState) {
    bad("policy",
        "the spectral policy computes the spectral limit with a dense solver, for at "
        "most " +
            std::to_string(kMaxSpectralState / 2) + " particles (" +
            std::to_string(kMaxSpectralState / 3) + " with apic); got " +
            std::to_string(static_cast<long long>(p.cells) * p.ppc));
  }
}

// 7. The step cap and the history a run keeps in memory.
void check_history(const RunParams& p, Issues& bad) {
  if (p.max_steps < 1) bad("max_steps", "must be >= 1, got " + std::to_string(p.max_steps));
  if (p.observe.history_stride < 1) {
    bad("history_stride", "must be >= 1, got " + std::to_string(p.observe.history_stride));
    return;
  }
  if (!p.observe.history || p.max_steps < 1) return;
  // The rows a run keeps in memory: every stride-th of its steps. The fixed and cfl policies
  // know their step count; a state-dependent policy takes at most max_steps.
  const bool fixed = p.stepping.policy == TimeStepPolicy::fixed;
  std::optional<std::int64_t> steps;
  const std::optional<double> step =
      fixed || p.stepping.policy == TimeStepPolicy::cfl ? fixed_step(p) : std::nullopt;
  if (step && positive_finite(*step) && positive_finite(p.T)) {
    steps = step_count(p.T, std::min(*step, p.T));
  } else if (!fixed && p.stepping.policy != TimeStepPolicy::cfl) {
    steps = p.max_steps;
  }
  if (steps && *steps / p.observe.history_stride > kMaxHistoryRows) {
    bad("history_stride", "keeps " + exact_text(double(*steps / p.observe.history_stride)) +
                              " history rows in memory; the limit is " +
                              exact_text(double(kMaxHistoryRows)) + " (raise history_stride" +
                              (fixed ? "" : " or lower max_steps") + ")");
  }
}

// 8. The scene: the boundaries it is posed with, where its body lies, its free surface, and
// (the block between walls) that its exact motion stays inside the grid until T.
void check_scene(const RunParams& p, Issues& bad) {
  const SceneInfo& scene = scene_info(p.scene);
  const std::string scene_name(scene.name);
  if (!scene.supports(p.bc)) {
    bad("bc", "scene " + scene_name + " does not support bc = " + std::string(to_string(p.bc)));
  }
  const double start = body_start(p), length = body_length(p);
  if (!std::isfinite(length) || !(length > 0) || !(length <= 1)) {
    bad("body_length",
        "must be a number in (0, 1] (the grid is [0, 1]), got " + exact_text(length));
  } else if (!std::isfinite(start) || !(start >= 0) || !(start + length <= 1)) {
    bad("body_start", "the body [" + brief_text(start) + ", " + brief_text(start + length) +
                          "] must lie inside the grid [0, 1]");
  } else if (p.cells >= 1) {
    // Both ends on cell boundaries, so that the body's cells are whole.
    for (const auto& [key, end] :
         {std::pair{"body_start", start}, std::pair{"body_length", length}}) {
      const double in_cells = end * p.cells;
      if (std::abs(in_cells - std::round(in_cells)) > 1e-9 * std::max(1.0, in_cells)) {
        bad(key, "must be a whole number of cells (h = 1 / cells = " + brief_text(1.0 / p.cells) +
                     "), got " + brief_text(end) + " = " + brief_text(in_cells) + " cells");
      }
    }
  }
  if (p.small_mass != SmallMass::none) {
    if (!scene.free_surface) {
      bad("small_mass", "scene " + scene_name +
                            " has no free surface (its body fills the grid): no node has a "
                            "sliver of mass to treat");
    }
    if (!std::isfinite(p.small_mass_fraction) || !(p.small_mass_fraction > 0) ||
        !(p.small_mass_fraction <= 1)) {
      bad("small_mass_fraction",
          "must be a number in (0, 1] (of the mass rho0 h of a full "
          "node), got " +
              exact_text(p.small_mass_fraction));
    }
  }
  if (!std::isfinite(p.tip_load) || !(p.tip_load >= 0)) {
    bad("tip_load", "must be a finite number >= 0 (of the traction E A / (2 L)), got " +
                        exact_text(p.tip_load));
  }
  if (p.scene == SceneKind::block && p.bc == Boundary::dirichlet && std::isfinite(p.T) &&
      positive_finite(p.E) && std::isfinite(p.A) &&
      start + length + p.A * wave_speed(p) * p.T > 1) {
    bad("T", "the block [" + brief_text(start) + ", " + brief_text(start + length) +
                 "] moving at A c = " + brief_text(p.A * wave_speed(p)) +
                 " reaches the wall X = 1 before T = " + brief_text(p.T) +
                 " (use bc = periodic or a shorter T)");
  }
}

// 9. The step count of the fixed-step policies, known before the run: refused if too large
// (the state-dependent policies stop with a step_limit failure when they reach the cap).
void check_step_count(const RunParams& p, Issues& bad) {
  const auto dt = fixed_step(p);
  if (!dt) return;
  const auto n = step_count(p.T, std::min(*dt, p.T));
  const std::string key = p.stepping.policy == TimeStepPolicy::fixed ? "dt" : "cfl_factor";
  if (!n || *n > p.max_steps) {
    bad(key, "T / dt = " + exact_text(p.T / *dt) + " steps exceeds the cap max_steps = " +
                 std::to_string(p.max_steps) + " (raise --max-steps or shorten T)");
  }
}

}  // namespace

std::vector<ParamIssue> validate(const RunParams& p) {
  Issues bad;
  check_values(p, bad);
  check_resolution(p, bad);
  check_transfer(p, bad);
  check_layout(p, bad);
  check_walls(p, bad);
  check_policy(p, bad);
  check_history(p, bad);
  check_scene(p, bad);
  if (bad.list.empty()) check_step_count(p, bad);
  return bad.list;
}

std::optional<ParamIssue> check_given(const RunParams& p, std::string_view key) {
  const TimeStepPolicy policy = p.stepping.policy;
  const std::string name(to_string(policy));
  if (key == "dt" && policy != TimeStepPolicy::fixed) {
    return ParamIssue{"dt", "only with policy fixed (the " + name + " policy chooses dt itself)"};
  }
  if (key == "cfl_factor" && policy != TimeStepPolicy::cfl && policy != TimeStepPolicy::min) {
    return ParamIssue{"cfl_factor",
                      "only with policy cfl or min (the " + name + " policy does not use it)"};
  }
  if (key == "safety" && policy != TimeStepPolicy::adaptive && policy != TimeStepPolicy::min &&
      policy != TimeStepPolicy::spectral) {
    return ParamIssue{"safety", "only with policy adaptive, min or spectral (the " + name +
                                    " policy does not use it)"};
  }
  if (key == "flip_fraction" && p.transfer != Transfer::blend) {
    return ParamIssue{
        "flip_fraction",
        "only with transfer = blend (" + std::string(to_string(p.transfer)) + " does not use it)"};
  }
  for (const auto& [order_key, transfer] :
       {std::pair{"xpic_order", Transfer::xpic}, std::pair{"fmpm_order", Transfer::fmpm}}) {
    if (key == order_key && p.transfer != transfer) {
      return ParamIssue{std::string(order_key),
                        "only with transfer = " + std::string(to_string(transfer)) + " (" +
                            std::string(to_string(p.transfer)) + " does not use it)"};
    }
  }
  if (key == "small_mass_fraction" && p.small_mass == SmallMass::none) {
    return ParamIssue{"small_mass_fraction", "only with small_mass other than none"};
  }
  const SceneInfo& scene = scene_info(p.scene);
  const std::string scene_name(scene.name);
  if ((key == "body_start" || key == "body_length") && scene.fills_grid) {
    return ParamIssue{std::string(key), "scene " + scene_name +
                                            " fills the grid [0, 1]; its body cannot be moved "
                                            "or resized"};
  }
  if (key == "tip_load" && !scene.tip_load) {
    return ParamIssue{"tip_load", "scene " + scene_name +
                                      " has no free end held against a fixed one (only "
                                      "vibration, impulsive and compaction take a tip load)"};
  }
  if (key == "body_start" && scene.fixed_start) {
    return ParamIssue{"body_start", "scene " + scene_name +
                                        " is fixed at the wall X = 0; only body_length can be "
                                        "given"};
  }
  return std::nullopt;
}

const std::vector<std::string>& conditional_parameters() {
  static const std::vector<std::string> keys = {
      "dt",         "cfl_factor", "safety",      "flip_fraction",       "xpic_order",
      "fmpm_order", "body_start", "body_length", "small_mass_fraction", "tip_load"};
  return keys;
}

}  // namespace mpmstab
