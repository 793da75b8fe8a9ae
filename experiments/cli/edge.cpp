// `mpmstab edge`: the largest fixed dt with which one case survives to T, and the largest that
// stays accurate (core/run/edge.hpp).
#include <algorithm>
#include <iostream>
#include <optional>
#include <ostream>
#include <string>

#include "args.hpp"
#include "base/accuracy.hpp"
#include "base/params.hpp"
#include "commands.hpp"
#include "result_json.hpp"
#include "run/edge.hpp"
#include "run_options.hpp"

namespace mpmstab::cli {

namespace {

constexpr const char* kEdgeHelp =
    R"(Usage: mpmstab edge --method <basis> --E <x> --A <x> [options]

Finds the real edges of one case in fixed dt (the scene, method and choices as given): the
survival edge dt_edge, the largest dt with which the bar survives to T, and the accuracy edge
dt_accurate, the largest dt up to which every dt tried from the reference (the smallest that
survives) survives with an error over time within 2 times the reference's; it is printed only
where the reference run and its own run are accurate (an error over time below a tenth of A:
docs/studies.md, "Accuracy classes"). A log-spaced scan dt = (h/c) 2^(k/2) from h/(16c) to 4h/c
(at most T / 10: a run of fewer steps gets no verdict), bisection to within --tolerance, then 8
dts from 0.9 x the edge up to it; a failure there moves the edge below it. Each edge is the
lowest failure found: where a larger dt survives again it says so (not monotone). Reports the
run length c T and amplitude A the edges hold for, both edges against h/c, dt_edge / (the
eq. 108 minimum of the run at dt_edge), and the dts where survival flips. Runs of fewer than
one wave pass are too short for a verdict: no edge.

Options: --T, --cells, --ppc, --bc, --position-update, --scene, --walls, --transfer,
--flip-fraction, --xpic-order, --fmpm-order, --update, --shift, --jitter, --body-force-time, --dt-stable-sigma, --dt-stable-vnorm,
--max-steps as for 'mpmstab run'; --tolerance <x> (default 0.02); --json.
)";

// The options of `run` that describe the case (not its dt, policy or history), and the
// search's tolerance.
std::vector<OptionSpec> edge_options() {
  const std::vector<std::string> searched = {"dt",     "policy",  "cfl-factor",
                                             "safety", "history", "history-stride"};
  std::vector<OptionSpec> options;
  for (const auto& o : run_options()) {
    if (std::find(searched.begin(), searched.end(), o.name) == searched.end()) {
      options.push_back(o);
    }
  }
  options.push_back({"tolerance"});
  return options;
}

// The case, then the search's result (edge_to_json).
nlohmann::ordered_json edge_json(const RunParams& params, const EdgeResult& e) {
  nlohmann::ordered_json out = {{"method", to_string(params.method)},
                                {"E", params.E},
                                {"A", params.A},
                                {"T", params.T},
                                {"cells", params.cells},
                                {"ppc", params.ppc},
                                {"bc", to_string(params.bc)}};
  nlohmann::ordered_json j = edge_to_json(e);
  for (auto& [k, v] : j.items())
    out[k] = v;
  return out;
}

void print_summary(std::ostream& out, const RunParams& params, const EdgeResult& e) {
  out << "mpmstab edge: " << to_string(params.method) << ", E = " << fmt(params.E)
      << ", A = " << fmt(params.A) << ", T = " << fmt(params.T) << ", " << params.cells
      << " cells x " << params.ppc << " ppc, " << to_string(params.bc) << nondefault_choices(params)
      << "\n";
  out << "  holds for             c T = " << fmt(e.wave_passes) << " wave passes, A = " << fmt(e.A)
      << "\n";
  if (e.too_short) {
    out << "  no edge: runs of fewer than " << fmt(kMinWavePasses)
        << " wave pass are too short for a verdict\n";
    return;
  }
  if (!e.dt_edge) {
    out << "  no edge: "
        << (e.dt_fail ? "the smallest dt tried, " + fmt(*e.dt_fail) + ", fails"
                      : std::string("no dt from h/(16c) survives to T"))
        << (e.survives_above ? " (not monotone: survives at " + fmt(*e.survives_above) + ")"
                             : std::string())
        << "\n";
    return;
  }
  out << "  dt_edge               " << fmt(*e.dt_edge)
      << (e.dt_fail ? "  (fails at " + fmt(*e.dt_fail) + ")"
                    : std::string("  (every dt with a verdict survives)"))
      << "\n  monotone              "
      << (e.monotone() ? std::string("yes: every dt tried up to the edge survives, none above")
                       : "no: the lowest failure is the edge; survives again at up to " +
                             fmt(*e.survives_above))
      << "\n  h/c                   " << fmt(e.dt_cfl) << "\n  dt_edge / (h/c)       "
      << fmt(*e.dt_edge / e.dt_cfl) << "\n";
  if (e.at_edge) {
    if (e.at_edge->outcome)
      out << "  outcome at dt_edge    " << to_string(*e.at_edge->outcome) << "\n";
    if (e.at_edge->max_error_over_time)
      out << "  error over time there " << fmt(*e.at_edge->max_error_over_time) << " ("
          << fmt(*e.at_edge->max_error_over_time / params.A) << " A)\n";
    if (e.at_edge->max_error)
      out << "  error at T there      " << fmt(*e.at_edge->max_error) << "\n";
    if (e.at_edge->dt_stable_min) {
      out << "  eq. (108) at dt_edge  " << fmt(*e.at_edge->dt_stable_min)
          << "\n  dt_edge / eq. (108)   " << fmt(*e.dt_edge / *e.at_edge->dt_stable_min) << "\n";
    }
  }
  out << "  reference             dt " << fmt(*e.dt_reference) << ", error over time "
      << fmt(*e.max_error_reference) << " (" << fmt(*e.max_error_reference / params.A) << " A)\n";
  std::optional<double> at_accurate;
  for (const auto& p : e.probes) {
    if (e.dt_accurate && p.dt == *e.dt_accurate) at_accurate = p.max_error;
  }
  const bool accurate =
      accuracy_class(*e.max_error_reference, params.A) == Accuracy::accurate &&
      (!at_accurate || accuracy_class(*at_accurate, params.A) == Accuracy::accurate);
  if (e.dt_accurate && !accurate) {
    out << "  dt_accurate           none: the reference run or the run at the search's "
        << fmt(*e.dt_accurate) << " is not accurate (error over time at least "
        << fmt(kAccurateFraction) << " A)\n";
  } else if (e.dt_accurate) {
    out << "  dt_accurate           " << fmt(*e.dt_accurate) << "  (error over time within "
        << fmt(e.accuracy_factor) << " x the reference's"
        << (e.dt_inaccurate ? "; not at " + fmt(*e.dt_inaccurate) : std::string()) << ")"
        << "\n  dt_accurate / (h/c)   " << fmt(*e.dt_accurate / e.dt_cfl) << "\n"
        << "  accuracy monotone     "
        << (e.accuracy_monotone() ? std::string("yes")
                                  : "no: accurate again at up to " + fmt(*e.accurate_above))
        << "\n";
  } else {
    out << "  dt_accurate           none: the reference run is meaningless\n";
  }
  out << "  runs                  " << e.probes.size() << ", " << fmt(double(e.particle_steps))
      << " particle-steps, in " << fmt(e.wall_seconds) << " s\n";
  if (!e.flips.empty()) {
    out << "  survival flips        as dt grows it";
    for (const auto& f : e.flips)
      out << (&f == &e.flips.front() ? " " : ", ")
          << (f.survives ? "survives from " : "fails from ") << fmt(f.dt);
    out << "\n";
  }
}

}  // namespace

int cmd_edge(const std::vector<std::string_view>& argv) {
  const Args args(argv, edge_options());
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
  if (args.flag("json")) {
    std::cout << edge_json(params, e).dump(2) << "\n";
  } else {
    print_summary(std::cout, params, e);
  }
  return 0;
}

}  // namespace mpmstab::cli
