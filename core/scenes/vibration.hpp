// Axial vibration of a bar fixed at X = 0 and free at X = L, inside a grid with empty cells
// beyond its free end (Bardenhagen and Kober 2004, section 5; docs/theory.md, "Scenes").
//
// Linear material sigma = E (F - 1), no load. The first mode of the fixed-free bar:
//   u(X, t) = A sin(beta X) sin(omega t),  beta = pi / (2 L),  omega = c beta,
// so u(0, t) = 0 and sigma(L, t) = E u_X(L, t) = E A beta cos(pi / 2) sin(omega t) = 0 (a free
// end), and u_tt = -omega^2 u = c^2 u_XX. The tip moves with amplitude A and period 4 L / c.
// The particles start undeformed (x = X, F = 1, sigma = 0) with v(X, 0) = A omega sin(beta X).
#pragma once

#include <memory>

#include "scenes/scene.hpp"

namespace mpmstab {

class VibrationScene final : public Scene {
 public:
  static constexpr SceneInfo kInfo{.name = "vibration",
                                   .periodic = false,
                                   .fills_grid = false,
                                   .fixed_start = true,
                                   .body_start = 0,
                                   .body_length = 0.5,
                                   .free_surface = true,
                                   .tip_load = true};

  VibrationScene(double youngs_modulus, double amplitude, double length);

  Material material() const override { return Material::linear; }

  double beta() const;   // pi / (2 L)
  double omega() const;  // c beta

  double displacement(double X, double t) const override;
  double velocity(double X, double t) const override;
  double stress(double X, double t) const override;

  double displacement_profile(double X) const override;  // A sin(beta X)
  double displacement_factor(double t) const override;   // sin(omega t)

  std::unique_ptr<BodyForceAtParticles> body_force_at(const Eigen::ArrayXd& X) const override;
  bool has_body_force() const override { return false; }

  // K = rho0 A^2 omega^2 L cos^2(omega t) / 4, U = E A^2 beta^2 L sin^2(omega t) / 4 (equal
  // amplitudes, since omega = c beta), no work.
  ExactEnergy exact_energy(double t) const override;
  double period() const override { return 4 * L / c; }

  Particles initial_particles(int cells, int ppc, const Layout& layout = {}) const override;
};

}  // namespace mpmstab
