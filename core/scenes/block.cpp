#include "scenes/block.hpp"

namespace mpmstab {

BlockScene::BlockScene(double youngs_modulus, double amplitude, double start, double length)
    : Scene(youngs_modulus, amplitude, start, length) {}

double BlockScene::displacement_profile(double) const {
  return A;
}
double BlockScene::displacement_factor(double t) const {
  return c * t;
}
double BlockScene::displacement(double X, double t) const {
  return displacement_profile(X) * displacement_factor(t);
}
double BlockScene::velocity(double, double) const {
  return speed();
}
double BlockScene::stress(double, double) const {
  return 0.0;
}

std::unique_ptr<BodyForceAtParticles> BlockScene::body_force_at(const Eigen::ArrayXd& X) const {
  return zero_body_force(X.size());
}

ExactEnergy BlockScene::exact_energy(double) const {
  return {0.5 * rho0 * L * speed() * speed(), 0.0, 0.0};
}

Particles BlockScene::initial_particles(int cells, int ppc, const Layout& layout) const {
  Particles P = reference_layout(cells, ppc, layout);
  start_undeformed(P);
  return P;
}

}  // namespace mpmstab
