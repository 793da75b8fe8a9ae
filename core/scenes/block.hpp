// Rigid translation of a block through the grid: the purest test of the noise of particles
// crossing cells (docs/theory.md, "Scenes"). The block [x0, x0 + L] moves at v0 = A c with
// nothing acting on it: the exact motion has no deformation and no stress at any time,
//   u(X, t) = v0 t,  v = v0,  sigma = 0,
// and the block travels A per time 1 / c (the grid's length over c). Linear material, no load.
// Posed on a periodic grid (the block comes round again) or between Dirichlet walls, where
// validate() refuses a T at which the block would reach the wall X = 1.
#pragma once

#include <memory>

#include "scenes/scene.hpp"

namespace mpmstab {

class BlockScene final : public Scene {
 public:
  static constexpr SceneInfo kInfo{.name = "block",
                                   .fills_grid = false,
                                   .body_start = 0.375,
                                   .body_length = 0.25,
                                   .free_surface = true};

  BlockScene(double youngs_modulus, double amplitude, double start, double length);

  Material material() const override { return Material::linear; }
  double speed() const { return A * c; }  // v0

  double displacement(double X, double t) const override;
  double velocity(double X, double t) const override;
  double stress(double X, double t) const override;  // 0

  double displacement_profile(double X) const override;  // A
  double displacement_factor(double t) const override;   // c t

  std::unique_ptr<BodyForceAtParticles> body_force_at(const Eigen::ArrayXd& X) const override;
  bool has_body_force() const override { return false; }

  // K = rho0 L v0^2 / 2 at every t; no strain energy, no work.
  ExactEnergy exact_energy(double t) const override;
  double period() const override { return 1 / c; }

  // Undeformed, every particle at v0.
  Particles initial_particles(int cells, int ppc, const Layout& layout = {}) const override;
};

}  // namespace mpmstab
