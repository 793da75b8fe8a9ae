// `mpmstab run`: one case of the bar, measured (DESIGN.md section 4).
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "args.hpp"
#include "atomic_file.hpp"
#include "commands.hpp"
#include "edge.hpp"
#include "params.hpp"
#include "result_json.hpp"
#include "run.hpp"

namespace mpmstab::cli {

namespace {

constexpr const char* kHelp =
    R"(Usage: mpmstab run --method gimp|cpgimp|mpm --E <x> --A <x> --dt <x> [options]

Runs one case of a 1D scene to time T (default: the paper's bar, manufactured solution
u = A sin(2 pi X) sin(c pi t), c = sqrt(E)) and reports its verdict and every measured
quantity.

Required:
  --method gimp|cpgimp|mpm shape functions: uGIMP, cpGIMP (half-width follows F) or
                           linear MPM
  --E <x>                  Young's modulus, > 0
  --A <x>                  amplitude of the solution, >= 0
  --dt <x>                 time step, 0 < dt <= T (the last step is shortened to land on T);
                           required with --policy fixed only

Options:
  --T <x>                  final time (default 1)
  --cells <n>              grid cells N on [0, 1], h = 1/N (default 100)
  --ppc <n>                particles per cell (default 2)
  --bc dirichlet|periodic  boundary conditions (default dirichlet)
  --position-update grid|particle
                           move particles with the grid velocity (default) or with
                           the updated particle velocity (the paper's eq. 10)
  --scene bar|steffen      the paper's bar (default: linear material, u = A sin(2 pi X)
                           sin(c pi t)) or Steffen et al. (2008): neo-Hookean material,
                           u = A sin(2 pi X) cos(c pi t)
  --walls clip|ghost       GIMP supports at a Dirichlet wall: nodes on [0, 1] only
                           (default) or one free ghost node beyond each wall
  --transfer flip|pic|blend
                           particle velocity update (default flip)
  --flip-fraction <a>      FLIP share of a blend, 0 < a < 1 (default 0.95)
  --update usl|usf|musl    stress update last (default), first (the paper's section 6),
                           or last with the grid velocity re-mapped from the particles
  --body-force-time start|end
                           evaluate b at the start t^n (default) or end t^{n+1} of a step
  --dt-stable-sigma scaled|raw
                           stress in eq. (108) scaled by 1/sqrt(E) (default) or not
  --dt-stable-vnorm l2|max norm of the nodal velocity in eq. (108) (default l2)
  --policy fixed|cfl|adaptive|min
                           time-step policy (default fixed): fixed dt; dt = C h / c;
                           dt_n = s * eq. (108) bound of the current state; or the minimum
                           of the last two. Every policy lands exactly on T.
  --cfl-factor <C>         Courant factor of the cfl and min policies (default 0.5)
  --safety <s>             factor on the eq. (108) bound, adaptive and min (default 1)
  --max-steps <n>          refuse runs needing more steps (default 200000000); an adaptive
                           run that reaches it stops with the verdict step_limit
  --history <file.csv>     also write the per-step history (error, eq. 108, crossings)
  --history-stride <n>     keep every n-th step in the history (default 1)
  --json                   print one JSON object instead of the text summary
  --help                   show this text

Exit status: 0 when the run completed (stable or not: an unstable run is a result),
2 for invalid input (nothing is run or written), 1 for an internal error.
)";

const std::vector<OptionSpec> kOptions = {
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
    {"update"},
    {"body-force-time"},
    {"dt-stable-sigma"},
    {"dt-stable-vnorm"},
    {"max-steps"},
    {"policy"},
    {"cfl-factor"},
    {"safety"},
    {"history"},
    {"history-stride"},
    {"json", false},
    {"help", false},
};

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

template <class Enum>
Enum parse_choice(std::string_view text, std::string_view option,
                  std::optional<Enum> (*parse)(std::string_view), std::string_view choices) {
  if (auto e = parse(text)) return *e;
  throw UsageError("--" + std::string(option) + ": unknown value '" + std::string(text) +
                   "' (expected " + std::string(choices) + ")");
}

int to_int(std::string_view text, std::string_view option) {
  const std::int64_t v = parse_int(text, option);
  if (v < -1'000'000'000 || v > 1'000'000'000) {
    throw UsageError("--" + std::string(option) + ": " + std::string(text) + " is out of range");
  }
  return static_cast<int>(v);
}

RunParams params_from(const Args& a, bool searching_dt = false) {
  RunParams p;
  p.method = parse_choice(required(a, "method"), "method", parse_method, "gimp, cpgimp or mpm");
  p.E = parse_double(required(a, "E"), "E");
  p.A = parse_double(required(a, "A"), "A");
  if (auto v = a.value("policy")) {
    p.stepping.policy =
        parse_choice(*v, "policy", parse_time_step_policy, "fixed, cfl, adaptive or min");
  }
  if (searching_dt) {
    p.dt = p.T;  // replaced by the search
  } else if (p.stepping.policy == TimeStepPolicy::fixed) {
    p.dt = parse_double(required(a, "dt"), "dt");
  } else if (auto v = a.value("dt")) {
    throw UsageError("--dt: only with --policy fixed (the " +
                     std::string(to_string(p.stepping.policy)) + " policy chooses dt itself)");
  }
  if (auto v = a.value("cfl-factor")) p.stepping.cfl_factor = parse_double(*v, "cfl-factor");
  if (auto v = a.value("safety")) p.stepping.safety = parse_double(*v, "safety");
  if (auto v = a.value("T")) p.T = parse_double(*v, "T");
  if (searching_dt) p.dt = p.T;
  if (auto v = a.value("cells")) p.cells = to_int(*v, "cells");
  if (auto v = a.value("ppc")) p.ppc = to_int(*v, "ppc");
  if (auto v = a.value("bc"))
    p.bc = parse_choice(*v, "bc", parse_boundary, "dirichlet or periodic");
  if (auto v = a.value("position-update")) {
    p.position_update =
        parse_choice(*v, "position-update", parse_position_update, "grid or particle");
  }
  if (auto v = a.value("scene")) p.scene = parse_choice(*v, "scene", parse_scene, "bar or steffen");
  if (auto v = a.value("walls")) p.walls = parse_choice(*v, "walls", parse_walls, "clip or ghost");
  if (auto v = a.value("transfer")) {
    p.transfer = parse_choice(*v, "transfer", parse_transfer, "flip, pic or blend");
  }
  if (auto v = a.value("flip-fraction")) {
    if (p.transfer != Transfer::blend)
      throw UsageError("--flip-fraction: only with --transfer blend");
    p.flip_fraction = parse_double(*v, "flip-fraction");
  }
  if (auto v = a.value("update")) {
    p.update = parse_choice(*v, "update", parse_update_order, "usl, usf or musl");
  }
  if (auto v = a.value("body-force-time")) {
    p.body_force_time = parse_choice(*v, "body-force-time", parse_body_force_time, "start or end");
  }
  if (auto v = a.value("dt-stable-sigma")) {
    p.stable.sigma = parse_choice(*v, "dt-stable-sigma", parse_stress_scaling, "scaled or raw");
  }
  if (auto v = a.value("dt-stable-vnorm")) {
    p.stable.vnorm = parse_choice(*v, "dt-stable-vnorm", parse_velocity_norm, "l2 or max");
  }
  if (auto v = a.value("max-steps")) p.max_steps = parse_int(*v, "max-steps");
  if (auto v = a.value("history-stride"))
    p.observe.history_stride = parse_int(*v, "history-stride");
  p.observe.history = a.value("history").has_value();
  if (searching_dt) p.dt = p.T;
  if (p.observe.history && a.value("history")->empty()) {
    throw UsageError("--history: needs a file name");
  }

  const auto issues = validate(p);
  if (!issues.empty()) {
    std::string message;
    for (const auto& issue : issues) {
      if (!message.empty()) message += "\n";
      message += option_for_key(issue.key) + ": " + issue.message;
    }
    throw UsageError(message);
  }
  return p;
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

template <class T>
std::string fmt(const std::optional<T>& v) {
  if (!v) return "-";
  if constexpr (std::is_floating_point_v<T>) {
    return fmt(*v);
  } else {
    return std::to_string(*v);
  }
}

std::string text_summary(const RunResult& r) {
  const RunParams& p = r.params;
  std::ostringstream s;
  s << "mpmstab run: " << to_string(p.method) << ", E = " << fmt(p.E) << ", A = " << fmt(p.A)
    << ", dt = " << fmt(p.dt) << ", T = " << fmt(p.T) << ", " << p.cells << " cells x " << p.ppc
    << " ppc, " << to_string(p.bc) << "\n";
  std::string verdict = r.stable ? "stable" : "unstable";
  if (r.failure) {
    verdict += " (" + std::string(to_string(r.failure->reason)) + " at step " +
               std::to_string(r.failure->step) + ", t = " + fmt(r.failure->time) + ", particle " +
               std::to_string(r.failure->particle) + ")";
  }
  if (r.meaningless.value_or(false)) verdict += ", meaningless: error over time reached A";
  auto line = [&](std::string_view key, const std::string& value) {
    s << "  " << key << std::string(22 - key.size(), ' ') << value << "\n";
  };
  line("verdict", verdict);
  line("steps", std::to_string(r.steps) +
                    (r.steps_planned ? " of " + std::to_string(r.steps_planned) : std::string()) +
                    "  (policy " + std::string(to_string(p.stepping.policy)) + ", dt " +
                    fmt(r.dt_min) + " to " + fmt(r.dt_max) + ")");
  line("max_error", fmt(r.max_error));
  line("max_error_over_time", fmt(r.max_error_over_time));
  line("dt_stable_min", fmt(r.dt_stable_min) + "  (eq. 108, sigma " +
                            std::string(to_string(p.stable.sigma)) + ", ||v|| " +
                            std::string(to_string(p.stable.vnorm)) + ")");
  line("crossings", fmt(r.crossings));
  line("dt_cfl = h/c", fmt(r.dt_cfl));
  line("dt_sound = 1/c", fmt(r.dt_sound));
  line("courant = c dt/h", fmt(r.courant) + (r.dt_min != r.dt_max ? "  (largest dt)" : ""));
  line("wall_seconds", fmt(r.wall_seconds));
  line("ns/particle-step", fmt(r.ns_per_particle_step));
  return s.str();
}

std::string history_csv(const RunResult& r) {
  std::ostringstream s;
  s.precision(17);
  s << "step,time,error,dt_stable,crossings\n";
  for (const auto& h : r.history) {
    s << h.step << ',' << h.time << ',';
    if (h.error) s << *h.error;
    s << ',';
    if (h.dt_stable) s << *h.dt_stable;
    s << ',';
    if (h.crossings) s << *h.crossings;
    s << '\n';
  }
  return s.str();
}

constexpr const char* kEdgeHelp =
    R"(Usage: mpmstab edge --method gimp|cpgimp|mpm --E <x> --A <x> [options]

Finds the real stability edge of one case: the largest fixed dt with which the bar survives
to T (the scene, method and choices as given). A log-spaced scan dt = (h/c) 2^(k/2) from h/(16c) to 4h/c, then bisection to within
--tolerance. Reports dt_edge, dt_edge / (h/c), dt_edge / (the eq. 108 minimum of the run at
dt_edge), and warns when stability is not monotone in dt.

Options: --T, --cells, --ppc, --bc, --position-update, --scene, --walls, --transfer,
--flip-fraction, --update, --body-force-time, --dt-stable-sigma, --dt-stable-vnorm,
--max-steps as for 'mpmstab run'; --tolerance <x> (default 0.02); --json.
)";

// The options of `run` that describe the case (not its dt, policy or history), and the
// search's tolerance.
const std::vector<OptionSpec> kEdgeOptions = [] {
  const std::vector<std::string> searched = {"dt",     "policy",  "cfl-factor",
                                             "safety", "history", "history-stride"};
  std::vector<OptionSpec> options;
  for (const auto& o : kOptions) {
    if (std::find(searched.begin(), searched.end(), o.name) == searched.end()) {
      options.push_back(o);
    }
  }
  options.push_back({"tolerance"});
  return options;
}();

}  // namespace

int cmd_edge(const std::vector<std::string_view>& argv) {
  const Args args(argv, kEdgeOptions);
  if (args.flag("help")) {
    std::cout << kEdgeHelp;
    return 0;
  }
  if (!args.positional().empty()) {
    throw UsageError("unexpected argument '" + std::string(args.positional().front()) + "'");
  }
  EdgeOptions options;
  if (auto v = args.value("tolerance")) {
    options.tolerance = parse_double(*v, "tolerance");
    if (!(options.tolerance >= 1e-6 && options.tolerance <= 1)) {
      throw UsageError("--tolerance: must be in [1e-6, 1]");
    }
  }
  const RunParams params = params_from(args, true);
  const EdgeResult e = find_edge(params, options);
  nlohmann::ordered_json j = edge_to_json(e);
  if (args.flag("json")) {
    nlohmann::ordered_json out = {{"method", to_string(params.method)},
                                  {"E", params.E},
                                  {"A", params.A},
                                  {"T", params.T},
                                  {"cells", params.cells},
                                  {"ppc", params.ppc},
                                  {"bc", to_string(params.bc)}};
    for (auto& [k, v] : j.items())
      out[k] = v;
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  std::cout << "mpmstab edge: " << to_string(params.method) << ", E = " << fmt(params.E)
            << ", A = " << fmt(params.A) << ", T = " << fmt(params.T) << ", " << params.cells
            << " cells x " << params.ppc << " ppc, " << to_string(params.bc) << "\n";
  if (!e.dt_edge) {
    std::cout << "  no dt from h/(16c) to 4h/c survives to T\n";
    return 0;
  }
  std::cout << "  dt_edge               " << fmt(*e.dt_edge)
            << (e.dt_fail ? "  (fails at " + fmt(*e.dt_fail) + ")"
                          : std::string("  (every dt up to T survives)"))
            << "\n  h/c                   " << fmt(e.dt_cfl) << "\n  dt_edge / (h/c)       "
            << fmt(*e.dt_edge / e.dt_cfl) << "\n";
  if (e.at_edge && e.at_edge->dt_stable_min) {
    std::cout << "  eq. (108) at dt_edge  " << fmt(*e.at_edge->dt_stable_min)
              << "\n  dt_edge / eq. (108)   " << fmt(*e.dt_edge / *e.at_edge->dt_stable_min)
              << "\n";
  }
  std::cout << "  runs                  " << e.probes.size() << " in " << fmt(e.wall_seconds)
            << " s\n";
  if (!e.failed_below_edge.empty()) {
    std::cout << "  warning: stability is not monotone in dt: smaller steps failed at";
    for (double dt : e.failed_below_edge)
      std::cout << " " << fmt(dt);
    std::cout << "\n";
  }
  return 0;
}

int cmd_run(const std::vector<std::string_view>& argv) {
  const Args args(argv, kOptions);
  if (args.flag("help")) {
    std::cout << kHelp;
    return 0;
  }
  if (!args.positional().empty()) {
    throw UsageError("unexpected argument '" + std::string(args.positional().front()) + "'");
  }
  const RunParams params = params_from(args);
  const RunResult result = run(params);
  if (auto path = args.value("history")) {
    try {
      write_file_atomically(std::string(*path), history_csv(result));
    } catch (const std::runtime_error& e) {
      throw UsageError(std::string("--history: ") + e.what());
    }
  }
  if (args.flag("json")) {
    std::cout << to_json(result).dump(2) << "\n";
  } else {
    std::cout << text_summary(result);
  }
  return 0;
}

}  // namespace mpmstab::cli
