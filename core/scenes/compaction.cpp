#include "scenes/compaction.hpp"

#include <cmath>
#include <numbers>

namespace mpmstab {

namespace {

// b = -g r(t) at every particle.
class RampedBodyForce final : public BodyForceAtParticles {
 public:
  RampedBodyForce(const CompactionScene& scene, Eigen::Index n) : scene_(&scene), n_(n) {}
  void evaluate(double t, Eigen::ArrayXd& b) const override {
    b.setConstant(n_, -scene_->gravity() * scene_->ramp(t));
  }

 private:
  const CompactionScene* scene_;
  Eigen::Index n_;
};

}  // namespace

CompactionScene::CompactionScene(double youngs_modulus, double amplitude, double length)
    : Scene(youngs_modulus, amplitude, 0.0, length) {}

double CompactionScene::beta(int n) const {
  return (2 * n - 1) * std::numbers::pi / (2 * L);
}

double CompactionScene::static_displacement(double X) const {
  return rho0 * gravity() / E * (0.5 * X * X - L * X);
}

double CompactionScene::modal(int n, double t) const {
  const double w = c * beta(n), tr = ramp_time();
  const double load = -2 * gravity() / (L * beta(n)) / (w * w);  // B_n / omega_n^2
  const double d =
      t <= tr ? -std::sin(w * t) / (w * tr) : (std::sin(w * (t - tr)) - std::sin(w * t)) / (w * tr);
  return load * d;
}

double CompactionScene::modal_rate(int n, double t) const {
  const double w = c * beta(n), tr = ramp_time();
  const double load = -2 * gravity() / (L * beta(n)) / (w * w);
  const double d =
      t <= tr ? -std::cos(w * t) / tr : (std::cos(w * (t - tr)) - std::cos(w * t)) / tr;
  return load * d;
}

double CompactionScene::displacement(double X, double t) const {
  double u = static_displacement(X) * ramp(t);
  for (int n = 1; n <= kModes; ++n)
    u += modal(n, t) * std::sin(beta(n) * X);
  return u;
}

double CompactionScene::velocity(double X, double t) const {
  double v = t <= ramp_time() ? static_displacement(X) / ramp_time() : 0.0;  // as modal_rate
  for (int n = 1; n <= kModes; ++n)
    v += modal_rate(n, t) * std::sin(beta(n) * X);
  return v;
}

double CompactionScene::stress(double X, double t) const {
  double strain = rho0 * gravity() / E * (X - L) * ramp(t);
  for (int n = 1; n <= kModes; ++n)
    strain += modal(n, t) * beta(n) * std::cos(beta(n) * X);
  return E * strain;
}

void CompactionScene::displacements(const Eigen::ArrayXd& X, double t, Eigen::ArrayXd& u) const {
  if (sines_X_.size() != X.size() || !(sines_X_ == X).all()) {
    sines_X_ = X;
    sines_.resize(X.size(), kModes);
    for (int n = 1; n <= kModes; ++n)
      sines_.col(n - 1) = X.unaryExpr([&](double Xp) { return std::sin(beta(n) * Xp); });
  }
  const double r = ramp(t);
  u.resize(X.size());
  for (Eigen::Index p = 0; p < X.size(); ++p)
    u[p] = static_displacement(X[p]) * r;
  for (int n = 1; n <= kModes; ++n)
    u += modal(n, t) * sines_.col(n - 1);
}

std::unique_ptr<BodyForceAtParticles> CompactionScene::body_force_at(
    const Eigen::ArrayXd& X) const {
  return std::make_unique<RampedBodyForce>(*this, X.size());
}

Particles CompactionScene::initial_particles(int cells, int ppc, const Layout& layout) const {
  Particles P = reference_layout(cells, ppc, layout);
  start_undeformed(P);
  P.v.setZero();  // at rest (the truncated modal sum of v(X, 0) is zero only to about 1e-6)
  return P;
}

}  // namespace mpmstab
