#include "base/params.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>
#include <utility>

namespace mpmstab {

std::string exact_text(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

// The shortest text that reads back as v.
std::string brief_text(double v) {
  for (int digits = 1; digits < 17; ++digits) {
    std::ostringstream s;
    s.precision(digits);
    s << v;
    if (std::stod(s.str()) == v) return s.str();
  }
  return exact_text(v);
}

namespace {

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
constexpr Names<VelocityStart, 2> kVelocityStarts{
    {{VelocityStart::exact, "exact"}, {VelocityStart::half_step, "half_step"}}};
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

template <class Enum, std::size_t N>
std::vector<std::string_view> names(const Names<Enum, N>& table) {
  std::vector<std::string_view> out;
  for (const auto& entry : table)
    out.push_back(entry.second);
  return out;
}

// Each enum's table, for names_of.
constexpr const auto& table_of(Method) {
  return kMethods;
}
constexpr const auto& table_of(Boundary) {
  return kBoundaries;
}
constexpr const auto& table_of(PositionUpdate) {
  return kPositionUpdates;
}
constexpr const auto& table_of(StressScaling) {
  return kScalings;
}
constexpr const auto& table_of(VelocityNorm) {
  return kNorms;
}
constexpr const auto& table_of(TimeStepPolicy) {
  return kPolicies;
}
constexpr const auto& table_of(SceneKind) {
  return kScenes;
}
constexpr const auto& table_of(Walls) {
  return kWalls;
}
constexpr const auto& table_of(Transfer) {
  return kTransfers;
}
constexpr const auto& table_of(UpdateOrder) {
  return kUpdateOrders;
}
constexpr const auto& table_of(BodyForceTime) {
  return kBodyForceTimes;
}
constexpr const auto& table_of(VelocityStart) {
  return kVelocityStarts;
}
constexpr const auto& table_of(SmallMass) {
  return kSmallMass;
}

}  // namespace

template <class Enum>
std::vector<std::string_view> names_of() {
  return names(table_of(Enum{}));
}
template std::vector<std::string_view> names_of<Method>();
template std::vector<std::string_view> names_of<Boundary>();
template std::vector<std::string_view> names_of<PositionUpdate>();
template std::vector<std::string_view> names_of<StressScaling>();
template std::vector<std::string_view> names_of<VelocityNorm>();
template std::vector<std::string_view> names_of<TimeStepPolicy>();
template std::vector<std::string_view> names_of<SceneKind>();
template std::vector<std::string_view> names_of<Walls>();
template std::vector<std::string_view> names_of<Transfer>();
template std::vector<std::string_view> names_of<UpdateOrder>();
template std::vector<std::string_view> names_of<BodyForceTime>();
template std::vector<std::string_view> names_of<VelocityStart>();
template std::vector<std::string_view> names_of<SmallMass>();

std::string choices_text(const std::vector<std::string_view>& names) {
  std::string text;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i) text += i + 1 == names.size() ? " or " : ", ";
    text += names[i];
  }
  return text;
}

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
std::string_view to_string(VelocityStart s) {
  return name_of(kVelocityStarts, s);
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
std::optional<VelocityStart> parse_velocity_start(std::string_view s) {
  return parse(kVelocityStarts, s);
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
    if (p.transfer == Transfer::blend) order = exact_text(p.flip_fraction);
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
  if (p.layout.shift != d.layout.shift) add("shift", brief_text(p.layout.shift));
  if (p.layout.jitter != d.layout.jitter) add("jitter", brief_text(p.layout.jitter));
  if (p.body_force_time != d.body_force_time)
    add("body_force_time", std::string(to_string(p.body_force_time)));
  if (p.start != d.start) add("start", std::string(to_string(p.start)));
  if (!std::isnan(p.body_start)) add("body_start", brief_text(p.body_start));
  if (!std::isnan(p.body_length)) add("body_length", brief_text(p.body_length));
  if (p.small_mass != d.small_mass) {
    add("small_mass",
        std::string(to_string(p.small_mass)) + "(" + brief_text(p.small_mass_fraction) + ")");
  }
  if (p.tip_load != d.tip_load) add("tip_load", brief_text(p.tip_load));
  return text;
}

bool default_choices(const RunParams& p) {
  const RunParams d;
  return p.scene == d.scene && p.walls == d.walls && p.transfer == d.transfer &&
         p.update == d.update && p.body_force_time == d.body_force_time && p.start == d.start &&
         p.layout.shift == d.layout.shift && p.layout.jitter == d.layout.jitter &&
         std::isnan(p.body_start) && std::isnan(p.body_length) && p.small_mass == d.small_mass &&
         p.tip_load == d.tip_load;
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
                                                 "start",
                                                 "body_start",
                                                 "body_length",
                                                 "small_mass",
                                                 "small_mass_fraction",
                                                 "tip_load",
                                                 "dt_stable_sigma",
                                                 "dt_stable_vnorm",
                                                 "policy",
                                                 "cfl_factor",
                                                 "safety"};
  return names;
}

}  // namespace mpmstab
