#include "scenes/vibration.hpp"

#include <cmath>
#include <numbers>

namespace mpmstab {

VibrationScene::VibrationScene(double youngs_modulus, double amplitude, double length)
    : Scene(youngs_modulus, amplitude, 0.0, length) {}

double VibrationScene::beta() const {
  return std::numbers::pi / (2 * L);
}
double VibrationScene::omega() const {
  return c * beta();
}

double VibrationScene::displacement_profile(double X) const {
  return A * std::sin(beta() * X);
}
double VibrationScene::displacement_factor(double t) const {
  return std::sin(omega() * t);
}
double VibrationScene::displacement(double X, double t) const {
  return displacement_profile(X) * displacement_factor(t);
}
double VibrationScene::velocity(double X, double t) const {
  return A * omega() * std::sin(beta() * X) * std::cos(omega() * t);
}
double VibrationScene::stress(double X, double t) const {
  return E * A * beta() * std::cos(beta() * X) * std::sin(omega() * t);
}

std::unique_ptr<BodyForceAtParticles> VibrationScene::body_force_at(const Eigen::ArrayXd& X) const {
  return zero_body_force(X.size());
}

ExactEnergy VibrationScene::exact_energy(double t) const {
  const double s = std::sin(omega() * t), co = std::cos(omega() * t);
  return {rho0 * A * A * omega() * omega() * L * co * co / 4,
          E * A * A * beta() * beta() * L * s * s / 4, 0.0};
}

Particles VibrationScene::initial_particles(int cells, int ppc, const Layout& layout) const {
  Particles P = reference_layout(cells, ppc, layout);
  start_undeformed(P);
  return P;
}

}  // namespace mpmstab
