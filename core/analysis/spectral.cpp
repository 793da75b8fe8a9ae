#include "analysis/spectral.hpp"
#include "scenes/scene_registry.hpp"

#include <cmath>
#include <map>
#include <mutex>
#include <sstream>
#include <string>

#include "analysis/bloch.hpp"
#include "analysis/eigen_solve.hpp"
#include "step/simulation.hpp"

namespace mpmstab {

namespace {

// The size of the central difference, in the scaled state (v / c, F - 1, C h / c): 1e-6, small
// enough that the quadratic terms cancel to round-off and large enough that F' - 1 (stored as
// F' near 1) keeps about 10 digits. cpGIMP's and CPDI's weights follow F and, at the uniform
// layout, have a kink at F = 1 (each particle's domain ends on a node): a central difference
// across it errs by O(eps), which at 1e-6 (2e-7 in the map) pushed their neutral eigenvalues past
// 1 + 1e-8 and gave a spurious limit of 0.16 instead of GIMP's 0.756. For their F columns the
// step is 2^-27 (about 7.5e-9, exact in 1 +/- eps), where the kink's error and the rounding of
// F' - 1 are both near 1e-8 of an entry.
constexpr double kEps = 1e-6;
constexpr double kEpsAcrossKink = 0x1p-27;

// p with what the linearisation about rest needs: no amplitude (the body force of either scene
// vanishes with A, so rest is a fixed point of the step) and one step.
RunParams at_rest(const RunParams& p, double dt) {
  RunParams q = p;
  q.A = 0;
  q.stepping.policy = TimeStepPolicy::fixed;
  q.dt = dt;
  q.T = dt;
  q.observe = Observe{};
  return q;
}

// The scaled state after one step from rest plus `delta` (scaled), particles at `x`.
Eigen::VectorXd step_from(const RunParams& q, const Eigen::ArrayXd& x, const Eigen::VectorXd& delta,
                          double c, double h) {
  Simulation sim(q);
  Particles& P = sim.particles();
  const Eigen::Index n = P.size();
  const bool apic = q.transfer == Transfer::apic;
  const MaterialLaw law = sim.scene().law();
  P.x = x;
  P.v = delta.segment(0, n).array() * c;
  P.F = 1.0 + delta.segment(n, n).array();
  for (Eigen::Index k = 0; k < n; ++k)
    P.sigma[k] = law.stress(P.F[k]);
  if (apic) P.C = delta.segment(2 * n, n).array() * (c / h);
  sim.advance_to(q.dt);
  Eigen::VectorXd out(delta.size());
  out.segment(0, n) = P.v.matrix() / c;
  out.segment(n, n) = (P.F - 1.0).matrix();
  if (apic) out.segment(2 * n, n) = P.C.matrix() * (h / c);
  return out;
}

// The largest eigenvalue's modulus and, when asked, its eigenvector's moduli.
double radius_and_mode(const Eigen::MatrixXd& M, Eigen::ArrayXd* mode) {
  const EigenPairs es = eigen_pairs(M, mode != nullptr);
  Eigen::Index k = 0;
  const double r = es.values.cwiseAbs().maxCoeff(&k);
  if (mode) *mode = es.vectors.col(k).cwiseAbs().array();
  return r;
}

}  // namespace

void set_limiting_mode(SpectralLimit& out, Eigen::ArrayXd moduli, Eigen::Index particles) {
  const double top = moduli.maxCoeff();
  if (top > 0) moduli /= top;
  out.mode_v = moduli.segment(0, particles);
  out.mode_strain = moduli.segment(particles, particles);
}

Eigen::MatrixXd linear_step_columns(const RunParams& p, const Eigen::ArrayXd& x, double courant,
                                    const std::vector<Eigen::Index>& columns) {
  const double h = 1.0 / p.cells;
  const double c = Simulation(p).scene().c;
  const RunParams q = at_rest(p, courant * h / c);
  const Eigen::Index size = spectral_state_size(p);
  Eigen::MatrixXd M(size, Eigen::Index(columns.size()));
  Eigen::VectorXd delta = Eigen::VectorXd::Zero(size);
  const Eigen::Index n = x.size();
  for (std::size_t col = 0; col < columns.size(); ++col) {
    const Eigen::Index j = columns[col];
    const bool strain = j >= n && j < 2 * n;
    const double eps = strain && follows_F(p.method) ? kEpsAcrossKink : kEps;
    delta[j] = eps;
    const Eigen::VectorXd plus = step_from(q, x, delta, c, h);
    delta[j] = -eps;
    const Eigen::VectorXd minus = step_from(q, x, delta, c, h);
    delta[j] = 0;
    M.col(Eigen::Index(col)) = (plus - minus) / (2 * eps);
  }
  return M;
}

Eigen::MatrixXd linear_step_map(const RunParams& p, const Eigen::ArrayXd& x, double courant) {
  std::vector<Eigen::Index> all(std::size_t(spectral_state_size(p)));
  for (std::size_t j = 0; j < all.size(); ++j)
    all[j] = Eigen::Index(j);
  return linear_step_columns(p, x, courant, all);
}

std::function<Eigen::MatrixXd(double)> quadratic_in_courant(
    const std::function<Eigen::MatrixXd(double)>& build, int& builds) {
  const Eigen::MatrixXd A0 = build(0.0), A1 = build(1.0), A2 = build(2.0), half = build(0.5);
  builds += 4;
  const Eigen::MatrixXd M2 = 0.5 * (A2 - 2.0 * A1 + A0), M1 = A1 - A0 - M2;
  const bool quadratic =
      (A0 + 0.5 * M1 + 0.25 * M2 - half).cwiseAbs().maxCoeff() <= 1e-8 * (1 + half.norm());
  if (quadratic) {
    return [A0, M1, M2](double C) -> Eigen::MatrixXd { return A0 + C * M1 + C * C * M2; };
  }
  return [build, &builds](double C) -> Eigen::MatrixXd {
    ++builds;
    return build(C);
  };
}

std::optional<std::pair<double, double>> first_amplifying_courant(
    const std::function<bool(double)>& amplifies, std::optional<double> near, int& calls) {
  auto test = [&](double C) {
    ++calls;
    return amplifies(C);
  };
  double lo = 0, hi = 0.25;
  if (near && *near > 0 && !test(0.9 * *near)) {
    lo = 0.9 * *near;
    hi = 1.1 * *near;
  }
  while (!test(hi)) {
    lo = hi;
    hi *= 1.4;
    if (hi > kMaxSpectralCourant) return std::nullopt;
  }
  while (hi - lo > 1e-4 * hi) {
    const double mid = 0.5 * (lo + hi);
    (test(mid) ? hi : lo) = mid;
  }
  return std::pair{lo, hi};
}

double spectral_radius(const Eigen::MatrixXd& M) {
  return radius_and_mode(M, nullptr);
}

SpectralLimit spectral_limit(const RunParams& p) {
  return spectral_limit(p, Simulation(p).particles().x);  // the scene's initial layout
}

namespace {

// The search of spectral_limit: the map as a function of C, and the bracket of its limit.
struct SpectralSearch {
  std::function<Eigen::MatrixXd(double)> map_at;
  std::optional<std::pair<double, double>> bracket;
};

SpectralSearch search_limit(const RunParams& p, const Eigen::ArrayXd& x, std::optional<double> near,
                            SpectralLimit& out) {
  SpectralSearch s;
  // Every scheme's map is a polynomial of degree two in the Courant number (docs/theory.md, "The
  // spectral limit").
  s.map_at = quadratic_in_courant([&p, &x](double C) { return linear_step_map(p, x, C); },
                                  out.evaluations);
  s.bracket = first_amplifying_courant(
      [&](double C) { return spectral_radius(s.map_at(C)) > 1 + kSpectralTolerance; }, near,
      out.solves);
  if (s.bracket) out.courant = s.bracket->first;
  return s;
}

}  // namespace

SpectralLimit spectral_limit(const RunParams& p, const Eigen::ArrayXd& x,
                             std::optional<double> near) {
  SpectralLimit out;
  const SpectralSearch s = search_limit(p, x, near, out);
  if (!s.bracket) return out;
  Eigen::ArrayXd mode;
  out.radius_above = radius_and_mode(s.map_at(s.bracket->second), &mode);
  ++out.solves;
  set_limiting_mode(out, std::move(mode), x.size());
  return out;
}

std::optional<double> spectral_courant_at(const RunParams& p, const Eigen::ArrayXd& x,
                                          std::optional<double> near) {
  SpectralLimit out;
  search_limit(p, x, near, out);
  return out.courant;
}

namespace {

// What the limit depends on: the scheme, the grid and the layout (the steffen scene's depends on
// A; the bar's is uniform at every A).
std::string spectral_key(const RunParams& p, bool bloch) {
  std::ostringstream k;
  k << to_string(p.method) << '/' << to_string(p.walls) << '/' << to_string(p.bc) << '/'
    << to_string(p.scene) << '/' << to_string(p.transfer) << '/' << to_string(p.update) << '/'
    << (bloch ? 0 : p.cells) << '/' << p.ppc;  // Bloch: the same for every grid
  if (p.transfer == Transfer::xpic) k << "/x" << p.xpic_order;
  if (p.transfer == Transfer::fmpm) k << "/f" << p.fmpm_order;
  k.precision(17);
  if (p.transfer == Transfer::blend) k << "/b" << p.flip_fraction;
  if (p.scene != SceneKind::bar) k << "/A" << p.A;
  if (!scene_info(p.scene).fills_grid) k << "/x" << body_start(p) << "/L" << body_length(p);
  k << "/s" << p.layout.shift << "/j" << p.layout.jitter;
  return k.str();
}

}  // namespace

std::string spectral_analysis_key(const RunParams& p, SpectralAnalysis analysis) {
  const bool bloch = analysis == SpectralAnalysis::bloch;
  return std::string(to_string(analysis)) + '/' + spectral_key(p, bloch);
}

DenseAnalyses dense_analyses(const RunParams& p) {
  DenseAnalyses d;
  const bool policy = p.stepping.policy == TimeStepPolicy::spectral;
  // A uniform layout's limit is Bloch's, for the record and the policy's first step alike.
  if (!bloch_applies(p) && (p.observe.spectral || policy) &&
      spectral_state_size(p) <= kMaxSpectralState)
    d.initial_key = spectral_analysis_key(p, SpectralAnalysis::dense);
  if (policy) d.later = p.A * p.cells + 1;
  return d;
}

std::optional<double> spectral_courant(const RunParams& p, SpectralAnalysis analysis) {
  const bool bloch = analysis == SpectralAnalysis::bloch;
  if (bloch ? !bloch_applies(p) : spectral_state_size(p) > kMaxSpectralState) return std::nullopt;
  static std::mutex mutex;
  static std::map<std::string, std::optional<double>> known;
  const std::string key = spectral_analysis_key(p, analysis);
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (const auto it = known.find(key); it != known.end()) return it->second;
  }
  // Outside the lock: two threads may compute the same, once each.
  const std::optional<double> c =
      bloch ? bloch_courant(p) : spectral_courant_at(p, Simulation(p).particles().x);
  const std::lock_guard<std::mutex> lock(mutex);
  known.emplace(key, c);
  return c;
}

}  // namespace mpmstab
