#include "scene.hpp"

#include <cmath>
#include <numbers>
#include <utility>

#include "simd.hpp"

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

}  // namespace

double layout_jitter_unit(std::uint64_t index) {
  // SplitMix64 (Steele, Lea and Flood 2014) of the index: 53 bits to [0, 1), less 1/2.
  std::uint64_t z = index + 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return double(z >> 11) * 0x1p-53 - 0.5;
}

Scene::Scene(double youngs_modulus, double amplitude)
    : E(youngs_modulus), A(amplitude), c(std::sqrt(youngs_modulus / rho0)) {}

Particles Scene::reference_layout(int cells, int ppc, const Layout& layout) const {
  Particles P;
  const Eigen::Index n = Eigen::Index(cells) * ppc;
  P.resize(n);
  const double h = 1.0 / cells;
  for (int i = 0; i < cells; ++i) {
    for (int k = 0; k < ppc; ++k) {
      const Eigen::Index p = Eigen::Index(i) * ppc + k;
      const double offset =
          layout.jitter == 0 ? 0.0 : layout.jitter * layout_jitter_unit(std::uint64_t(p));
      P.X[p] = (i + (k + 0.5 + layout.shift + offset) / ppc) * h;
      P.mass[p] = rho0 * h / ppc;
      P.volume0[p] = h / ppc;
    }
  }
  return P;
}

ExactEnergy BarScene::exact_energy(double t) const {
  const double w = c * kPi, s = std::sin(w * t), co = std::cos(w * t);
  return {rho0 * A * A * w * w * co * co / 4, E * kPi * kPi * A * A * s * s,
          0.75 * rho0 * A * A * w * w * s * s};
}

namespace {
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

std::unique_ptr<Scene> make_scene(const RunParams& p) {
  if (p.scene == SceneKind::steffen) return std::make_unique<SteffenScene>(p.E, p.A);
  if (p.scene == SceneKind::mode) return std::make_unique<ModeScene>(p.E, p.A);
  return std::make_unique<BarScene>(p.E, p.A);
}

// ---------------------------------------------------------------------------------------------
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

// ---------------------------------------------------------------------------------------------
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

namespace {
// The state of the steffen and mode scenes at t = 0: at rest at the deformed positions,
// x = X + u(X, 0), v = 0, F = F(X, 0), sigma = sigma(F) of the scene's law.
template <class S>
void start_deformed_at_rest(const S& scene, Particles& P) {
  const MaterialLaw material_law = scene.law();
  for (Eigen::Index p = 0; p < P.size(); ++p) {
    const double X = P.X[p];
    P.x[p] = X + scene.displacement(X, 0.0);
    P.v[p] = 0.0;  // v(X, 0) = 0
    P.F[p] = scene.deformation_gradient(X, 0.0);
    P.sigma[p] = material_law.stress(P.F[p]);
  }
}
}  // namespace

Particles SteffenScene::initial_particles(int cells, int ppc, const Layout& layout) const {
  Particles P = reference_layout(cells, ppc, layout);
  start_deformed_at_rest(*this, P);
  return P;
}

// ---------------------------------------------------------------------------------------------
// mode

namespace {

// b = 0 at every particle: zeros once, then nothing (the solver does not call it at all when
// the scene has no body force).
class ZeroBodyForce final : public BodyForceAtParticles {
 public:
  void evaluate(double, Eigen::ArrayXd& b) const override {
    if (b.size() != n_ || (b != 0.0).any()) b.setZero(n_);
  }
  explicit ZeroBodyForce(Eigen::Index n) : n_(n) {}

 private:
  Eigen::Index n_;
};

}  // namespace

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
  return std::make_unique<ZeroBodyForce>(X.size());
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
