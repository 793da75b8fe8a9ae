#include "scenes/mode.hpp"

#include <cmath>
#include <numbers>
#include <utility>

namespace mpmstab {

namespace {

constexpr double kPi = std::numbers::pi;

}  // namespace

// mode

namespace {}  // namespace

ModeScene::ModeScene(double youngs_modulus, double amplitude) : Scene(youngs_modulus, amplitude) {}

double ModeScene::displacement_profile(double X) const {
  return A * std::sin(2 * kPi * X);
}
double ModeScene::displacement_factor(double t) const {
  return std::cos(2 * kPi * c * t);
}

double ModeScene::displacement(double X, double t) const {
  return displacement_profile(X) * displacement_factor(t);
}
double ModeScene::velocity(double X, double t) const {
  return -2 * kPi * c * A * std::sin(2 * kPi * X) * std::sin(2 * kPi * c * t);
}
double ModeScene::deformation_gradient(double X, double t) const {
  return 1.0 + 2 * kPi * A * std::cos(2 * kPi * X) * std::cos(2 * kPi * c * t);
}
double ModeScene::stress(double X, double t) const {
  return E * (deformation_gradient(X, t) - 1.0);
}
double ModeScene::body_force(double, double) const {
  return 0.0;
}

std::unique_ptr<BodyForceAtParticles> ModeScene::body_force_at(const Eigen::ArrayXd& X) const {
  return zero_body_force(X.size());
}

ExactEnergy ModeScene::exact_energy(double t) const {
  const double s = std::sin(2 * kPi * c * t), co = std::cos(2 * kPi * c * t);
  ExactEnergy e;
  e.kinetic = rho0 * kPi * kPi * c * c * A * A * s * s;
  e.strain = kPi * kPi * E * A * A * co * co;
  e.work = 0;
  return e;
}

Particles ModeScene::initial_particles(int cells, int ppc, const Layout& layout) const {
  Particles P = reference_layout(cells, ppc, layout);
  start_deformed_at_rest(*this, P);
  return P;
}

}  // namespace mpmstab
