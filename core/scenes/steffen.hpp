// The manufactured solution of Steffen et al. (2008).
//
// steffen (Steffen, Wallstedt, Guilkey, Kirby and Berzins 2008): neo-Hookean material
// sigma = (E / 2) (F - 1 / F) (material.hpp),
//   u(X, t) = A sin(2 pi X) cos(c pi t),  F(X, t) = 1 + 2 pi A cos(2 pi X) cos(c pi t).
//   Body force. dP/dX = P'(F) F_X with P'(F) = (E / 2) (1 + 1 / F^2) and F_X = u_XX = -(2 pi)^2 u;
//   u_tt = -(c pi)^2 u. Hence, with rho0 c^2 = E,
//     rho0 b = rho0 u_tt - dP/dX = -E pi^2 u + (E / 2) (1 + 1 / F^2) 4 pi^2 u
//            = E pi^2 u (1 + 2 / F^2),
//   that is b(X, t) = (c pi)^2 u(X, t) (1 + 2 / F(X, t)^2) per unit mass. For the linear law
//   P' = E and the same steps give b = 3 (c pi)^2 u, the bar's form. The particles start at the
//   deformed positions x_p = X_p + u(X_p, 0) at rest (v(X, 0) = 0), with F_p = F(X_p, 0), the
//   stress of the material at F_p, and the reference volume V_p^0 = h / m (the current volume is
//   F_p V_p^0).
//
// In both scenes m particles per cell sit at the reference positions X_p = (i + (k + 1/2) / m) h
// with mass rho0 h / m.
#pragma once

#include <limits>
#include <memory>

#include <Eigen/Core>

#include "scenes/scene.hpp"

namespace mpmstab {

class SteffenScene final : public Scene {
 public:
  SteffenScene(double youngs_modulus, double amplitude);

  Material material() const override { return Material::neo_hookean; }
  static constexpr SceneInfo kInfo{.name = "steffen"};  // fills [0, 1]; Dirichlet and periodic

  double displacement(double X, double t) const override;
  double velocity(double X, double t) const override;
  double deformation_gradient(double X, double t) const;  // F = 1 + u_X
  double stress(double X, double t) const override;       // sigma(F(X, t))
  double body_force(double X, double t) const override;

  double displacement_profile(double X) const override;  // A sin(2 pi X)
  double displacement_factor(double t) const override;   // cos(c pi t)

  std::unique_ptr<BodyForceAtParticles> body_force_at(const Eigen::ArrayXd& X) const override;

  // With w = c pi and a = 2 pi A cos(w t): K = A^2 w^2 sin^2(w t) / 4 and, from
  // int_0^1 (F^2 - 1) dX = a^2 / 2 and int_0^1 ln F dX = ln((1 + sqrt(1 - a^2)) / 2),
  // U = E a^2 / 8 - (E / 2) ln((1 + sqrt(1 - a^2)) / 2); the work is K + U - U(0), the balance
  // of the exact solution (not finite once 2 pi A >= 1, where F reaches 0).
  ExactEnergy exact_energy(double t) const override;
  double period() const override { return 2.0 / c; }

  // x = X + u(X, 0), v = 0, F = F(X, 0), sigma = sigma(F).
  Particles initial_particles(int cells, int ppc, const Layout& layout = {}) const override;
};

}  // namespace mpmstab
