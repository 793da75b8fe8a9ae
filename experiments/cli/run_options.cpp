#include "run_options.hpp"
#include "scenes/validate.hpp"

#include <algorithm>
#include <cstdio>
#include <optional>

namespace mpmstab::cli {

namespace {

// Parameter keys (params.hpp) are snake_case; options spell them with dashes.
std::string option_for_key(std::string key) {
  std::replace(key.begin(), key.end(), '_', '-');
  return "--" + key;
}

std::string_view required(const Args& a, std::string_view name) {
  auto v = a.value(name);
  if (!v) throw UsageError("missing required option --" + std::string(name));
  return *v;
}

// A value of one of params.hpp's enums; a name it does not know is refused with every name it
// knows, from the same table that parses it.
template <class Enum>
Enum parse_choice(std::string_view text, std::string_view option,
                  std::optional<Enum> (*parse)(std::string_view)) {
  if (auto e = parse(text)) return *e;
  throw UsageError("--" + std::string(option) + ": unknown value '" + std::string(text) +
                   "' (expected " + choices_text(names_of<Enum>()) + ")");
}

int to_int(std::string_view text, std::string_view option) {
  const std::int64_t v = parse_int(text, option);
  if (v < -1'000'000'000 || v > 1'000'000'000) {
    throw UsageError("--" + std::string(option) + ": " + std::string(text) + " is out of range");
  }
  return static_cast<int>(v);
}

// --policy, --dt, --cfl-factor, --safety and --T.
void read_time_stepping(const Args& a, bool searching_dt, RunParams& p) {
  if (auto v = a.value("policy")) {
    p.stepping.policy = parse_choice(*v, "policy", parse_time_step_policy);
  }
  if (!searching_dt) {
    if (p.stepping.policy == TimeStepPolicy::fixed) {
      p.dt = parse_double(required(a, "dt"), "dt");
    }
  }
  if (auto v = a.value("cfl-factor")) p.stepping.cfl_factor = parse_double(*v, "cfl-factor");
  if (auto v = a.value("safety")) p.stepping.safety = parse_double(*v, "safety");
  if (auto v = a.value("T")) p.T = parse_double(*v, "T");
  if (searching_dt) p.dt = p.T;  // replaced by the search
}

// The grid, the boundary conditions and the implementation choices (params.hpp).
void read_choices(const Args& a, RunParams& p) {
  if (auto v = a.value("cells")) p.cells = to_int(*v, "cells");
  if (auto v = a.value("ppc")) p.ppc = to_int(*v, "ppc");
  if (auto v = a.value("bc")) p.bc = parse_choice(*v, "bc", parse_boundary);
  if (auto v = a.value("position-update")) {
    p.position_update = parse_choice(*v, "position-update", parse_position_update);
  }
  if (auto v = a.value("scene")) p.scene = parse_choice(*v, "scene", parse_scene);
  if (auto v = a.value("walls")) p.walls = parse_choice(*v, "walls", parse_walls);
  if (auto v = a.value("transfer")) {
    p.transfer = parse_choice(*v, "transfer", parse_transfer);
  }
  if (auto v = a.value("flip-fraction")) p.flip_fraction = parse_double(*v, "flip-fraction");
  if (auto v = a.value("xpic-order")) p.xpic_order = to_int(*v, "xpic-order");
  if (auto v = a.value("fmpm-order")) p.fmpm_order = to_int(*v, "fmpm-order");
  if (auto v = a.value("shift")) p.layout.shift = parse_double(*v, "shift");
  if (auto v = a.value("jitter")) p.layout.jitter = parse_double(*v, "jitter");
  if (auto v = a.value("update")) {
    p.update = parse_choice(*v, "update", parse_update_order);
  }
  if (auto v = a.value("body-force-time")) {
    p.body_force_time = parse_choice(*v, "body-force-time", parse_body_force_time);
  }
  if (auto v = a.value("start")) {
    p.start = parse_choice(*v, "start", parse_velocity_start);
  }
  if (auto v = a.value("body-start")) p.body_start = parse_double(*v, "body-start");
  if (auto v = a.value("body-length")) p.body_length = parse_double(*v, "body-length");
  if (auto v = a.value("small-mass")) {
    p.small_mass = parse_choice(*v, "small-mass", parse_small_mass);
  }
  if (auto v = a.value("small-mass-fraction"))
    p.small_mass_fraction = parse_double(*v, "small-mass-fraction");
  if (auto v = a.value("tip-load")) p.tip_load = parse_double(*v, "tip-load");
}

// The options of eq. (108), the step cap and the history.
void read_measurements(const Args& a, RunParams& p) {
  if (auto v = a.value("dt-stable-sigma")) {
    p.stable.sigma = parse_choice(*v, "dt-stable-sigma", parse_stress_scaling);
  }
  if (auto v = a.value("dt-stable-vnorm")) {
    p.stable.vnorm = parse_choice(*v, "dt-stable-vnorm", parse_velocity_norm);
  }
  if (auto v = a.value("max-steps")) p.max_steps = parse_int(*v, "max-steps");
  p.observe.energy = a.flag("energy");
  p.observe.tip = a.flag("tip");
  p.observe.error_l2 = a.flag("error-l2");
  if (auto v = a.value("history-stride"))
    p.observe.history_stride = parse_int(*v, "history-stride");
  // --history FILE streams the rows into FILE as the run makes them (run()'s sink): none is
  // kept in memory, so observe.history (rows kept) stays off.
  if (a.value("history") && a.value("history")->empty()) {
    throw UsageError("--history: needs a file name");
  }
}

// One UsageError naming, line by line, every option that validate() rejects.
void throw_if_invalid(const RunParams& p) {
  const auto issues = validate(p);
  if (issues.empty()) return;
  std::string message;
  for (const auto& issue : issues) {
    if (!message.empty()) message += "\n";
    message += option_for_key(issue.key) + ": " + issue.message;
  }
  throw UsageError(message);
}

}  // namespace

const std::vector<OptionSpec>& run_options() {
  static const std::vector<OptionSpec> options = {
      {"method"},
      {"E"},
      {"A"},
      {"dt"},
      {"T"},
      {"cells"},
      {"ppc"},
      {"bc"},
      {"position-update"},
      {"scene"},
      {"walls"},
      {"transfer"},
      {"flip-fraction"},
      {"xpic-order"},
      {"fmpm-order"},
      {"update"},
      {"shift"},
      {"jitter"},
      {"body-start"},
      {"body-length"},
      {"small-mass"},
      {"small-mass-fraction"},
      {"tip-load"},
      {"body-force-time"},
      {"start"},
      {"dt-stable-sigma"},
      {"dt-stable-vnorm"},
      {"max-steps"},
      {"policy"},
      {"cfl-factor"},
      {"safety"},
      {"history"},
      {"history-stride"},
      {"energy", false},
      {"tip", false},
      {"error-l2", false},
      {"json", false},
      {"help", false},
  };
  return options;
}

RunParams params_from(const Args& a, bool searching_dt, bool amplitude_required) {
  RunParams p;
  p.method = parse_choice(required(a, "method"), "method", parse_method);
  p.E = parse_double(required(a, "E"), "E");
  p.A = amplitude_required || a.value("A") ? parse_double(required(a, "A"), "A") : 0.0;
  read_time_stepping(a, searching_dt, p);
  read_choices(a, p);
  read_measurements(a, p);
  // What was given but is not used, then the values: the order and the messages of a spec.
  for (const auto& key : conditional_parameters()) {
    if (key == "dt" && searching_dt) continue;
    std::string option = key;
    std::replace(option.begin(), option.end(), '_', '-');
    if (!a.value(option)) continue;
    if (const auto issue = check_given(p, key)) {
      throw UsageError(option_for_key(issue->key) + ": " + issue->message);
    }
  }
  throw_if_invalid(p);
  return p;
}

}  // namespace mpmstab::cli
