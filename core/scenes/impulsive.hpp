// The impulsively loaded bar: a bar fixed at X = 0, free at X = L, at rest and undeformed until
// a traction sigma0 is applied at its free end at t = 0 and held (Uintah's 1D MPM code,
// AMRMPM.m, problem "impulsiveBar"; docs/theory.md, "Scenes").
//
// Linear material, rho0 = 1. sigma0 = E A / (2 L), so that the largest tip displacement,
// 2 sigma0 L / E, is A. d'Alembert with the fixed end: u(X, t) = phi(c t + X) - phi(c t - X).
// At rest until t = 0 gives phi' = 0 on [-L, L]; the traction, E u_X(L, t) = sigma0, gives
// phi'(s) = sigma0 / E - phi'(s - 2 L) for s > L. Hence phi' = (sigma0 / E) chi with chi the
// indicator of the union over k >= 0 of (L + 4 k L, 3 L + 4 k L), and
//   u(X, t) = (sigma0 / E) (Phi(c t + X) - Phi(c t - X)),  Phi(s) = int_{-L}^{s} chi,
//   v(X, t) = c (sigma0 / E) (chi(c t + X) - chi(c t - X)),
//   sigma(X, t) = sigma0 (chi(c t + X) + chi(c t - X)):
// the tip moves at sigma0 / (rho0 c) to A at t = 2 L / c and back to 0 at 4 L / c, piecewise
// linear with period 4 L / c; the stress takes the values 0, sigma0 and 2 sigma0.
// The traction enters as a force sigma0 (per unit cross-section) on the last particle of the
// bar, as the Uintah code applies its tip force: b = sigma0 / m_p there, 0 elsewhere. The force
// acts at that particle's centre, h / (2 m) inside the end: a discretization error of O(h).
#pragma once

#include <memory>

#include "scenes/scene.hpp"

namespace mpmstab {

class ImpulsiveScene final : public Scene {
 public:
  static constexpr SceneInfo kInfo{.name = "impulsive",
                                   .periodic = false,
                                   .fills_grid = false,
                                   .fixed_start = true,
                                   .body_start = 0,
                                   .body_length = 0.5,
                                   .free_surface = true,
                                   .tip_load = true};

  ImpulsiveScene(double youngs_modulus, double amplitude, double length);

  Material material() const override { return Material::linear; }
  double traction() const { return E * A / (2 * L); }  // sigma0

  double displacement(double X, double t) const override;
  double velocity(double X, double t) const override;
  double stress(double X, double t) const override;
  bool separable() const override { return false; }

  // sigma0 / m_p on the last particle (the largest X_p).
  std::unique_ptr<BodyForceAtParticles> body_force_at(const Eigen::ArrayXd& X) const override;

  double period() const override { return 4 * L / c; }

  // At rest, undeformed.
  Particles initial_particles(int cells, int ppc, const Layout& layout = {}) const override;

 private:
  double chi(double s) const;  // the indicator above
  double Phi(double s) const;  // its integral from -L
};

}  // namespace mpmstab
