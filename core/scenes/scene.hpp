// The problems the solver runs (params.hpp, SceneKind). A scene declares everything the solver
// needs to know about a problem, and the solver reads a problem only through these declarations:
//  - SceneInfo: its name, the boundaries it is posed with, where its body lies in the grid
//    [0, 1] (filling it, or leaving empty cells beside it), whether it has a free surface;
//  - its material law;
//  - its loads, as a force per unit mass at each particle (BodyForceAtParticles): a
//    manufactured body force, a ramped body force, a force on the particle at a free end, or
//    none (has_body_force() false: the solver never evaluates one);
//  - its initial particle state;
//  - its exact solution: displacement, velocity and stress at (X, t), the exact energies, and
//    whether the displacement is separable (u = profile(X) * factor(t), which the error
//    observers evaluate as one product per particle) or evaluated per particle (ExactDisplacement).
// One file per scene in core/scenes/ holds its class, its SceneInfo and its derivation; the
// registry (scenes/scene_registry.hpp) is the one place that lists them.
//
// Every scene has rho0 = 1 and c = sqrt(E / rho0) and is posed in the material description:
// rho0 u_tt = dP/dX + rho0 b, F = 1 + u_X. m particles per cell sit at the reference positions
// X_p = (i + (k + 1/2) / m) h of the cells the body covers, with mass rho0 h / m.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>

#include <Eigen/Core>

#include "base/material.hpp"
#include "base/params.hpp"
#include "base/particles.hpp"

namespace mpmstab {

// What a scene declares about itself, without being made (validate() reads it).
struct SceneInfo {
  std::string_view name;
  bool dirichlet = true;  // posed with Dirichlet walls at X = 0 and X = 1
  bool periodic = true;   // posed on a periodic grid
  // The body fills [0, 1]: body_start and body_length are the grid's and may not be given.
  bool fills_grid = true;
  // The body's left end is the fixed wall X = 0: body_start may not be given.
  bool fixed_start = false;
  double body_start = 0;   // default extent of the body in the grid
  double body_length = 1;  //
  // A free surface inside the grid (an end of the body beside empty cells): the nodes beyond it
  // can hold a sliver of mass, which small_mass treats.
  bool free_surface = false;
  // A bar of linear material fixed at X = 0 whose other end is free: a traction on that end
  // (RunParams::tip_load) adds the impulsive bar's exact motion to the scene's.
  bool tip_load = false;

  constexpr bool supports(Boundary bc) const {
    return bc == Boundary::dirichlet ? dirichlet : periodic;
  }
};

// The loads of a scene at fixed reference positions X_p, as a force per unit mass b_p. The
// profiles in X are evaluated when it is made; each evaluation then costs little per particle.
class BodyForceAtParticles {
 public:
  virtual ~BodyForceAtParticles() = default;
  // b[p] = b(X_p, t), per unit mass.
  virtual void evaluate(double t, Eigen::ArrayXd& b) const = 0;
};

// b = 0 at every particle, for a scene without loads (never evaluated by the solver).
std::unique_ptr<BodyForceAtParticles> zero_body_force(Eigen::Index n);

// The exact energies of a scene at a time t, per unit cross-section (energy.hpp): kinetic
// 1/2 int rho0 v^2 dX, strain int W(F) dX over the body, and the work the loads have done on the
// body since t = 0.
struct ExactEnergy {
  double kinetic = 0;
  double strain = 0;
  double work = 0;
};

class Scene {
 public:
  // The body lies on [start, start + length] of the grid [0, 1].
  Scene(double youngs_modulus, double amplitude, double start = 0, double length = 1);
  virtual ~Scene() = default;

  double E;           // Young's modulus
  double A;           // amplitude (the scene's displacement scale, params.hpp)
  double rho0 = 1.0;  // reference density
  double c;           // wave speed sqrt(E / rho0)
  double x0;          // the body's left end
  double L;           // the body's length

  // The material law.
  virtual Material material() const = 0;
  MaterialLaw law() const { return {material(), E}; }

  // Exact fields at reference position X and time t.
  virtual double displacement(double X, double t) const = 0;
  virtual double velocity(double X, double t) const = 0;
  virtual double stress(double X, double t) const = 0;
  // The body force per unit mass where the load is a field (0 elsewhere; a force on one
  // particle is body_force_at's only).
  virtual double body_force(double, double) const { return 0.0; }

  // Whether u(X, t) = displacement_profile(X) * displacement_factor(t). Only a separable scene
  // is asked for its profile and factor; the others are asked for displacements().
  virtual bool separable() const { return true; }
  virtual double displacement_profile(double X) const;
  // displacement_profile at every X_p, the same values.
  virtual Eigen::ArrayXd displacement_profiles(const Eigen::ArrayXd& X) const {
    return X.unaryExpr([this](double Xp) { return displacement_profile(Xp); });
  }
  virtual double displacement_factor(double t) const;
  // u(X_p, t) at every X_p into u.
  virtual void displacements(const Eigen::ArrayXd& X, double t, Eigen::ArrayXd& u) const;

  // The loads at the reference positions X (one per particle); null when has_body_force() is
  // false.
  virtual std::unique_ptr<BodyForceAtParticles> body_force_at(const Eigen::ArrayXd& X) const = 0;
  // False for a scene without loads (b = 0 everywhere): the solver then never evaluates
  // body_force_at's object and its force sums add zero.
  virtual bool has_body_force() const { return true; }

  // The exact energies at time t (docs/theory.md, "Energy"). By default by quadrature of the
  // exact velocity and stress over the body (kExactEnergyPoints midpoints; fields with a jump
  // are then exact to about 1 / kExactEnergyPoints relative), the work by the balance
  // K + U - (K + U)(0) of the exact solution. Scenes with a closed form override it.
  virtual ExactEnergy exact_energy(double t) const;
  static constexpr int kExactEnergyPoints = 1 << 14;
  // The period of the exact solution in time (its fundamental period where it has one).
  virtual double period() const = 0;

  // The particle state at t = 0 on `cells` cells with `ppc` particles per cell.
  virtual Particles initial_particles(int cells, int ppc, const Layout& layout = {}) const = 0;

 protected:
  // The quadrature's K + U at t = 0, computed at the first call of the default exact_energy.
  mutable std::optional<double> initial_energy_;
  // The reference layout on the cells the body covers: X_p, mass rho0 h / m and reference
  // volume h / m; x, v, F and sigma are left to the scene.
  Particles reference_layout(int cells, int ppc, const Layout& layout) const;
  // Undeformed (x = X, F = 1, sigma = 0) with the exact velocity v(X_p, 0).
  void start_undeformed(Particles& P) const;
};

// The state at t = 0 of a scene that starts at rest at its deformed positions (steffen, mode):
// x = X + u(X, 0), v = 0, F = F(X, 0), sigma = sigma(F) of the scene's law.
template <class S>
void start_deformed_at_rest(const S& scene, Particles& P) {
  const MaterialLaw material_law = scene.law();
  for (Eigen::Index p = 0; p < P.size(); ++p) {
    const double X = P.X[p];
    P.x[p] = X + scene.displacement(X, 0.0);
    P.v[p] = 0.0;  // v(X, 0) = 0
    P.F[p] = scene.deformation_gradient(X, 0.0);
    P.sigma[p] = material_law.stress(P.F[p]);
  }
}

// The layout's first and one-past-last cell of a body on [start, start + length] of a grid of
// `cells` cells (both ends on cell boundaries, which validate() checks).
std::pair<int, int> body_cells(double start, double length, int cells);

// The jitter's pseudo-random value of particle `index`, in [-1/2, 1/2) (Layout).
double layout_jitter_unit(std::uint64_t index);

// The exact displacement at fixed reference positions, as the error observers read it:
// u(X_p, t) = u[p] * factor. For a separable scene u is the profile at X_p, kept from the
// construction, and factor the scene's factor of t (the error (x_p - X_p) - u_p f is then one
// product per particle); otherwise u(X_p, t) is evaluated into u at each call and factor is 1 (a
// product by 1 is exact). `X` is the same reference positions at every call.
class ExactDisplacement {
 public:
  ExactDisplacement(const Scene& scene, const Eigen::ArrayXd& X);
  struct Terms {
    const double* u;
    double factor;
  };
  Terms at(const Eigen::ArrayXd& X, double t) const;

 private:
  const Scene* scene_;
  mutable Eigen::ArrayXd u_;  // the profile (separable) or the last u(X_p, t)
};

}  // namespace mpmstab
