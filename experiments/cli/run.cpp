// `mpmstab run`: one case of the bar, measured (docs/theory.md, "Measured quantities").
#include <iostream>
#include <optional>
#include <sstream>
#include <type_traits>

#include "args.hpp"
#include "base/params.hpp"
#include "commands.hpp"
#include "files.hpp"
#include "observers/energy.hpp"
#include "result_json.hpp"
#include "run/run.hpp"
#include "run_options.hpp"
#include "run_summary.hpp"

namespace mpmstab::cli {

namespace {

constexpr const char* kRunHelp =
    R"(Usage: mpmstab run --method <basis> --E <x> --A <x> --dt <x> [options]

Runs one case of a 1D scene to time T (default: the paper's bar, manufactured solution
u = A sin(2 pi X) sin(c pi t), c = sqrt(E)) and reports its verdict and every measured
quantity.

Required:
  --method <basis>         shape functions: gimp (uGIMP), cpgimp (half-width follows F), mpm
                           (linear hat), bspline2 or bspline3 (quadratic or cubic B-spline,
                           the node beyond a Dirichlet wall eliminated by linear
                           extrapolation) or cpdi (the hat interpolated between the corners
                           of cpGIMP's domain); the last three with the fixed or cfl policy
                           only, dt_stable not measured
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
  --scene bar|steffen|mode|vibration|impulsive|compaction|block|impact
                           the paper's bar (default: linear material, u = A sin(2 pi X)
                           sin(c pi t)), Steffen et al. (2008): neo-Hookean material,
                           u = A sin(2 pi X) cos(c pi t), or mode: one free standing wave
                           of the linear bar, u = A sin(2 pi X) cos(2 pi c t), no body
                           force, --bc periodic only; or a body in a larger grid (A is its
                           displacement scale; docs/theory.md, "Scenes"): vibration (fixed-
                           free bar, first mode of tip amplitude A), impulsive (tip traction
                           E A / (2 L) from t = 0), compaction (body force ramped to the
                           static top compaction A), block (rigid translation at A c),
                           impact (two bars meeting at +-A c / (L / 2))
  --walls clip|ghost       GIMP supports at a Dirichlet wall: nodes on [0, 1] only
                           (default) or one free ghost node beyond each wall
  --transfer flip|pic|blend|apic|xpic|fmpm
                           particle velocity update (default flip); apic: PIC with an affine
                           velocity per particle (Jiang et al. 2015); xpic: XPIC(m)
                           (Hammerquist and Nairn 2017); fmpm: FMPM(k) (Nairn and
                           Hammerquist 2021); order 1 of either is PIC
  --flip-fraction <a>      FLIP share of a blend, 0 < a < 1 (default 0.95)
  --xpic-order <m>         m of XPIC(m), 1..32 (default 2; transfer xpic only)
  --fmpm-order <k>         k of FMPM(k), 1..32 (default 2; transfer fmpm only)
  --shift <s>              move every particle by s times the spacing h / ppc, s in (-0.5, 0.5)
                           (default 0: centred in its slot; near 0.5 a particle sits near a node)
  --jitter <j>             move each particle by j times the spacing times its own fixed
                           pseudo-random number in [-1/2, 1/2), j in [0, 1) (default 0)
  --update usl|usf|musl    stress update last (default), first (the paper's section 6),
                           or last with the grid velocity re-mapped from the particles
  --body-force-time start|end
                           evaluate b at the start t^n (default) or end t^{n+1} of a step
  --start exact|half_step  the particles' velocity starts as the exact v(X, 0) (default) or
                           v(X, -dt/2), the leapfrog's staggered start (fixed or cfl policy,
                           bar or steffen scene)
  --body-start <x0>        left end of the body in the grid [0, 1] (block, impact; default
                           the scene's own), on a cell boundary
  --body-length <L>        length of the body (vibration, impulsive, compaction, block,
                           impact; default the scene's own), a whole number of cells
  --small-mass none|cutoff|drop|momentum
                           treatment of nodes with less mass than a fraction of rho0 h
                           (scenes with a free surface; default none)
  --small-mass-fraction <f>
                           that fraction, in (0, 1] (default 0.01; with --small-mass only)
  --tip-load <k>           add a traction k E A / (2 L) held on the free end from t = 0
                           (vibration, impulsive, compaction; default 0), k >= 0
  --dt-stable-sigma scaled|raw
                           stress in eq. (108) scaled by 1/sqrt(E) (default) or not
  --dt-stable-vnorm l2|max norm of the nodal velocity in eq. (108) (default l2)
  --policy fixed|cfl|adaptive|min|spectral
                           time-step policy (default fixed): fixed dt; dt = C h / c;
                           dt_n = s * eq. (108) bound of the current state; the minimum
                           of the last two; or dt = s * the spectral limit of the layout
                           (recomputed each time the largest displacement from the
                           initial layout grows by another h; at most 600 particles). Every policy lands exactly on T. An adaptive or
                           min run whose step falls below 1e-3 h/c stops as unstable with
                           the reason dt_collapse.
  --cfl-factor <C>         Courant factor of the cfl and min policies (default 0.5)
  --safety <s>             factor on the eq. (108) bound (adaptive, min) or on the
                           spectral limit (spectral) (default 1)
  --max-steps <n>          refuse runs needing more steps (default 200000000); an adaptive
                           run that reaches it stops with the verdict step_limit
  --history <file.csv>     also write the per-step history (error, eq. 108, crossings)
  --history-stride <n>     keep every n-th step in the history (default 1)
  --tip                    in the history, also the displacement of the body's last particle
                           (the free end) and the exact one there: tip_u, tip_u_exact
  --energy                 also observe the energies at every step: the record's
                           energy_error_max, energy_exact_error_max, energy_drift and
                           energy_warning_step, and the history's energy columns
  --error-l2               also measure error_l2_time, the RMS of the displacement error
                           over the body and the run
  --json                   print the run's record (one JSON object, the same as a row of
                           a sweep's results) instead of the text summary; the record
                           holds no wall time (the text summary shows it)
  --help                   show this text

Every quantity printed (outcome, steps, dt_min/dt_max/dt_mean, max_error,
max_error_over_time, dt_stable_min, crossings, dt_cfl, courant, ...) is defined with its
unit in docs/theory.md, "Measured quantities". The outcome is unstable (the run stopped:
reason and step), meaningless (it reached T but its error over time reached A) or stable.

Exit status: 0 when the run completed (stable or not: an unstable run is a result),
2 for invalid input (nothing is run or written), 1 for an internal error.
)";

// One line of the history CSV (header: kHistoryHeader).
// The energy columns are empty unless the run observes its energy (--energy), the tip columns
// unless it observes its tip (--tip).
constexpr std::string_view kHistoryHeader =
    "step,time,error,dt_stable,crossings,kinetic,strain,work,energy_balance,kinetic_exact,"
    "strain_exact,work_exact,tip_u,tip_u_exact\n";
std::string history_line(const HistoryRow& h) {
  std::ostringstream s;
  s.precision(17);
  s << h.step << ',' << h.time;
  auto cell = [&s](const auto& v) {
    s << ',';
    if (v) s << *v;
  };
  cell(h.error);
  cell(h.dt_stable);
  cell(h.crossings);
  for (const auto* v : {&h.kinetic, &h.strain, &h.work, &h.energy_balance, &h.kinetic_exact,
                        &h.strain_exact, &h.work_exact, &h.tip_u, &h.tip_u_exact})
    cell(*v);
  s << '\n';
  return s.str();
}

}  // namespace

int cmd_run(const std::vector<std::string_view>& argv) {
  const Args args(argv, run_options());
  if (args.flag("help")) {
    std::cout << kRunHelp;
    return 0;
  }
  if (!args.positional().empty()) {
    throw UsageError("unexpected argument '" + std::string(args.positional().front()) + "'");
  }
  const RunParams params = params_from(args);
  // The history file is checked before the run and its rows streamed into a temporary file as
  // the run makes them; it replaces FILE only when the run is over.
  std::optional<FileWriter> history;
  if (auto path = args.value("history")) {
    try {
      history.emplace(std::string(*path));
    } catch (const std::runtime_error& e) {
      throw UsageError(std::string("--history: ") + e.what());
    }
    history->write(kHistoryHeader);
  }
  HistorySink sink;
  if (history) sink = [&history](const HistoryRow& h) { history->write(history_line(h)); };
  const RunResult result = run(params, nullptr, sink);
  if (history) history->commit();
  if (args.flag("json")) {
    // The record with, after courant, the run's other dimensionless coordinates: the columns of
    // a sweep's rows.
    const nlohmann::ordered_json record = to_json(result);
    nlohmann::ordered_json j;
    for (const auto& [k, v] : record.items()) {
      j[k] = v;
      if (k != "courant") continue;
      j["A_over_h"] = amplitude_per_cell(params);
      j["cT"] = wave_passes(params);
    }
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << text_summary(result);
  }
  return 0;
}

}  // namespace mpmstab::cli
