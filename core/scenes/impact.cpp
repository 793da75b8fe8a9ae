#include "scenes/impact.hpp"

#include <cmath>

namespace mpmstab {

ImpactScene::ImpactScene(double youngs_modulus, double amplitude, double start, double length)
    : Scene(youngs_modulus, amplitude, start, length) {}

namespace {
// s - x0 reduced to [0, period).
double reduce(double s, double period) {
  const double r = std::fmod(s, period);
  return r < 0 ? r + period : r;
}
}  // namespace

// Over one period 2 L from x0: +v on [0, L / 2), -v on [L / 2, 3 L / 2), +v on [3 L / 2, 2 L).
double ImpactScene::extended_velocity(double s) const {
  const double r = reduce(s - x0, 2 * L);
  return r < L / 2 || r >= 1.5 * L ? speed() : -speed();
}

double ImpactScene::Psi(double s) const {
  const double r = reduce(s - x0, 2 * L), v = speed();
  if (r < L / 2) return v * r;
  if (r < 1.5 * L) return v * L / 2 - v * (r - L / 2);
  return -v * L / 2 + v * (r - 1.5 * L);
}

double ImpactScene::displacement(double X, double t) const {
  if (t > separation_time())
    return (X < interface() ? -speed() : speed()) * (t - separation_time());
  return (Psi(X + c * t) - Psi(X - c * t)) / (2 * c);
}
double ImpactScene::velocity(double X, double t) const {
  if (t > separation_time()) return X < interface() ? -speed() : speed();
  return 0.5 * (extended_velocity(X + c * t) + extended_velocity(X - c * t));
}
double ImpactScene::stress(double X, double t) const {
  if (t > separation_time()) return 0.0;
  return E * (extended_velocity(X + c * t) - extended_velocity(X - c * t)) / (2 * c);
}

std::unique_ptr<BodyForceAtParticles> ImpactScene::body_force_at(const Eigen::ArrayXd& X) const {
  return zero_body_force(X.size());
}

Particles ImpactScene::initial_particles(int cells, int ppc, const Layout& layout) const {
  Particles P = reference_layout(cells, ppc, layout);
  start_undeformed(P);
  for (Eigen::Index p = 0; p < P.size(); ++p)
    P.v[p] = P.X[p] < interface() ? speed() : -speed();  // v0, without the jump's average
  return P;
}

}  // namespace mpmstab
