#include "scene.hpp"

#include <cmath>

namespace mpmstab {

namespace {
constexpr double kPi = std::numbers::pi;
}

BarScene::BarScene(double youngs_modulus, double amplitude)
    : E(youngs_modulus), A(amplitude), c(std::sqrt(youngs_modulus / rho0)) {}

double BarScene::displacement_profile(double X) const {
  return A * std::sin(2 * kPi * X);
}
double BarScene::displacement_factor(double t) const {
  return std::sin(c * kPi * t);
}
double BarScene::body_force_profile(double X) const {
  return 3.0 * (c * kPi) * (c * kPi) * A * std::sin(2 * kPi * X);
}
double BarScene::body_force_factor(double t) const {
  return std::sin(c * kPi * t);
}

double BarScene::displacement(double X, double t) const {
  return displacement_profile(X) * displacement_factor(t);
}
double BarScene::velocity(double X, double t) const {
  return A * c * kPi * std::sin(2 * kPi * X) * std::cos(c * kPi * t);
}
double BarScene::stress(double X, double t) const {
  return E * A * 2 * kPi * std::cos(2 * kPi * X) * std::sin(c * kPi * t);
}
double BarScene::body_force(double X, double t) const {
  return body_force_profile(X) * body_force_factor(t);
}

Particles BarScene::initial_particles(int cells, int ppc) const {
  Particles P;
  const Eigen::Index n = Eigen::Index(cells) * ppc;
  P.resize(n);
  const double h = 1.0 / cells;
  for (int i = 0; i < cells; ++i) {
    for (int k = 0; k < ppc; ++k) {
      const Eigen::Index p = Eigen::Index(i) * ppc + k;
      const double X = (i + (k + 0.5) / ppc) * h;
      P.X[p] = X;
      P.x[p] = X;
      P.v[p] = velocity(X, 0.0);
      P.F[p] = 1.0;
      P.sigma[p] = 0.0;
      P.mass[p] = rho0 * h / ppc;
      P.volume0[p] = h / ppc;
    }
  }
  return P;
}

}  // namespace mpmstab
