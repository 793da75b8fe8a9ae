// One free standing wave of the periodic linear bar.
#pragma once

#include <limits>
#include <memory>

#include <Eigen/Core>

#include "scenes/scene.hpp"

namespace mpmstab {

// mode: one free standing wave of wavelength 1 on the periodic linear bar (the dispersion
// study's scene, core/analysis/dispersion.hpp). Linear material sigma = E (F - 1), no body force:
//   u(X, t) = A sin(2 pi X) cos(2 pi c t),  F(X, t) = 1 + 2 pi A cos(2 pi X) cos(2 pi c t).
//   u_tt = -(2 pi c)^2 u = E u_XX / rho0 with rho0 c^2 = E: the balance of momentum holds with
//   b = 0, so the scheme's own wave is what moves. Its period is 1 / c. Dirichlet walls at X = 0
//   and X = 1 would hold u = 0 there, which u does, but the scene is the free wave of a periodic
//   grid (no wall modes, the Bloch symbol's setting): it is posed with periodic boundaries only.
//   The particles start at the deformed positions x_p = X_p + u(X_p, 0) at rest, with
//   F_p = F(X_p, 0) and sigma_p = E (F_p - 1); at A > 0 this layout is not uniform.
class ModeScene final : public Scene {
 public:
  ModeScene(double youngs_modulus, double amplitude);

  Material material() const override { return Material::linear; }
  static constexpr SceneInfo kInfo{.name = "mode", .dirichlet = false};  // periodic only

  double displacement(double X, double t) const override;
  double velocity(double X, double t) const override;
  double deformation_gradient(double X, double t) const;  // F = 1 + u_X
  double stress(double X, double t) const override;       // E (F - 1)
  double body_force(double X, double t) const override;   // 0

  double displacement_profile(double X) const override;  // A sin(2 pi X)
  double displacement_factor(double t) const override;   // cos(2 pi c t)

  // A body force that is zero: never evaluated by the solver (has_body_force).
  std::unique_ptr<BodyForceAtParticles> body_force_at(const Eigen::ArrayXd& X) const override;
  bool has_body_force() const override { return false; }

  // With v = -2 pi c A sin(2 pi X) sin(2 pi c t) and u_X = 2 pi A cos(2 pi X) cos(2 pi c t):
  // K = (1/2) int_0^1 v^2 dX = pi^2 c^2 A^2 sin^2(2 pi c t) and
  // U = (E/2) int_0^1 u_X^2 dX = pi^2 E A^2 cos^2(2 pi c t) (rho0 = 1, so E = c^2 and K + U is
  // pi^2 E A^2 at every t); no body force, no work.
  ExactEnergy exact_energy(double t) const override;
  double period() const override { return 1.0 / c; }

  // x = X + u(X, 0), v = 0, F = F(X, 0), sigma = E (F - 1).
  Particles initial_particles(int cells, int ppc, const Layout& layout = {}) const override;
};

}  // namespace mpmstab
