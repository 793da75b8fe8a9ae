#include "scenes/steffen.hpp"

#include <cmath>
#include <numbers>
#include <utility>

namespace mpmstab {

namespace {

constexpr double kPi = std::numbers::pi;

class SteffenBodyForce final : public BodyForceAtParticles {
 public:
  SteffenBodyForce(const SteffenScene& scene, const Eigen::ArrayXd& X)
      : A_(scene.A),
        c_pi_(scene.c * kPi),
        sin_(X.unaryExpr([](double Xp) { return std::sin(2 * kPi * Xp); })),
        cos_(X.unaryExpr([](double Xp) { return std::cos(2 * kPi * Xp); })) {}
  void evaluate(double t, Eigen::ArrayXd& b) const override {
    const double g = std::cos(c_pi_ * t);
    const auto u = (A_ * g) * sin_;
    const auto F = 1.0 + (2 * kPi * A_ * g) * cos_;
    b = (c_pi_ * c_pi_) * u * (1.0 + 2.0 / F.square());
  }

 private:
  double A_;
  double c_pi_;
  Eigen::ArrayXd sin_;  // sin(2 pi X_p)
  Eigen::ArrayXd cos_;  // cos(2 pi X_p)
};

// int_0^1 W(F(X, t)) dX of the steffen scene's neo-Hookean law with F = 1 + a cos(2 pi X).
double steffen_strain_energy(double E, double a) {
  return E * a * a / 8 - 0.5 * E * std::log(0.5 * (1 + std::sqrt(1 - a * a)));
}
}  // namespace

ExactEnergy SteffenScene::exact_energy(double t) const {
  const double w = c * kPi, s = std::sin(w * t);
  const double kinetic = rho0 * A * A * w * w * s * s / 4;
  const double strain = steffen_strain_energy(E, 2 * kPi * A * std::cos(w * t));
  return {kinetic, strain, kinetic + strain - steffen_strain_energy(E, 2 * kPi * A)};
}

// steffen

SteffenScene::SteffenScene(double youngs_modulus, double amplitude)
    : Scene(youngs_modulus, amplitude) {}

double SteffenScene::displacement_profile(double X) const {
  return A * std::sin(2 * kPi * X);
}
double SteffenScene::displacement_factor(double t) const {
  return std::cos(c * kPi * t);
}

double SteffenScene::displacement(double X, double t) const {
  return displacement_profile(X) * displacement_factor(t);
}
double SteffenScene::velocity(double X, double t) const {
  return -A * c * kPi * std::sin(2 * kPi * X) * std::sin(c * kPi * t);
}
double SteffenScene::deformation_gradient(double X, double t) const {
  return 1.0 + 2 * kPi * A * std::cos(2 * kPi * X) * std::cos(c * kPi * t);
}
double SteffenScene::stress(double X, double t) const {
  return law().stress(deformation_gradient(X, t));
}
double SteffenScene::body_force(double X, double t) const {
  const double F = deformation_gradient(X, t);
  return (c * kPi) * (c * kPi) * displacement(X, t) * (1.0 + 2.0 / (F * F));
}

std::unique_ptr<BodyForceAtParticles> SteffenScene::body_force_at(const Eigen::ArrayXd& X) const {
  return std::make_unique<SteffenBodyForce>(*this, X);
}

Particles SteffenScene::initial_particles(int cells, int ppc, const Layout& layout) const {
  Particles P = reference_layout(cells, ppc, layout);
  start_deformed_at_rest(*this, P);
  return P;
}

}  // namespace mpmstab
