#include "params.hpp"

#include "spectral.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>
#include <utility>

#include "scene_registry.hpp"

namespace mpmstab {

namespace {

std::string show(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

// The shortest text that reads back as v.
std::string brief(double v) {
  for (int digits = 1; digits < 17; ++digits) {
    std::ostringstream s;
    s.precision(digits);
    s << v;
    if (std::stod(s.str()) == v) return s.str();
  }
  return show(v);
}

// Name tables: one place for every enum's spelling.
template <class Enum, std::size_t N>
using Names = std::array<std::pair<Enum, std::string_view>, N>;

constexpr Names<Method, 6> kMethods{{{Method::mpm, "mpm"},
                                     {Method::gimp, "gimp"},
                                     {Method::cpgimp, "cpgimp"},
                                     {Method::bspline2, "bspline2"},
                                     {Method::bspline3, "bspline3"},
                                     {Method::cpdi, "cpdi"}}};
constexpr Names<SceneKind, 8> kScenes{{{SceneKind::bar, "bar"},
                                       {SceneKind::steffen, "steffen"},
                                       {SceneKind::mode, "mode"},
                                       {SceneKind::vibration, "vibration"},
                                       {SceneKind::impulsive, "impulsive"},
                                       {SceneKind::compaction, "compaction"},
                                       {SceneKind::block, "block"},
                                       {SceneKind::impact, "impact"}}};
constexpr Names<SmallMass, 4> kSmallMass{{{SmallMass::none, "none"},
                                          {SmallMass::cutoff, "cutoff"},
                                          {SmallMass::drop, "drop"},
                                          {SmallMass::momentum, "momentum"}}};
constexpr Names<Walls, 3> kWalls{
    {{Walls::clip, "clip"}, {Walls::ghost, "ghost"}, {Walls::modified, "modified"}}};
constexpr Names<Transfer, 6> kTransfers{{{Transfer::flip, "flip"},
                                         {Transfer::pic, "pic"},
                                         {Transfer::blend, "blend"},
                                         {Transfer::apic, "apic"},
                                         {Transfer::xpic, "xpic"},
                                         {Transfer::fmpm, "fmpm"}}};
constexpr Names<UpdateOrder, 3> kUpdateOrders{
    {{UpdateOrder::usl, "usl"}, {UpdateOrder::usf, "usf"}, {UpdateOrder::musl, "musl"}}};
constexpr Names<BodyForceTime, 2> kBodyForceTimes{
    {{BodyForceTime::start, "start"}, {BodyForceTime::end, "end"}}};
constexpr Names<Boundary, 2> kBoundaries{
    {{Boundary::dirichlet, "dirichlet"}, {Boundary::periodic, "periodic"}}};
constexpr Names<PositionUpdate, 2> kPositionUpdates{
    {{PositionUpdate::grid, "grid"}, {PositionUpdate::particle, "particle"}}};
constexpr Names<StressScaling, 2> kScalings{
    {{StressScaling::scaled, "scaled"}, {StressScaling::raw, "raw"}}};
constexpr Names<VelocityNorm, 2> kNorms{{{VelocityNorm::l2, "l2"}, {VelocityNorm::max, "max"}}};
constexpr Names<TimeStepPolicy, 5> kPolicies{{{TimeStepPolicy::fixed, "fixed"},
                                              {TimeStepPolicy::cfl, "cfl"},
                                              {TimeStepPolicy::adaptive, "adaptive"},
                                              {TimeStepPolicy::min, "min"},
                                              {TimeStepPolicy::spectral, "spectral"}}};

template <class Enum, std::size_t N>
std::string_view name_of(const Names<Enum, N>& table, Enum e) {
  for (const auto& [value, name] : table)
    if (value == e) return name;
  return "?";
}

template <class Enum, std::size_t N>
std::optional<Enum> parse(const Names<Enum, N>& table, std::string_view s) {
  for (const auto& [value, name] : table)
    if (name == s) return value;
  return std::nullopt;
}

}  // namespace

std::string_view to_string(Method m) {
  return name_of(kMethods, m);
}
std::string_view to_string(Boundary b) {
  return name_of(kBoundaries, b);
}
std::string_view to_string(PositionUpdate u) {
  return name_of(kPositionUpdates, u);
}
std::string_view to_string(StressScaling s) {
  return name_of(kScalings, s);
}
std::string_view to_string(VelocityNorm n) {
  return name_of(kNorms, n);
}

std::optional<Method> parse_method(std::string_view s) {
  return parse(kMethods, s);
}
std::optional<Boundary> parse_boundary(std::string_view s) {
  return parse(kBoundaries, s);
}
std::optional<PositionUpdate> parse_position_update(std::string_view s) {
  return parse(kPositionUpdates, s);
}
std::optional<StressScaling> parse_stress_scaling(std::string_view s) {
  return parse(kScalings, s);
}
std::optional<VelocityNorm> parse_velocity_norm(std::string_view s) {
  return parse(kNorms, s);
}

std::string_view to_string(TimeStepPolicy p) {
  return name_of(kPolicies, p);
}
std::optional<TimeStepPolicy> parse_time_step_policy(std::string_view s) {
  return parse(kPolicies, s);
}

std::string_view to_string(SceneKind s) {
  return name_of(kScenes, s);
}
std::string_view to_string(Walls w) {
  return name_of(kWalls, w);
}
std::string_view to_string(Transfer t) {
  return name_of(kTransfers, t);
}
std::string_view to_string(UpdateOrder u) {
  return name_of(kUpdateOrders, u);
}
std::string_view to_string(BodyForceTime b) {
  return name_of(kBodyForceTimes, b);
}
std::optional<SceneKind> parse_scene(std::string_view s) {
  return parse(kScenes, s);
}
std::optional<Walls> parse_walls(std::string_view s) {
  return parse(kWalls, s);
}
std::optional<Transfer> parse_transfer(std::string_view s) {
  return parse(kTransfers, s);
}
std::optional<UpdateOrder> parse_update_order(std::string_view s) {
  return parse(kUpdateOrders, s);
}
std::optional<BodyForceTime> parse_body_force_time(std::string_view s) {
  return parse(kBodyForceTimes, s);
}
std::string_view to_string(SmallMass s) {
  return name_of(kSmallMass, s);
}
std::optional<SmallMass> parse_small_mass(std::string_view s) {
  return parse(kSmallMass, s);
}

std::string nondefault_choices(const RunParams& p) {
  const RunParams d;
  std::string text;
  auto add = [&](std::string_view key, std::string value) {
    text += ", ";
    text += key;
    text += ' ';
    text += value;
  };
  if (p.position_update != d.position_update)
    add("position_update", std::string(to_string(p.position_update)));
  if (p.scene != d.scene) add("scene", std::string(to_string(p.scene)));
  if (p.walls != d.walls) add("walls", std::string(to_string(p.walls)));
  if (p.transfer != d.transfer) {
    std::string t(to_string(p.transfer));
    std::string order;
    if (p.transfer == Transfer::blend) order = show(p.flip_fraction);
    if (p.transfer == Transfer::xpic) order = std::to_string(p.xpic_order);
    if (p.transfer == Transfer::fmpm) order = std::to_string(p.fmpm_order);
    if (!order.empty()) {
      t += '(';
      t += order;
      t += ')';
    }
    add("transfer", t);
  }
  if (p.update != d.update) add("update", std::string(to_string(p.update)));
  if (p.layout.shift != d.layout.shift) add("shift", brief(p.layout.shift));
  if (p.layout.jitter != d.layout.jitter) add("jitter", brief(p.layout.jitter));
  if (p.body_force_time != d.body_force_time)
    add("body_force_time", std::string(to_string(p.body_force_time)));
  if (!std::isnan(p.body_start)) add("body_start", brief(p.body_start));
  if (!std::isnan(p.body_length)) add("body_length", brief(p.body_length));
  if (p.small_mass != d.small_mass) {
    add("small_mass",
        std::string(to_string(p.small_mass)) + "(" + brief(p.small_mass_fraction) + ")");
  }
  return text;
}

bool default_choices(const RunParams& p) {
  const RunParams d;
  return p.scene == d.scene && p.walls == d.walls && p.transfer == d.transfer &&
         p.update == d.update && p.body_force_time == d.body_force_time &&
         p.layout.shift == d.layout.shift && p.layout.jitter == d.layout.jitter &&
         std::isnan(p.body_start) && std::isnan(p.body_length) && p.small_mass == d.small_mass;
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
  if (key == "body_start" && scene.fixed_start) {
    return ParamIssue{"body_start", "scene " + scene_name +
                                        " is fixed at the wall X = 0; only body_length can be "
                                        "given"};
  }
  return std::nullopt;
}

const std::vector<std::string>& conditional_parameters() {
  static const std::vector<std::string> keys = {
      "dt",         "cfl_factor", "safety",      "flip_fraction",      "xpic_order",
      "fmpm_order", "body_start", "body_length", "small_mass_fraction"};
  return keys;
}

std::optional<double> fixed_step(const RunParams& p) {
  switch (p.stepping.policy) {
    case TimeStepPolicy::fixed:
      return p.dt;
    case TimeStepPolicy::cfl:
      return p.stepping.cfl_factor * (1.0 / p.cells) / std::sqrt(p.E);
    default:
      return std::nullopt;
  }
}

double wave_speed(const RunParams& p) {
  return std::sqrt(p.E);
}  // rho0 = 1 in both scenes

double amplitude_per_cell(const RunParams& p) {
  return p.A * p.cells;
}

double body_start(const RunParams& p) {
  return std::isnan(p.body_start) ? scene_info(p.scene).body_start : p.body_start;
}
double body_length(const RunParams& p) {
  return std::isnan(p.body_length) ? scene_info(p.scene).body_length : p.body_length;
}

double wave_passes(const RunParams& p) {
  return wave_speed(p) * p.T;
}  // L = 1

std::optional<double> courant_number(const RunParams& p) {
  switch (p.stepping.policy) {
    case TimeStepPolicy::fixed:
      return wave_speed(p) * p.dt * p.cells;
    case TimeStepPolicy::cfl:
      return p.stepping.cfl_factor;
    default:
      return std::nullopt;
  }
}

std::optional<std::int64_t> step_count(double T, double dt) {
  if (!(T > 0) || !(dt > 0) || !std::isfinite(T) || !std::isfinite(dt)) return std::nullopt;
  const double ratio = T / dt;
  if (!(ratio < 9.0e18)) return std::nullopt;
  // T / dt within a relative 1e-9 of an integer counts as that integer: T = 1, dt = 1e-5 is
  // 100000 steps, not 100001 with a last step of 1e-16.
  const double nearest = std::round(ratio);
  if (std::abs(ratio - nearest) <= 1e-9 * nearest && nearest >= 1) {
    return static_cast<std::int64_t>(nearest);
  }
  return static_cast<std::int64_t>(std::ceil(ratio));
}

const std::vector<std::string>& parameter_names() {
  static const std::vector<std::string> names = {"method",
                                                 "E",
                                                 "A",
                                                 "dt",
                                                 "T",
                                                 "cells",
                                                 "ppc",
                                                 "bc",
                                                 "position_update",
                                                 "scene",
                                                 "walls",
                                                 "transfer",
                                                 "flip_fraction",
                                                 "xpic_order",
                                                 "fmpm_order",
                                                 "update",
                                                 "shift",
                                                 "jitter",
                                                 "body_force_time",
                                                 "body_start",
                                                 "body_length",
                                                 "small_mass",
                                                 "small_mass_fraction",
                                                 "dt_stable_sigma",
                                                 "dt_stable_vnorm",
                                                 "policy",
                                                 "cfl_factor",
                                                 "safety"};
  return names;
}

std::vector<ParamIssue> validate(const RunParams& p) {
  std::vector<ParamIssue> issues;
  auto bad = [&](std::string key, std::string message) {
    issues.push_back({std::move(key), std::move(message)});
  };
  constexpr int kMaxCells = 10'000'000;
  constexpr int kMaxPpc = 64;

  if (!std::isfinite(p.E) || !(p.E > 0)) bad("E", "must be a finite number > 0, got " + show(p.E));
  if (!std::isfinite(p.A) || !(p.A >= 0))
    bad("A", "must be a finite number >= 0, got " + show(p.A));
  if (!std::isfinite(p.T) || !(p.T > 0)) bad("T", "must be a finite number > 0, got " + show(p.T));
  const bool fixed = p.stepping.policy == TimeStepPolicy::fixed;
  if (fixed && (!std::isfinite(p.dt) || !(p.dt > 0))) {
    bad("dt", "must be a finite number > 0, got " + show(p.dt));
  } else if (fixed && std::isfinite(p.T) && p.T > 0 && p.dt > p.T) {
    bad("dt", "must not exceed T = " + show(p.T) + ", got " + show(p.dt));
  }
  if (!std::isfinite(p.stepping.cfl_factor) || !(p.stepping.cfl_factor > 0)) {
    bad("cfl_factor", "must be a finite number > 0, got " + show(p.stepping.cfl_factor));
  }
  if (!std::isfinite(p.stepping.safety) || !(p.stepping.safety > 0)) {
    bad("safety", "must be a finite number > 0, got " + show(p.stepping.safety));
  }
  if (p.cells < 1 || p.cells > kMaxCells) {
    bad("cells", "must be an integer in [1, " + std::to_string(kMaxCells) + "], got " +
                     std::to_string(p.cells));
  }
  if (p.ppc < 1 || p.ppc > kMaxPpc) {
    bad("ppc",
        "must be an integer in [1, " + std::to_string(kMaxPpc) + "], got " + std::to_string(p.ppc));
  }
  if (p.cells >= 1 && p.ppc >= 1 && run_bytes(p) > kMaxRunBytes) {
    bad("cells", "cells * ppc = " + show(double(p.cells) * p.ppc) + " particles need about " +
                     show(std::round(run_bytes(p) / double(1 << 20))) + " MiB (" +
                     std::to_string(kBytesPerParticle) + " bytes per particle); the limit is " +
                     std::to_string(kMaxRunBytes >> 20) + " MiB (" +
                     show(std::floor(double(kMaxRunBytes) / kBytesPerParticle)) + " particles)");
  }
  if (p.transfer == Transfer::blend &&
      (!std::isfinite(p.flip_fraction) || !(p.flip_fraction > 0) || !(p.flip_fraction < 1))) {
    bad("flip_fraction",
        "must be a number in (0, 1) for transfer = blend, got " + show(p.flip_fraction));
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
  if (!std::isfinite(p.layout.shift) || !(p.layout.shift > -0.5) || !(p.layout.shift < 0.5)) {
    bad("shift", "must be a number in (-0.5, 0.5) (a fraction of the particle spacing), got " +
                     show(p.layout.shift));
  }
  if (!std::isfinite(p.layout.jitter) || !(p.layout.jitter >= 0) || !(p.layout.jitter < 1)) {
    bad("jitter", "must be a number in [0, 1) (a fraction of the particle spacing), got " +
                      show(p.layout.jitter));
  }
  if (p.layout.jitter > 0 && std::abs(p.layout.shift) + p.layout.jitter / 2 >= 0.5) {
    bad("jitter",
        "|shift| + jitter / 2 must stay below 0.5, so that every particle keeps its "
        "cell; got shift " +
            brief(p.layout.shift) + ", jitter " + brief(p.layout.jitter));
  }
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
  if (!has_eq108(p.method)) {
    if (is_bspline(p.method) && p.walls == Walls::ghost) {
      bad("walls",
          "a B-spline eliminates its node beyond each wall (linear extrapolation); free "
          "ghost nodes apply to mpm, gimp and cpgimp");
    }
    if (p.stepping.policy == TimeStepPolicy::adaptive || p.stepping.policy == TimeStepPolicy::min) {
      bad("policy", "the " + std::string(to_string(p.stepping.policy)) +
                        " policy steps by eq. (108), which is derived for mpm, gimp and cpgimp "
                        "only; use fixed or cfl with " +
                        std::string(to_string(p.method)));
    }
  }
  if (p.stepping.policy == TimeStepPolicy::spectral && p.cells >= 1 && p.ppc >= 1 &&
      spectral_state_size(p) > kMaxSpectralState) {
    bad("policy",
        "the spectral policy computes the spectral limit with a dense solver, for at "
        "most " +
            std::to_string(kMaxSpectralState / 2) + " particles (" +
            std::to_string(kMaxSpectralState / 3) + " with apic); got " +
            std::to_string(static_cast<long long>(p.cells) * p.ppc));
  }
  if (p.max_steps < 1) bad("max_steps", "must be >= 1, got " + std::to_string(p.max_steps));
  if (p.observe.history_stride < 1) {
    bad("history_stride", "must be >= 1, got " + std::to_string(p.observe.history_stride));
  } else if (p.observe.history && p.max_steps >= 1) {
    // The rows a run keeps in memory: every stride-th of its steps (at most max_steps with a
    // state-dependent policy).
    // The fixed and cfl policies know their step count.
    std::optional<std::int64_t> steps;
    const std::optional<double> step =
        fixed || p.stepping.policy == TimeStepPolicy::cfl ? fixed_step(p) : std::nullopt;
    if (step && std::isfinite(*step) && *step > 0 && std::isfinite(p.T) && p.T > 0) {
      steps = step_count(p.T, std::min(*step, p.T));
    } else if (!fixed && p.stepping.policy != TimeStepPolicy::cfl) {
      steps = p.max_steps;
    }
    if (steps && *steps / p.observe.history_stride > kMaxHistoryRows) {
      bad("history_stride", "keeps " + show(double(*steps / p.observe.history_stride)) +
                                " history rows in memory; the limit is " +
                                show(double(kMaxHistoryRows)) + " (raise history_stride" +
                                (fixed ? "" : " or lower max_steps") + ")");
    }
  }
  // A scene declares the boundaries it is posed with and where its body lies (scene.hpp).
  const SceneInfo& scene = scene_info(p.scene);
  const std::string scene_name(scene.name);
  if (!scene.supports(p.bc)) {
    bad("bc", "scene " + scene_name + " does not support bc = " + std::string(to_string(p.bc)));
  }
  const double start = body_start(p), length = body_length(p);
  if (!std::isfinite(length) || !(length > 0) || !(length <= 1)) {
    bad("body_length", "must be a number in (0, 1] (the grid is [0, 1]), got " + show(length));
  } else if (!std::isfinite(start) || !(start >= 0) || !(start + length <= 1)) {
    bad("body_start", "the body [" + brief(start) + ", " + brief(start + length) +
                          "] must lie inside the grid [0, 1]");
  } else if (p.cells >= 1) {
    // Both ends on cell boundaries, so that the body's cells are whole.
    for (const auto& [key, end] :
         {std::pair{"body_start", start}, std::pair{"body_length", length}}) {
      const double in_cells = end * p.cells;
      if (std::abs(in_cells - std::round(in_cells)) > 1e-9 * std::max(1.0, in_cells)) {
        bad(key, "must be a whole number of cells (h = 1 / cells = " + brief(1.0 / p.cells) +
                     "), got " + brief(end) + " = " + brief(in_cells) + " cells");
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
              show(p.small_mass_fraction));
    }
  }
  // The block between walls: its exact motion must not reach the wall X = 1 by T.
  if (p.scene == SceneKind::block && p.bc == Boundary::dirichlet && std::isfinite(p.T) &&
      std::isfinite(p.E) && p.E > 0 && std::isfinite(p.A) &&
      start + length + p.A * wave_speed(p) * p.T > 1) {
    bad("T", "the block [" + brief(start) + ", " + brief(start + length) + "] moving at A c = " +
                 brief(p.A * wave_speed(p)) + " reaches the wall X = 1 before T = " + brief(p.T) +
                 " (use bc = periodic or a shorter T)");
  }
  // The step count of the fixed-step policies is known before the run: refuse it if too large.
  // (The state-dependent policies stop with a step_limit failure when they reach the cap.)
  if (issues.empty()) {
    if (const auto dt = fixed_step(p)) {
      const auto n = step_count(p.T, std::min(*dt, p.T));
      const std::string key = fixed ? "dt" : "cfl_factor";
      if (!n || *n > p.max_steps) {
        bad(key, "T / dt = " + show(p.T / *dt) + " steps exceeds the cap max_steps = " +
                     std::to_string(p.max_steps) + " (raise --max-steps or shorten T)");
      }
    }
  }
  return issues;
}

}  // namespace mpmstab
