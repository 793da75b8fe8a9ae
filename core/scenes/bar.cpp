#include "scenes/bar.hpp"

#include <cmath>
#include <numbers>
#include <utility>

#include "base/simd.hpp"

namespace mpmstab {

namespace {

constexpr double kPi = std::numbers::pi;

// out[p] = a[p] * f, compiled for each instruction set (simd.hpp): a product per element, the
// same bits in any of them. Every step of the bar runs it; in the build's baseline (SSE) it took
// about 3% of a run.
MPMSTAB_SIMD_CLONES void scale(const double* __restrict a, double f, double* __restrict out,
                               Eigen::Index n) {
  for (Eigen::Index p = 0; p < n; ++p)
    out[p] = a[p] * f;
}

// b(X_p, t) = profile[p] * sin(c pi t): the bar's separable body force.
class BarBodyForce final : public BodyForceAtParticles {
 public:
  // profile: body_force_profile(X_p), from the scene's sines of X.
  BarBodyForce(const BarScene& scene, Eigen::ArrayXd profile)
      : scene_(&scene), profile_(std::move(profile)) {}
  BarBodyForce(const BarBodyForce&) = delete;
  BarBodyForce& operator=(const BarBodyForce&) = delete;
  void evaluate(double t, Eigen::ArrayXd& b) const override {
    b.resize(profile_.size());
    scale(profile_.data(), scene_->body_force_factor(t), b.data(), profile_.size());
  }

 private:
  const BarScene* scene_;   // its time factor (time_sine)
  Eigen::ArrayXd profile_;  // 3 (c pi)^2 A sin(2 pi X_p)
};

// b(X_p, t) = (c pi)^2 u (1 + 2 / F^2) with u = A sin(2 pi X_p) g and
// F = 1 + 2 pi A cos(2 pi X_p) g, g = cos(c pi t).

}  // namespace

// bar

BarScene::BarScene(double youngs_modulus, double amplitude) : Scene(youngs_modulus, amplitude) {}

double BarScene::displacement_profile(double X) const {
  return A * std::sin(2 * kPi * X);
}
const Eigen::ArrayXd& BarScene::space_sines(const Eigen::ArrayXd& X) const {
  if (sines_X_.size() != X.size() || !(sines_X_ == X).all()) {
    sines_X_ = X;
    sines_ = X.unaryExpr([](double Xp) { return std::sin(2 * kPi * Xp); });
  }
  return sines_;
}
Eigen::ArrayXd BarScene::displacement_profiles(const Eigen::ArrayXd& X) const {
  return A * space_sines(X);  // displacement_profile's A * sin(2 pi X)
}
double BarScene::time_sine(double t) const {
  if (t != sine_t_) {
    sine_t_ = t;
    sine_ = std::sin(c * kPi * t);
  }
  return sine_;
}
double BarScene::displacement_factor(double t) const {
  return time_sine(t);
}
double BarScene::body_force_profile(double X) const {
  return 3.0 * (c * kPi) * (c * kPi) * A * std::sin(2 * kPi * X);
}
double BarScene::body_force_factor(double t) const {
  return time_sine(t);
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

std::unique_ptr<BodyForceAtParticles> BarScene::body_force_at(const Eigen::ArrayXd& X) const {
  // body_force_profile's 3 (c pi)^2 A sin(2 pi X), its products in its order.
  const double factor = 3.0 * (c * kPi) * (c * kPi) * A;
  return std::make_unique<BarBodyForce>(*this, factor * space_sines(X));
}

Particles BarScene::initial_particles(int cells, int ppc, const Layout& layout) const {
  Particles P = reference_layout(cells, ppc, layout);
  // velocity(X_p, 0), its products in its order, from the scene's sines of X.
  const Eigen::ArrayXd& sines = space_sines(P.X);
  const double amplitude = A * c * kPi, time_factor = std::cos(c * kPi * 0.0);
  for (Eigen::Index p = 0; p < P.size(); ++p) {
    P.x[p] = P.X[p];
    P.v[p] = amplitude * sines[p] * time_factor;
    P.F[p] = 1.0;
    P.sigma[p] = 0.0;
  }
  return P;
}

ExactEnergy BarScene::exact_energy(double t) const {
  const double w = c * kPi, s = std::sin(w * t), co = std::cos(w * t);
  return {rho0 * A * A * w * w * co * co / 4, E * kPi * kPi * A * A * s * s,
          0.75 * rho0 * A * A * w * w * s * s};
}

}  // namespace mpmstab
