#include "scenes/scene.hpp"

#include <cmath>
#include <stdexcept>

namespace mpmstab {

namespace {

// b = 0 at every particle: zeros once, then nothing.
class ZeroBodyForce final : public BodyForceAtParticles {
 public:
  explicit ZeroBodyForce(Eigen::Index n) : n_(n) {}
  void evaluate(double, Eigen::ArrayXd& b) const override {
    if (b.size() != n_ || (b != 0.0).any()) b.setZero(n_);
  }

 private:
  Eigen::Index n_;
};

}  // namespace

std::unique_ptr<BodyForceAtParticles> zero_body_force(Eigen::Index n) {
  return std::make_unique<ZeroBodyForce>(n);
}

double layout_jitter_unit(std::uint64_t index) {
  // SplitMix64 (Steele, Lea and Flood 2014) of the index: 53 bits to [0, 1), less 1/2.
  std::uint64_t z = index + 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return double(z >> 11) * 0x1p-53 - 0.5;
}

std::pair<int, int> body_cells(double start, double length, int cells) {
  return {int(std::lround(start * cells)), int(std::lround((start + length) * cells))};
}

Scene::Scene(double youngs_modulus, double amplitude, double start, double length)
    : E(youngs_modulus), A(amplitude), c(std::sqrt(youngs_modulus / rho0)), x0(start), L(length) {}

double Scene::displacement_profile(double) const {
  throw std::logic_error("displacement_profile of a scene that is not separable");
}
double Scene::displacement_factor(double) const {
  throw std::logic_error("displacement_factor of a scene that is not separable");
}

void Scene::displacements(const Eigen::ArrayXd& X, double t, Eigen::ArrayXd& u) const {
  u.resize(X.size());
  for (Eigen::Index p = 0; p < X.size(); ++p)
    u[p] = displacement(X[p], t);
}

ExactEnergy Scene::exact_energy(double t) const {
  const MaterialLaw material_law = law();
  auto energies = [&](double time) {
    double kinetic = 0, strain = 0;
    const double dX = L / kExactEnergyPoints;
    for (int k = 0; k < kExactEnergyPoints; ++k) {
      const double X = x0 + (k + 0.5) * dX;
      const double v = velocity(X, time);
      kinetic += 0.5 * rho0 * v * v * dX;
      // F from the stress of the linear law, sigma = E (F - 1) (the scenes that use this
      // quadrature are linear).
      strain += material_law.energy(1.0 + stress(X, time) / E) * dX;
    }
    return std::pair{kinetic, strain};
  };
  const auto [k, u] = energies(t);
  if (!initial_energy_) {
    const auto [k0, u0] = energies(0.0);
    initial_energy_ = k0 + u0;
  }
  return {k, u, k + u - *initial_energy_};
}

Particles Scene::reference_layout(int cells, int ppc, const Layout& layout) const {
  Particles P;
  const auto [first, last] = body_cells(x0, L, cells);
  const Eigen::Index n = Eigen::Index(last - first) * ppc;
  P.resize(n);
  const double h = 1.0 / cells;
  for (int i = first; i < last; ++i) {
    for (int k = 0; k < ppc; ++k) {
      const Eigen::Index p = Eigen::Index(i - first) * ppc + k;
      const double offset =
          layout.jitter == 0 ? 0.0 : layout.jitter * layout_jitter_unit(std::uint64_t(p));
      P.X[p] = (i + (k + 0.5 + layout.shift + offset) / ppc) * h;
      P.mass[p] = rho0 * h / ppc;
      P.volume0[p] = h / ppc;
    }
  }
  return P;
}

void Scene::start_undeformed(Particles& P) const {
  for (Eigen::Index p = 0; p < P.size(); ++p) {
    P.x[p] = P.X[p];
    P.v[p] = velocity(P.X[p], 0.0);
    P.F[p] = 1.0;
    P.sigma[p] = 0.0;
  }
}

ExactDisplacement::ExactDisplacement(const Scene& scene, const Eigen::ArrayXd& X) : scene_(&scene) {
  if (scene.separable()) u_ = scene.displacement_profiles(X);
}

ExactDisplacement::Terms ExactDisplacement::at(const Eigen::ArrayXd& X, double t) const {
  if (scene_->separable()) return {u_.data(), scene_->displacement_factor(t)};
  scene_->displacements(X, t, u_);
  return {u_.data(), 1.0};
}

}  // namespace mpmstab
