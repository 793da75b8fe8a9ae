// Quasi-static compaction of a column under a ramped body force (Uintah's 1D MPM code,
// AMRMPM.m, problem "compaction"; docs/theory.md, "Scenes"). The column [0, L] is fixed at
// X = 0 and free at X = L; a body force b(t) = -g r(t) pulls it towards its base, ramped by
// r(t) = min(t / t_r, 1) over t_r = kRampPasses L / c.
//
// Linear material, rho0 = 1, g = 2 E A / (rho0 L^2), so that the static compaction of the top is
// A. The static solution of E u_XX = rho0 g, u(0) = 0, u_X(L) = 0 is
//   u_s(X) = (rho0 g / E) (X^2 / 2 - L X),   u_s(L) = -A.
// The exact motion is u_s(X) r(t) plus the free modes the ramp excites: with beta_n =
// (2 n - 1) pi / (2 L), omega_n = c beta_n and the modal load B_n = -2 g / (L beta_n) (the
// projection of -g on sin(beta_n X)), each mode obeys q'' + omega_n^2 q = B_n r(t), so that
//   u(X, t) = u_s(X) r(t) + sum_n (B_n / omega_n^2) d_n(t) sin(beta_n X),
//   d_n(t) = -sin(omega_n t) / (omega_n t_r)                          for t <= t_r,
//   d_n(t) = (sin(omega_n (t - t_r)) - sin(omega_n t)) / (omega_n t_r)  after,
// (the sum of B_n / omega_n^2 sin(beta_n X) over all n is u_s). The terms fall as n^-4; the
// sum keeps kModes of them (the first omitted is below 1e-8 A).
// The particles start at rest, undeformed.
#pragma once

#include <memory>

#include "scenes/scene.hpp"

namespace mpmstab {

class CompactionScene final : public Scene {
 public:
  static constexpr SceneInfo kInfo{.name = "compaction",
                                   .periodic = false,
                                   .fills_grid = false,
                                   .fixed_start = true,
                                   .body_start = 0,
                                   .body_length = 0.5,
                                   .free_surface = true,
                                   .tip_load = true};
  static constexpr double kRampPasses = 8;  // t_r = 8 L / c, two periods of the first mode
  static constexpr int kModes = 64;

  CompactionScene(double youngs_modulus, double amplitude, double length);

  Material material() const override { return Material::linear; }
  double gravity() const { return 2 * E * A / (rho0 * L * L); }  // g
  double ramp_time() const { return kRampPasses * L / c; }       // t_r
  double ramp(double t) const { return t < ramp_time() ? t / ramp_time() : 1.0; }

  double displacement(double X, double t) const override;
  double velocity(double X, double t) const override;
  double stress(double X, double t) const override;
  double body_force(double, double t) const override { return -gravity() * ramp(t); }
  bool separable() const override { return false; }
  // The modal sum at every X_p, with sin(beta_n X_p) kept from the last X asked.
  void displacements(const Eigen::ArrayXd& X, double t, Eigen::ArrayXd& u) const override;

  // b = -g r(t) at every particle.
  std::unique_ptr<BodyForceAtParticles> body_force_at(const Eigen::ArrayXd& X) const override;

  double period() const override { return 4 * L / c; }

  Particles initial_particles(int cells, int ppc, const Layout& layout = {}) const override;

 private:
  double beta(int n) const;  // (2 n - 1) pi / (2 L), n = 1..kModes
  // B_n / omega_n^2 d_n(t), and its derivative in t.
  double modal(int n, double t) const;
  double modal_rate(int n, double t) const;
  double static_displacement(double X) const;  // u_s(X)
  mutable Eigen::ArrayXd sines_X_;
  mutable Eigen::ArrayXXd sines_;  // sin(beta_n X_p), particle by mode
};

}  // namespace mpmstab
