#include "analysis/bloch.hpp"
#include "scenes/scene_registry.hpp"

#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "analysis/eigen_solve.hpp"
#include "step/simulation.hpp"

namespace mpmstab {

namespace {

constexpr double kPi = 3.14159265358979323846;
// Cells left untouched at either wall by the response to the middle cell.
constexpr int kWallMargin = 4;
constexpr int kMaxBlochCells = 4096;

// The response of every particle's state to the state of the particles of the middle cell of
// a bar of `cells` cells, at one Courant number: size x k, k = values x ppc.
struct Probe {
  RunParams bar;
  Eigen::ArrayXd x;
  int middle = 0;
  std::vector<Eigen::Index> columns;
};

Probe probe_of(const RunParams& p, int cells) {
  Probe pr;
  pr.bar = p;
  pr.bar.cells = cells;
  pr.bar.A = 0;
  pr.x = Simulation(pr.bar).particles().x;
  pr.middle = cells / 2;
  const Eigen::Index n = Eigen::Index(cells) * p.ppc;
  const int values = int(spectral_state_size(pr.bar) / n);
  for (int v = 0; v < values; ++v)
    for (int k = 0; k < p.ppc; ++k)
      pr.columns.push_back(v * n + Eigen::Index(pr.middle) * p.ppc + k);
  return pr;
}

// The farthest cell (from the middle) whose state responds.
int reach_of(const Eigen::MatrixXd& R, const Probe& pr) {
  const int ppc = pr.bar.ppc;
  const Eigen::Index n = Eigen::Index(pr.bar.cells) * ppc;
  int reach = 0;
  for (Eigen::Index row = 0; row < R.rows(); ++row) {
    if (R.row(row).cwiseAbs().maxCoeff() == 0) continue;
    const int cell = int((row % n) / ppc);
    reach = std::max(reach, std::abs(cell - pr.middle));
  }
  return reach;
}

// The bar on which the middle cell's response stays kWallMargin cells clear of both walls.
Probe interior_probe(const RunParams& p) {
  for (int cells = 24; cells <= kMaxBlochCells; cells *= 2) {
    Probe pr = probe_of(p, cells);
    const int reach = reach_of(linear_step_columns(pr.bar, pr.x, 1.0, pr.columns), pr);
    if (reach + kWallMargin < cells - 1 - pr.middle) return pr;
  }
  throw std::invalid_argument("bloch_limit: the map reaches beyond " +
                              std::to_string(kMaxBlochCells / 2) + " cells");
}

// The symbol S(theta) from the middle cell's response R: a mode s_j = s e^{i j theta} maps to
// (S s) e^{i j theta}, S = sum_d M_{j, j+d} e^{i d theta} = sum_d B_d e^{-i d theta}, where B_d
// (the response of cell m + d to cell m) is M_{j, j-d} by the translation invariance.
// R's nonzero entries, in the order the sum takes them (rows, then columns), with the cell offset
// d of each: built once per R, then S at every wavenumber from them and one phase per offset.
struct SymbolTerms {
  Eigen::Index size = 0;  // S is size x size
  int min_d = 0;          // offsets from min_d to min_d + phases - 1
  int phases = 0;
  struct Term {
    Eigen::Index i, j;
    int d;
    double value;
  };
  std::vector<Term> terms;
};

SymbolTerms symbol_terms(const Eigen::MatrixXd& R, const Probe& pr) {
  const int ppc = pr.bar.ppc;
  const Eigen::Index n = Eigen::Index(pr.bar.cells) * ppc;
  SymbolTerms t;
  t.size = R.cols();
  int max_d = 0;
  for (Eigen::Index row = 0; row < R.rows(); ++row) {
    const Eigen::Index value = row / n, particle = row % n;
    const int d = int(particle / ppc) - pr.middle;
    const Eigen::Index i = value * ppc + particle % ppc;
    for (Eigen::Index j = 0; j < t.size; ++j) {
      if (R(row, j) == 0) continue;
      if (t.terms.empty() || d < t.min_d) t.min_d = d;
      if (t.terms.empty() || d > max_d) max_d = d;
      t.terms.push_back({i, j, d, R(row, j)});
    }
  }
  t.phases = t.terms.empty() ? 0 : max_d - t.min_d + 1;
  return t;
}

// S(theta): each term adds value * e^{-i d theta}, in R's order (the same sums, bit for bit, as
// adding R(row, j) * std::polar(1, -d theta) row by row).
Eigen::MatrixXcd symbol(const SymbolTerms& t, double theta) {
  std::vector<std::complex<double>> phase(std::size_t(t.phases));
  for (int k = 0; k < t.phases; ++k)
    phase[std::size_t(k)] = std::polar(1.0, -(t.min_d + k) * theta);
  Eigen::MatrixXcd S = Eigen::MatrixXcd::Zero(t.size, t.size);
  for (const SymbolTerms::Term& term : t.terms)
    S(term.i, term.j) += term.value * phase[std::size_t(term.d - t.min_d)];
  return S;
}

Eigen::MatrixXcd symbol(const Eigen::MatrixXd& R, const Probe& pr, double theta) {
  return symbol(symbol_terms(R, pr), theta);
}

struct Peak {
  double radius = 0;
  double theta = 0;
  int sample = -1;  // theta = pi sample / kBlochSamples
};

// The largest spectral radius over the wavenumbers, from theta = pi down (where the worst mode
// of most schemes lies); with `stop_above`, the first radius above it is returned at once, and
// `first`, a sample index, is tried before the others (where the last amplification was: whether
// some radius exceeds `stop_above` does not depend on the order the samples are tried in).
Peak peak_radius(const Eigen::MatrixXd& R, const Probe& pr, int& solves,
                 double stop_above = std::numeric_limits<double>::infinity(), int first = -1) {
  Peak peak;
  const SymbolTerms terms = symbol_terms(R, pr);
  const auto solve_at = [&](int j) {
    const double theta = kPi * j / kBlochSamples;
    const double r = eigen_pairs(symbol(terms, theta), false).values.cwiseAbs().maxCoeff();
    ++solves;
    if (r > peak.radius) peak = {r, theta, j};
    return r > stop_above;
  };
  if (first >= 0 && solve_at(first)) return peak;
  for (int j = kBlochSamples; j >= 0; --j)
    if (j != first && solve_at(j)) break;
  return peak;
}

}  // namespace

bool uniform_layout(const RunParams& p) {
  // A body with ends inside the grid is no lattice: its limit is the dense map's.
  if (!scene_info(p.scene).fills_grid) return false;
  return (p.scene == SceneKind::bar || p.A == 0) && p.layout.jitter == 0;
}

bool bloch_applies(const RunParams& p) {
  return uniform_layout(p) && (p.transfer == Transfer::apic ? 3 : 2) * p.ppc <= kMaxBlochSymbol;
}

Eigen::MatrixXcd bloch_symbol(const RunParams& p, double courant, double theta) {
  const Probe pr = interior_probe(p);
  return symbol(linear_step_columns(pr.bar, pr.x, courant, pr.columns), pr, theta);
}

namespace {

// The search of bloch_limit: the probe, the response as a function of C, and the bracket.
struct BlochSearch {
  Probe probe;
  std::function<Eigen::MatrixXd(double)> response_at;
  std::optional<std::pair<double, double>> bracket;
};

BlochSearch search_bloch(const RunParams& p, SpectralLimit& out) {
  if (!bloch_applies(p)) {
    throw std::invalid_argument("bloch_limit: needs a uniform layout and a symbol of at most " +
                                std::to_string(kMaxBlochSymbol) + " values");
  }
  out.analysis = SpectralAnalysis::bloch;
  BlochSearch s{interior_probe(p), {}, {}};
  const Probe& pr = s.probe;
  s.response_at = quadratic_in_courant(
      [&pr](double C) { return linear_step_columns(pr.bar, pr.x, C, pr.columns); },
      out.evaluations);
  const double threshold = 1 + kSpectralTolerance;
  int calls = 0;
  int last = -1;  // the sample index of the last amplification found, tried first
  s.bracket = first_amplifying_courant(
      [&](double C) {
        const Peak peak = peak_radius(s.response_at(C), pr, out.solves, threshold, last);
        const bool amplifies = peak.radius > threshold;
        if (amplifies) last = peak.sample;
        return amplifies;
      },
      std::nullopt, calls);
  if (s.bracket) out.courant = s.bracket->first;
  return s;
}

}  // namespace

SpectralLimit bloch_limit(const RunParams& p) {
  SpectralLimit out;
  const BlochSearch s = search_bloch(p, out);
  if (!s.bracket) return out;
  const Probe& pr = s.probe;
  const Eigen::MatrixXd R = s.response_at(s.bracket->second);
  const Peak peak = peak_radius(R, pr, out.solves);
  out.radius_above = peak.radius;
  out.wavenumber = peak.theta / kPi;
  const EigenPairs es = eigen_pairs(symbol(R, pr, peak.theta), true);
  Eigen::Index top = 0;
  es.values.cwiseAbs().maxCoeff(&top);
  set_limiting_mode(out, es.vectors.col(top).cwiseAbs().array(), p.ppc);
  return out;
}

std::optional<double> bloch_courant(const RunParams& p) {
  SpectralLimit out;
  search_bloch(p, out);
  return out.courant;
}

}  // namespace mpmstab
