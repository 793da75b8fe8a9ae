#include "bloch.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <complex>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "simulation.hpp"

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
Eigen::MatrixXcd symbol(const Eigen::MatrixXd& R, const Probe& pr, double theta) {
  const int ppc = pr.bar.ppc;
  const Eigen::Index n = Eigen::Index(pr.bar.cells) * ppc;
  const Eigen::Index k = R.cols();
  Eigen::MatrixXcd S = Eigen::MatrixXcd::Zero(k, k);
  for (Eigen::Index row = 0; row < R.rows(); ++row) {
    const Eigen::Index value = row / n, particle = row % n;
    const int d = int(particle / ppc) - pr.middle;
    const Eigen::Index i = value * ppc + particle % ppc;
    const std::complex<double> phase = std::polar(1.0, -d * theta);
    for (Eigen::Index j = 0; j < k; ++j)
      if (R(row, j) != 0) S(i, j) += R(row, j) * phase;
  }
  return S;
}

struct Peak {
  double radius = 0;
  double theta = 0;
};

// The largest spectral radius over the wavenumbers, from theta = pi down (where the worst mode
// of most schemes lies); with `stop_above`, the first radius above it is returned at once.
Peak peak_radius(const Eigen::MatrixXd& R, const Probe& pr, int& solves,
                 double stop_above = std::numeric_limits<double>::infinity()) {
  Peak peak;
  Eigen::ComplexEigenSolver<Eigen::MatrixXcd> es;
  for (int j = kBlochSamples; j >= 0; --j) {
    const double theta = kPi * j / kBlochSamples;
    es.compute(symbol(R, pr, theta), false);
    const double r = es.eigenvalues().cwiseAbs().maxCoeff();
    ++solves;
    if (r > peak.radius) peak = {r, theta};
    if (r > stop_above) break;
  }
  return peak;
}

}  // namespace

bool uniform_layout(const RunParams& p) {
  return (p.scene == SceneKind::bar || p.A == 0) && p.layout.jitter == 0;
}

bool bloch_applies(const RunParams& p) {
  return uniform_layout(p) && (p.transfer == Transfer::apic ? 3 : 2) * p.ppc <= kMaxBlochSymbol;
}

Eigen::MatrixXcd bloch_symbol(const RunParams& p, double courant, double theta) {
  const Probe pr = interior_probe(p);
  return symbol(linear_step_columns(pr.bar, pr.x, courant, pr.columns), pr, theta);
}

SpectralLimit bloch_limit(const RunParams& p) {
  if (!bloch_applies(p)) {
    throw std::invalid_argument("bloch_limit: needs a uniform layout and a symbol of at most " +
                                std::to_string(kMaxBlochSymbol) + " values");
  }
  SpectralLimit out;
  out.analysis = SpectralAnalysis::bloch;
  const Probe pr = interior_probe(p);
  const auto response_at = quadratic_in_courant(
      [&](double C) { return linear_step_columns(pr.bar, pr.x, C, pr.columns); }, out.evaluations);
  const double threshold = 1 + kSpectralTolerance;
  int calls = 0;
  const auto bracket = first_amplifying_courant(
      [&](double C) {
        return peak_radius(response_at(C), pr, out.solves, threshold).radius > threshold;
      },
      std::nullopt, calls);
  if (!bracket) return out;
  out.courant = bracket->first;
  const Eigen::MatrixXd R = response_at(bracket->second);
  const Peak peak = peak_radius(R, pr, out.solves);
  out.radius_above = peak.radius;
  out.wavenumber = peak.theta / kPi;
  Eigen::ComplexEigenSolver<Eigen::MatrixXcd> es(symbol(R, pr, peak.theta), true);
  Eigen::Index top = 0;
  es.eigenvalues().cwiseAbs().maxCoeff(&top);
  set_limiting_mode(out, es.eigenvectors().col(top).cwiseAbs().array(), p.ppc);
  return out;
}

}  // namespace mpmstab
