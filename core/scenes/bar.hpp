// The paper's bar.
//
// The bar and steffen scenes are manufactured solutions on [0, 1] with rho0 = 1 and
// c = sqrt(E / rho0), in the material description, with the balance of momentum
// rho0 u_tt = dP/dX + rho0 b and F = 1 + u_X. Their displacements are A sin(2 pi X) times a
// function of t: zero at X = 0 and X = 1 and periodic, so both accept Dirichlet and periodic
// boundaries. The mode scene (below) is an exact free wave of the same form, without a body
// force, posed with periodic boundaries only. The displacement is separable,
// u(X, t) = displacement_profile(X) * displacement_factor(t), which the error observer uses: it
// keeps the profile per particle and evaluates the factor once per step.
//
// bar (the paper's section 5.1, docs/theory.md, "The problem"): linear material sigma = E (F - 1),
//   u(X, t) = A sin(2 pi X) sin(c pi t),  b(X, t) = 3 (c pi)^2 A sin(2 pi X) sin(c pi t).
//   The paper's eq. (114) prints "3 A (c pi)^2 u", which counts A twice; substituting u into the
//   balance of momentum gives this form. The particles start undeformed (x_p = X_p, F_p = 1,
//   sigma_p = 0) with the exact velocity v(X_p, 0).
//
#pragma once

#include <limits>
#include <memory>

#include <Eigen/Core>

#include "scenes/scene.hpp"

namespace mpmstab {

class BarScene final : public Scene {
 public:
  BarScene(double youngs_modulus, double amplitude);

  Material material() const override { return Material::linear; }
  static constexpr SceneInfo kInfo{.name = "bar"};  // fills [0, 1]; Dirichlet and periodic

  double displacement(double X, double t) const override;
  double velocity(double X, double t) const override;
  double stress(double X, double t) const override;
  double body_force(double X, double t) const override;

  double displacement_profile(double X) const override;  // A sin(2 pi X)
  Eigen::ArrayXd displacement_profiles(const Eigen::ArrayXd& X) const override;
  double displacement_factor(double t) const override;  // sin(c pi t)
  // The body force is separable too: b(X, t) = body_force_profile(X) * body_force_factor(t).
  double body_force_profile(double X) const;  // 3 (c pi)^2 A sin(2 pi X)
  double body_force_factor(double t) const;   // sin(c pi t)

  // With w = c pi: K = A^2 w^2 cos^2(w t) / 4, U = E pi^2 A^2 sin^2(w t) and the body force's
  // work 3 A^2 w^2 sin^2(w t) / 4 (rho0 = 1), so that K + U - work = K(0) at every t.
  ExactEnergy exact_energy(double t) const override;
  double period() const override { return 2.0 / c; }

  // The body force at particles X reads this scene (which must outlive it).
  std::unique_ptr<BodyForceAtParticles> body_force_at(const Eigen::ArrayXd& X) const override;

  // At rest positions x = X, F = 1, sigma = 0, velocity v(X_p, 0).
  Particles initial_particles(int cells, int ppc, const Layout& layout = {}) const override;

 private:
  // sin(c pi t), both time factors, for the last t asked: a run asks at t^{n+1} for the error
  // after a step, then at the same time for the body force of the next step (its t^n).
  double time_sine(double t) const;
  mutable double sine_t_ = std::numeric_limits<double>::quiet_NaN();
  mutable double sine_ = 0;
  // sin(2 pi X_p) for the last X asked: the initial velocities, the body force's profile and
  // the error's displacement profile of a run all take it at the same reference positions
  // (for a large bar, three sines per particle were a tenth of a short run).
  const Eigen::ArrayXd& space_sines(const Eigen::ArrayXd& X) const;
  mutable Eigen::ArrayXd sines_X_, sines_;
};

}  // namespace mpmstab
