#include "result_json.hpp"

#include "base/version.hpp"
#include "scenes/scene_registry.hpp"

namespace mpmstab {

namespace {

using ojson = nlohmann::ordered_json;

template <class T>
nlohmann::ordered_json or_null(const std::optional<T>& v) {
  return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
}

}  // namespace

const std::vector<std::string>& record_columns() {
  static const std::vector<std::string> columns = {
      // What was asked: the parameters (a parameter the run did not use is null).
      "method", "E", "A", "dt", "T", "cells", "ppc", "bc", "position_update", "scene", "walls",
      "transfer", "flip_fraction", "xpic_order", "fmpm_order", "update", "shift", "jitter",
      "body_force_time", "body_start", "body_length", "small_mass", "small_mass_fraction",
      "tip_load", "policy", "cfl_factor", "safety", "dt_stable_sigma", "dt_stable_vnorm",
      // What the run did.
      "outcome", "failure_reason", "failure_step", "failure_time", "failure_particle", "steps",
      "dt_min", "dt_max", "dt_mean", "max_error", "max_error_over_time", "error_l2_time",
      "crossings", "dt_stable_min", "energy_error_max", "energy_exact_error_max", "energy_drift",
      "energy_warning_step", "dt_cfl", "dt_sound", "courant", "courant_spectral", "dt_spectral",
      "spectral_analysis", "particles", "solver_version"};
  return columns;
}

nlohmann::ordered_json to_json(const RunResult& r) {
  const RunParams& p = r.params;
  const TimeStepPolicy policy = p.stepping.policy;
  const bool ran = r.steps > 0;
  ojson j;
  j["method"] = to_string(p.method);
  j["E"] = p.E;
  j["A"] = p.A;
  // The step that was used: only a fixed policy uses the given dt.
  j["dt"] = policy == TimeStepPolicy::fixed ? ojson(p.dt) : ojson(nullptr);
  j["T"] = p.T;
  j["cells"] = p.cells;
  j["ppc"] = p.ppc;
  j["bc"] = to_string(p.bc);
  j["position_update"] = to_string(p.position_update);
  j["scene"] = to_string(p.scene);
  j["walls"] = to_string(p.walls);
  j["transfer"] = to_string(p.transfer);
  j["flip_fraction"] = p.transfer == Transfer::blend ? ojson(p.flip_fraction) : ojson(nullptr);
  j["xpic_order"] = p.transfer == Transfer::xpic ? ojson(p.xpic_order) : ojson(nullptr);
  j["fmpm_order"] = p.transfer == Transfer::fmpm ? ojson(p.fmpm_order) : ojson(nullptr);
  j["update"] = to_string(p.update);
  j["shift"] = p.layout.shift;
  j["jitter"] = p.layout.jitter;
  j["body_force_time"] = to_string(p.body_force_time);
  // The body's extent: null where the scene's body fills the grid (it has none to choose).
  const bool placed = !scene_info(p.scene).fills_grid;
  j["body_start"] = placed ? ojson(body_start(p)) : ojson(nullptr);
  j["body_length"] = placed ? ojson(body_length(p)) : ojson(nullptr);
  j["small_mass"] = to_string(p.small_mass);
  j["small_mass_fraction"] =
      p.small_mass != SmallMass::none ? ojson(p.small_mass_fraction) : ojson(nullptr);
  // The tip load: null where the scene has no free end to take one.
  j["tip_load"] = scene_info(p.scene).tip_load ? ojson(p.tip_load) : ojson(nullptr);
  j["policy"] = to_string(policy);
  const bool uses_cfl = policy == TimeStepPolicy::cfl || policy == TimeStepPolicy::min;
  const bool uses_bound = policy == TimeStepPolicy::adaptive || policy == TimeStepPolicy::min ||
                          policy == TimeStepPolicy::spectral;
  j["cfl_factor"] = uses_cfl ? ojson(p.stepping.cfl_factor) : ojson(nullptr);
  j["safety"] = uses_bound ? ojson(p.stepping.safety) : ojson(nullptr);
  j["dt_stable_sigma"] = to_string(p.stable.sigma);
  j["dt_stable_vnorm"] = to_string(p.stable.vnorm);
  j["outcome"] = r.outcome ? ojson(to_string(*r.outcome)) : ojson(nullptr);
  const Failure* f = r.failure ? &*r.failure : nullptr;
  j["failure_reason"] = f ? ojson(to_string(f->reason)) : ojson(nullptr);
  j["failure_step"] = f ? ojson(f->step) : ojson(nullptr);
  j["failure_time"] = f ? ojson(f->time) : ojson(nullptr);
  j["failure_particle"] = f && f->particle >= 0 ? ojson(f->particle) : ojson(nullptr);
  j["steps"] = r.steps;
  j["dt_min"] = ran ? ojson(r.dt_min) : ojson(nullptr);
  j["dt_max"] = ran ? ojson(r.dt_max) : ojson(nullptr);
  j["dt_mean"] = ran ? ojson(r.dt_mean) : ojson(nullptr);
  j["max_error"] = or_null(r.max_error);
  j["max_error_over_time"] = or_null(r.max_error_over_time);
  j["error_l2_time"] = or_null(r.error_l2_time);
  j["crossings"] = or_null(r.crossings);
  j["dt_stable_min"] = or_null(r.dt_stable_min);
  j["energy_error_max"] = or_null(r.energy_error_max);
  j["energy_exact_error_max"] = or_null(r.energy_exact_error_max);
  j["energy_drift"] = or_null(r.energy_drift);
  j["energy_warning_step"] = or_null(r.energy_warning_step);
  j["dt_cfl"] = r.dt_cfl;
  j["dt_sound"] = r.dt_sound;
  const bool fixed_step = policy == TimeStepPolicy::fixed || policy == TimeStepPolicy::cfl;
  j["courant"] = fixed_step || ran ? ojson(r.courant) : ojson(nullptr);
  j["courant_spectral"] = or_null(r.courant_spectral);
  j["dt_spectral"] = or_null(r.dt_spectral);
  j["spectral_analysis"] =
      r.spectral_analysis ? ojson(to_string(*r.spectral_analysis)) : ojson(nullptr);
  j["particles"] = r.particles;
  j["solver_version"] = kSolverVersion;
  return j;
}

nlohmann::ordered_json timing_json(const RunResult& r) {
  return {{"wall_seconds", r.wall_seconds},
          {"ns_per_particle_step", r.steps > 0 ? nlohmann::ordered_json(r.ns_per_particle_step)
                                               : nlohmann::ordered_json(nullptr)}};
}

nlohmann::ordered_json history_to_json(const RunResult& r) {
  auto rows = nlohmann::ordered_json::array();
  for (const auto& h : r.history) {
    rows.push_back({{"step", h.step},
                    {"time", h.time},
                    {"error", or_null(h.error)},
                    {"dt_stable", or_null(h.dt_stable)},
                    {"crossings", or_null(h.crossings)}});
    if (r.params.observe.energy) {
      auto& row = rows.back();
      row["kinetic"] = or_null(h.kinetic);
      row["strain"] = or_null(h.strain);
      row["work"] = or_null(h.work);
      row["energy_balance"] = or_null(h.energy_balance);
      row["kinetic_exact"] = or_null(h.kinetic_exact);
      row["strain_exact"] = or_null(h.strain_exact);
      row["work_exact"] = or_null(h.work_exact);
    }
    if (r.params.observe.tip) {
      auto& row = rows.back();
      row["tip_u"] = or_null(h.tip_u);
      row["tip_u_exact"] = or_null(h.tip_u_exact);
    }
  }
  return rows;
}

nlohmann::ordered_json edge_to_json(const EdgeResult& e) {
  auto over_cfl = [&](const std::optional<double>& dt) {
    return dt ? ojson(*dt / e.dt_cfl) : ojson(nullptr);
  };
  ojson j;
  j["dt_cfl"] = e.dt_cfl;
  // What every run of the search holds for: its wave passes and amplitude.
  j["wave_passes"] = e.wave_passes;
  j["A"] = e.A;
  j["too_short"] = e.too_short;
  // The survival edge (the lowest failure found), and the highest survival above it.
  j["dt_edge"] = or_null(e.dt_edge);
  j["dt_fail"] = or_null(e.dt_fail);
  j["dt_edge_over_cfl"] = over_cfl(e.dt_edge);
  const bool have_bound = e.dt_edge && e.at_edge && e.at_edge->dt_stable_min;
  const double bound = have_bound ? e.at_edge->dt_stable_min.value() : 0.0;
  j["dt_stable_min_at_edge"] = have_bound ? ojson(bound) : nullptr;
  j["dt_edge_over_stable"] = have_bound ? ojson(e.dt_edge.value() / bound) : nullptr;
  j["above_scan"] = e.above_scan;
  j["monotone"] = e.monotone();
  j["dt_survives_above"] = or_null(e.survives_above);
  auto flips = ojson::array();
  for (const auto& f : e.flips)
    flips.push_back({{"below", f.below}, {"dt", f.dt}, {"survives", f.survives}});
  j["survival_flips"] = flips;
  // The accuracy edge.
  j["accuracy_factor"] = e.accuracy_factor;
  j["dt_reference"] = or_null(e.dt_reference);
  j["max_error_reference"] = or_null(e.max_error_reference);
  j["dt_accurate"] = or_null(e.dt_accurate);
  j["dt_inaccurate"] = or_null(e.dt_inaccurate);
  j["dt_accurate_over_cfl"] = over_cfl(e.dt_accurate);
  j["accuracy_monotone"] = e.accuracy_monotone();
  j["dt_accurate_above"] = or_null(e.accurate_above);
  const EdgeProbe* at_accurate = nullptr;
  for (const auto& p : e.probes) {
    if (e.dt_accurate && p.dt == *e.dt_accurate) at_accurate = &p;
  }
  j["max_error_at_accurate"] = at_accurate ? or_null(at_accurate->max_error) : nullptr;
  j["outcome_at_accurate"] = at_accurate && at_accurate->outcome
                                 ? ojson(to_string(*at_accurate->outcome))
                                 : ojson(nullptr);
  j["search_particle_steps"] = e.particle_steps;
  auto probes = ojson::array();
  for (const auto& p : e.probes) {
    probes.push_back({{"dt", p.dt},
                      {"survived", p.survived},
                      {"reason", p.reason ? ojson(to_string(*p.reason)) : ojson(nullptr)},
                      {"steps", p.steps},
                      {"max_error", or_null(p.max_error)},
                      {"outcome", p.outcome ? ojson(to_string(*p.outcome)) : ojson(nullptr)}});
  }
  j["probes"] = probes;
  return j;
}

nlohmann::ordered_json edge_columns(const nlohmann::ordered_json& edge) {
  nlohmann::ordered_json row;
  for (const char* col :
       {"dt_edge", "dt_fail", "dt_edge_over_cfl", "dt_stable_min_at_edge", "dt_edge_over_stable",
        "monotone", "dt_survives_above", "dt_reference", "max_error_reference", "dt_accurate",
        "dt_inaccurate", "dt_accurate_over_cfl", "accuracy_monotone", "dt_accurate_above",
        "max_error_at_accurate", "outcome_at_accurate", "search_particle_steps"}) {
    row[col] = edge.contains(col) ? edge[col] : nlohmann::ordered_json(nullptr);
  }
  // "fails 0.00119; survives 0.00168": each dt from which survival changes, in increasing dt.
  std::string flips;
  for (const auto& f : edge.value("survival_flips", nlohmann::ordered_json::array())) {
    if (!flips.empty()) flips += "; ";
    flips += f["survives"].get<bool>() ? "survives " : "fails ";
    flips += f["dt"].dump();
  }
  row["survival_flips"] = flips;
  row["probes"] = edge["probes"].size();
  return row;
}

namespace {

// The JSON type a record column may hold, as the example's: a number, a string or a boolean, or
// null.
bool fits(const nlohmann::ordered_json& v, const nlohmann::ordered_json& example) {
  if (v.is_null()) return true;
  if (example.is_number()) return v.is_number();
  if (example.is_string()) return v.is_string();
  if (example.is_boolean()) return v.is_boolean();
  return v.is_primitive();
}

}  // namespace

std::string record_defect(const nlohmann::ordered_json& row) {
  static const nlohmann::ordered_json example = [] {  // a record with every column's JSON type
    RunResult r;
    r.outcome = Outcome::stable;
    r.steps = 1;
    r.error_l2_time = r.energy_error_max = r.energy_exact_error_max = r.energy_drift = 0.0;
    r.energy_warning_step = 0;
    return to_json(r);
  }();
  if (!row.is_object()) return ": must be an object";
  for (const auto& col : record_columns()) {
    const auto it = row.find(col);
    if (it == row.end()) return "." + col + ": is missing";
    if (!fits(*it, example[col])) return "." + col + ": has the wrong type";
  }
  if (const auto& outcome = row["outcome"]; outcome.is_string()) {
    const std::string& o = outcome.get_ref<const std::string&>();
    bool known = false;
    for (const Outcome each :
         {Outcome::unstable, Outcome::meaningless, Outcome::stable, Outcome::too_short})
      known = known || o == to_string(each);
    if (!known) return ".outcome: must be unstable, meaningless, stable or too_short (or null)";
  }
  return "";
}

}  // namespace mpmstab
