// `mpmstab spectral`: the spectral limit of one scheme (core/analysis/spectral.hpp).
#include <algorithm>
#include <chrono>
#include <iostream>
#include <ostream>
#include <string>

#include "analysis/bloch.hpp"
#include "analysis/spectral.hpp"
#include "args.hpp"
#include "base/params.hpp"
#include "commands.hpp"
#include "run_options.hpp"
#include "step/simulation.hpp"

namespace mpmstab::cli {

namespace {

constexpr const char* kSpectralHelp =
    R"(Usage: mpmstab spectral --method <basis> --E <x> [options]

The spectral limit of one scheme: the largest time step at which its one-step map, linearised
about rest (v = 0, F = 1) with the particles frozen at the scene's initial layout, has no
eigenvalue of modulus above 1 + 1e-8 (docs/theory.md, "The spectral limit"). The map is taken
from the program's own step by central differences; it is a polynomial of degree two in
c dt / h, built from four maps; the limit is found by a scan up from c dt / h = 0.25 by factors
of 1.4 (to 8) and a bisection to a relative 1e-4. Two analyses:
  --analysis bloch  (default where the layout is uniform: the bar, or any scene at A = 0)
      the Bloch symbol of the interior, S(theta) = sum_d B_d e^(i d theta), at 257 wavenumbers
      theta in [0, pi], each a small eigenvalue problem (Eigen's ComplexEigenSolver); the same
      for every number of cells; the walls' own modes are not in it.
  --analysis dense  (default otherwise) the whole map of the bar, walls included (Eigen's
      EigenSolver): at most 400 particles with APIC and 600 otherwise (cells x ppc).
Prints courant_spectral (c dt / h at the limit, the same for every E), dt_spectral in seconds
for the given E, the spectral radius just above the limit and the eigenvector that limits it
(|velocity| and |strain| per particle, largest 1: every particle for dense, one cell's for
Bloch, with its wavenumber theta / pi).

Options: --cells, --ppc, --bc, --scene, --walls, --transfer, --flip-fraction, --xpic-order,
--fmpm-order, --update, --shift, --jitter as for 'mpmstab run' (--position-update and --body-force-time are
accepted and do not enter the linearised map); --A <x>: the amplitude of the scene's initial
layout (default 0; the bar's layout is uniform at every A); --analysis bloch|dense; --json.

Every scheme's limit is checked by runs just below and above it in results/spectral.md.
)";

std::vector<OptionSpec> spectral_options() {
  const std::vector<std::string> unused = {"dt",
                                           "T",
                                           "policy",
                                           "cfl-factor",
                                           "safety",
                                           "history",
                                           "history-stride",
                                           "max-steps",
                                           "dt-stable-sigma",
                                           "dt-stable-vnorm"};
  std::vector<OptionSpec> options;
  for (const auto& o : run_options()) {
    if (std::find(unused.begin(), unused.end(), o.name) == unused.end()) options.push_back(o);
  }
  options.push_back({"analysis"});
  return options;
}

struct Measured {
  SpectralLimit limit;
  double h = 0, c = 0;
  Eigen::ArrayXd x;
  double seconds = 0;
};

nlohmann::ordered_json spectral_json(const RunParams& p, const Measured& m) {
  nlohmann::ordered_json out = {{"method", to_string(p.method)},
                                {"E", p.E},
                                {"cells", p.cells},
                                {"ppc", p.ppc},
                                {"bc", to_string(p.bc)},
                                {"scene", to_string(p.scene)},
                                {"walls", to_string(p.walls)},
                                {"transfer", to_string(p.transfer)},
                                {"update", to_string(p.update)}};
  if (p.transfer == Transfer::xpic) out["xpic_order"] = p.xpic_order;
  if (p.transfer == Transfer::fmpm) out["fmpm_order"] = p.fmpm_order;
  if (p.transfer == Transfer::blend) out["flip_fraction"] = p.flip_fraction;
  out["analysis"] = to_string(m.limit.analysis);
  out["tolerance"] = kSpectralTolerance;
  if (m.limit.courant) {
    out["courant_spectral"] = *m.limit.courant;
    out["dt_spectral"] = *m.limit.courant * m.h / m.c;
    out["radius_above"] = m.limit.radius_above;
    const Eigen::ArrayXd x = m.x.head(m.limit.mode_v.size());  // Bloch: the first cell's
    out["mode"] = {
        {"x", std::vector<double>(x.begin(), x.end())},
        {"velocity", std::vector<double>(m.limit.mode_v.begin(), m.limit.mode_v.end())},
        {"strain", std::vector<double>(m.limit.mode_strain.begin(), m.limit.mode_strain.end())}};
    if (m.limit.wavenumber) out["mode"]["wavenumber"] = *m.limit.wavenumber;
  } else {
    out["courant_spectral"] = nullptr;
    out["dt_spectral"] = nullptr;
    out["searched_to"] = kMaxSpectralCourant;
  }
  out["maps_built"] = m.limit.evaluations;
  out["eigen_solves"] = m.limit.solves;
  out["wall_seconds"] = m.seconds;
  return out;
}

void print_summary(std::ostream& out, const RunParams& p, const Measured& m) {
  out << "mpmstab spectral: " << to_string(p.method) << ", " << p.cells << " cells x " << p.ppc
      << " ppc, " << to_string(p.bc) << nondefault_choices(p) << ", "
      << (m.limit.analysis == SpectralAnalysis::bloch ? "Bloch symbol of the interior"
                                                      : "dense map of the whole bar")
      << "\n";
  if (!m.limit.courant) {
    out << "  no amplifying map up to c dt / h = " << fmt(kMaxSpectralCourant) << "\n";
  } else {
    Eigen::Index k = 0;
    m.limit.mode_strain.maxCoeff(&k);
    Eigen::Index kv = 0;
    m.limit.mode_v.maxCoeff(&kv);
    out << "  courant_spectral      " << fmt(*m.limit.courant)
        << "  (c dt / h at the limit, every E)\n  dt_spectral           "
        << fmt(*m.limit.courant * m.h / m.c) << " s at E = " << fmt(p.E)
        << "\n  radius just above     1 + " << fmt(m.limit.radius_above - 1)
        << "\n  limiting mode         ";
    if (m.limit.wavenumber) out << "wavenumber theta / pi = " << fmt(*m.limit.wavenumber) << ", ";
    out << "strain largest at particle " << k << " (x = " << fmt(m.x[k])
        << "), velocity at particle " << kv << " (x = " << fmt(m.x[kv]) << ")"
        << (m.limit.wavenumber ? " of a cell" : "") << "\n";
  }
  out << "  work                  " << m.limit.evaluations << " maps, " << m.limit.solves
      << " eigenvalue problems, in " << fmt(m.seconds) << " s\n";
}

}  // namespace

int cmd_spectral(const std::vector<std::string_view>& argv) {
  const Args args(argv, spectral_options());
  if (args.flag("help")) {
    std::cout << kSpectralHelp;
    return 0;
  }
  if (!args.positional().empty()) {
    throw UsageError("unexpected argument '" + std::string(args.positional().front()) + "'");
  }
  const RunParams p = params_from(args, true, false);
  bool bloch = uniform_layout(p);
  if (const auto a = args.value("analysis")) {
    if (*a != "bloch" && *a != "dense") {
      throw UsageError("--analysis: expected bloch or dense, got '" + std::string(*a) + "'");
    }
    if (*a == "bloch" && !bloch) {
      throw UsageError(
          "--analysis: bloch needs a uniform layout (the bar, or the steffen or mode scene "
          "at A = 0)");
    }
    bloch = *a == "bloch";
  }
  if (!bloch && spectral_state_size(p) > kMaxSpectralState) {
    throw UsageError("--cells: the spectral limit is computed for at most " +
                     std::to_string(kMaxSpectralState / (p.transfer == Transfer::apic ? 3 : 2)) +
                     " particles (cells x ppc) by the dense solver; got " +
                     std::to_string(p.cells * p.ppc));
  }
  Measured m;
  const auto start = std::chrono::steady_clock::now();
  m.limit = bloch ? bloch_limit(p) : spectral_limit(p);
  m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const Simulation sim(p);
  m.h = 1.0 / p.cells;
  m.c = sim.scene().c;
  m.x = sim.particles().x;
  if (args.flag("json")) {
    std::cout << spectral_json(p, m).dump(2) << "\n";
  } else {
    print_summary(std::cout, p, m);
  }
  return 0;
}

}  // namespace mpmstab::cli
