#include "scenes/impulsive.hpp"

#include <algorithm>
#include <cmath>

namespace mpmstab {

namespace {

// A constant force on one particle: b = f there, 0 elsewhere.
class ParticleForce final : public BodyForceAtParticles {
 public:
  ParticleForce(Eigen::Index n, Eigen::Index particle, double b) : n_(n), p_(particle), b_(b) {}
  void evaluate(double, Eigen::ArrayXd& b) const override {
    if (b.size() == n_ && b[p_] == b_) return;  // set at the first step, constant since
    b.setZero(n_);
    b[p_] = b_;
  }

 private:
  Eigen::Index n_, p_;
  double b_;
};

}  // namespace

ImpulsiveScene::ImpulsiveScene(double youngs_modulus, double amplitude, double length)
    : Scene(youngs_modulus, amplitude, 0.0, length) {}

// On the half-open intervals [L + 4 k L, 3 L + 4 k L): the traction acts at the free end from
// t = 0 on, so that sigma(L, t) = sigma0 at every t >= 0.
double ImpulsiveScene::chi(double s) const {
  if (s < L) return 0.0;
  return std::fmod(s - L, 4 * L) < 2 * L ? 1.0 : 0.0;
}

double ImpulsiveScene::Phi(double s) const {
  if (s <= L) return 0.0;
  const double r = s - L;
  const double periods = std::floor(r / (4 * L));
  return 2 * L * periods + std::min(r - 4 * L * periods, 2 * L);
}

double ImpulsiveScene::displacement(double X, double t) const {
  return traction() / E * (Phi(c * t + X) - Phi(c * t - X));
}
double ImpulsiveScene::velocity(double X, double t) const {
  return c * traction() / E * (chi(c * t + X) - chi(c * t - X));
}
double ImpulsiveScene::stress(double X, double t) const {
  return traction() * (chi(c * t + X) + chi(c * t - X));
}

std::unique_ptr<BodyForceAtParticles> ImpulsiveScene::body_force_at(const Eigen::ArrayXd& X) const {
  const Eigen::Index last = X.size() - 1;
  // The mass of the last particle, rho0 h / m, is its reference volume times rho0; with the
  // layout's spacing h / m the particles are uniform, so any particle's volume will do. The
  // bar's length over its particle count is that volume.
  const double mass = rho0 * L / double(X.size());
  return std::make_unique<ParticleForce>(X.size(), last, traction() / mass);
}

Particles ImpulsiveScene::initial_particles(int cells, int ppc, const Layout& layout) const {
  Particles P = reference_layout(cells, ppc, layout);
  start_undeformed(P);  // v(X, 0) = 0
  return P;
}

}  // namespace mpmstab
