#include "result_json.hpp"

#include "version.hpp"

namespace mpmstab {

namespace {

template <class T>
nlohmann::ordered_json or_null(const std::optional<T>& v) {
  return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
}

}  // namespace

nlohmann::ordered_json to_json(const RunResult& r) {
  const RunParams& p = r.params;
  nlohmann::ordered_json j;
  j["method"] = to_string(p.method);
  j["E"] = p.E;
  j["A"] = p.A;
  j["dt"] = p.dt;
  j["T"] = p.T;
  j["cells"] = p.cells;
  j["ppc"] = p.ppc;
  j["bc"] = to_string(p.bc);
  j["position_update"] = to_string(p.position_update);
  j["scene"] = to_string(p.scene);
  j["walls"] = to_string(p.walls);
  j["transfer"] = to_string(p.transfer);
  j["flip_fraction"] = p.transfer == Transfer::blend ? nlohmann::ordered_json(p.flip_fraction)
                                                     : nlohmann::ordered_json(nullptr);
  j["update"] = to_string(p.update);
  j["body_force_time"] = to_string(p.body_force_time);
  j["policy"] = to_string(p.stepping.policy);
  j["cfl_factor"] = p.stepping.cfl_factor;
  j["safety"] = p.stepping.safety;
  j["stable"] = r.stable;
  if (r.failure) {
    j["failure"] = {{"reason", to_string(r.failure->reason)},
                    {"step", r.failure->step},
                    {"time", r.failure->time},
                    {"particle", r.failure->particle}};
  } else {
    j["failure"] = nullptr;
  }
  j["meaningless"] = or_null(r.meaningless);
  j["steps"] = r.steps;
  j["dt_min"] = r.dt_min;
  j["dt_max"] = r.dt_max;
  j["max_error"] = or_null(r.max_error);
  j["max_error_over_time"] = or_null(r.max_error_over_time);
  j["crossings"] = or_null(r.crossings);
  j["dt_stable_min"] = or_null(r.dt_stable_min);
  j["dt_stable_sigma"] = to_string(p.stable.sigma);
  j["dt_stable_vnorm"] = to_string(p.stable.vnorm);
  j["dt_cfl"] = r.dt_cfl;
  j["dt_sound"] = r.dt_sound;
  j["courant"] = r.courant;
  j["particles"] = r.particles;
  j["wall_seconds"] = r.wall_seconds;
  j["ns_per_particle_step"] = r.ns_per_particle_step;
  j["solver_version"] = kSolverVersion;
  return j;
}

nlohmann::ordered_json history_to_json(const RunResult& r) {
  auto rows = nlohmann::ordered_json::array();
  for (const auto& h : r.history) {
    rows.push_back({{"step", h.step},
                    {"time", h.time},
                    {"error", or_null(h.error)},
                    {"dt_stable", or_null(h.dt_stable)},
                    {"crossings", or_null(h.crossings)}});
  }
  return rows;
}

nlohmann::ordered_json edge_to_json(const EdgeResult& e) {
  nlohmann::ordered_json j;
  j["dt_cfl"] = e.dt_cfl;
  j["dt_edge"] = or_null(e.dt_edge);
  j["dt_fail"] = or_null(e.dt_fail);
  j["dt_edge_over_cfl"] = e.dt_edge ? nlohmann::ordered_json(*e.dt_edge / e.dt_cfl) : nullptr;
  const bool have_bound = e.dt_edge && e.at_edge && e.at_edge->dt_stable_min;
  const double bound = have_bound ? e.at_edge->dt_stable_min.value() : 0.0;
  j["dt_stable_min_at_edge"] = have_bound ? nlohmann::ordered_json(bound) : nullptr;
  j["dt_edge_over_stable"] =
      have_bound ? nlohmann::ordered_json(e.dt_edge.value() / bound) : nullptr;
  j["above_scan"] = e.above_scan;
  j["monotone"] = e.failed_below_edge.empty();
  j["failed_below_edge"] = e.failed_below_edge;
  auto probes = nlohmann::ordered_json::array();
  for (const auto& p : e.probes) {
    probes.push_back({{"dt", p.dt},
                      {"stable", p.stable},
                      {"reason", p.reason ? nlohmann::ordered_json(to_string(*p.reason))
                                          : nlohmann::ordered_json(nullptr)},
                      {"steps", p.steps}});
  }
  j["probes"] = probes;
  j["wall_seconds"] = e.wall_seconds;
  return j;
}

}  // namespace mpmstab
