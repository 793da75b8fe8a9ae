// The problems the solver runs (params.hpp, SceneKind). A scene declares everything the solver
// needs to know about a problem: its material law, the boundaries it can be posed with, its
// initial particle state, the body force that drives it and its exact solution. The solver
// evaluates only these declarations.
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
// bar (the paper's section 5.1, docs/design.md, "The problem"): linear material sigma = E (F - 1),
//   u(X, t) = A sin(2 pi X) sin(c pi t),  b(X, t) = 3 (c pi)^2 A sin(2 pi X) sin(c pi t).
//   The paper's eq. (114) prints "3 A (c pi)^2 u", which counts A twice; substituting u into the
//   balance of momentum gives this form. The particles start undeformed (x_p = X_p, F_p = 1,
//   sigma_p = 0) with the exact velocity v(X_p, 0).
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

#include <cstdint>
#include <limits>
#include <memory>

#include <Eigen/Core>

#include "material.hpp"
#include "params.hpp"
#include "particles.hpp"

namespace mpmstab {

// The body force of a scene at fixed reference positions X_p. The profiles in X are evaluated
// when it is made; each evaluation then costs one trigonometric value of t and a few operations
// per particle.
class BodyForceAtParticles {
 public:
  virtual ~BodyForceAtParticles() = default;
  // b[p] = b(X_p, t), per unit mass.
  virtual void evaluate(double t, Eigen::ArrayXd& b) const = 0;
};

// The exact energies of a scene at a time t, per unit cross-section (energy.hpp): kinetic
// 1/2 int rho0 v^2 dX, strain int W(F) dX over the body, and the work the body force has done
// on the body since t = 0.
struct ExactEnergy {
  double kinetic = 0;
  double strain = 0;
  double work = 0;
};

class Scene {
 public:
  Scene(double youngs_modulus, double amplitude);
  virtual ~Scene() = default;

  double E;           // Young's modulus
  double A;           // amplitude of the manufactured solution
  double rho0 = 1.0;  // reference density
  double c;           // wave speed sqrt(E / rho0)

  // The material law. (The boundaries a scene is posed with are a static declaration of each
  // scene, supports(), read through scene_supports() below.)
  virtual Material material() const = 0;
  MaterialLaw law() const { return {material(), E}; }

  // Exact fields at reference position X and time t.
  virtual double displacement(double X, double t) const = 0;
  virtual double velocity(double X, double t) const = 0;
  virtual double stress(double X, double t) const = 0;
  virtual double body_force(double X, double t) const = 0;  // per unit mass

  // u(X, t) = displacement_profile(X) * displacement_factor(t).
  virtual double displacement_profile(double X) const = 0;
  // displacement_profile at every X_p, the same values.
  virtual Eigen::ArrayXd displacement_profiles(const Eigen::ArrayXd& X) const {
    return X.unaryExpr([this](double Xp) { return displacement_profile(Xp); });
  }
  virtual double displacement_factor(double t) const = 0;

  // The body force at the reference positions X (one per particle).
  virtual std::unique_ptr<BodyForceAtParticles> body_force_at(const Eigen::ArrayXd& X) const = 0;

  // The exact energies at time t, in closed form (docs/design.md, "Energy").
  virtual ExactEnergy exact_energy(double t) const = 0;
  // The period of the exact solution in time.
  virtual double period() const = 0;
  // False for a scene without a body force (b = 0 everywhere): the solver then never evaluates
  // body_force_at's object and its force sums add zero.
  virtual bool has_body_force() const { return true; }

  // The particle state at t = 0 on `cells` cells with `ppc` particles per cell.
  virtual Particles initial_particles(int cells, int ppc, const Layout& layout = {}) const = 0;

 protected:
  // The reference layout: X_p, mass rho0 h / m and reference volume h / m; x, v, F and sigma are
  // left to the scene.
  Particles reference_layout(int cells, int ppc, const Layout& layout) const;
};

// The jitter's pseudo-random value of particle `index`, in [-1/2, 1/2) (Layout).
double layout_jitter_unit(std::uint64_t index);

class BarScene final : public Scene {
 public:
  BarScene(double youngs_modulus, double amplitude);

  Material material() const override { return Material::linear; }
  static constexpr bool supports(Boundary) { return true; }  // Dirichlet and periodic

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

class SteffenScene final : public Scene {
 public:
  SteffenScene(double youngs_modulus, double amplitude);

  Material material() const override { return Material::neo_hookean; }
  static constexpr bool supports(Boundary) { return true; }  // Dirichlet and periodic

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

// mode: one free standing wave of wavelength 1 on the periodic linear bar (the dispersion
// study's scene, core/dispersion.hpp). Linear material sigma = E (F - 1), no body force:
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
  static constexpr bool supports(Boundary bc) { return bc == Boundary::periodic; }

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

// The scene of a run: p.scene with p.E and p.A.
std::unique_ptr<Scene> make_scene(const RunParams& p);

// Whether scene `kind` is posed with boundaries `bc`, without making the scene (validate()).
constexpr bool scene_supports(SceneKind kind, Boundary bc) {
  switch (kind) {
    case SceneKind::bar:
      return BarScene::supports(bc);
    case SceneKind::steffen:
      return SteffenScene::supports(bc);
    case SceneKind::mode:
      return ModeScene::supports(bc);
  }
  return false;
}

}  // namespace mpmstab
