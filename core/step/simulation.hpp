// One simulation of a scene: the state, and a step that reads as its phases.
#pragma once

#include <cstdint>
#include <memory>
#include <variant>

#include "base/failure.hpp"
#include "base/params.hpp"
#include "base/particles.hpp"
#include "scenes/scene_registry.hpp"
#include "step/grid.hpp"
#include "step/phases.hpp"
#include "step/shape.hpp"
#include "step/stencil.hpp"
#include "step/xpic.hpp"

namespace mpmstab {

// The nodes a particle of basis `m` touches (its Basis::width).
int stencil_width(Method m);

class Simulation {
 public:
  // `p` must be valid (validate(p) empty).
  explicit Simulation(const RunParams& p);

  // One step from time() to t_next, its phases in the order of p.update (phases.hpp):
  //   usl:  p2g -> grid_update -> g2p -> stress_update
  // (with the momentum treatment of small-mass nodes after each grid_update)
  //   usf:  p2g -> grid_velocity -> stress_update -> p2g_force -> grid_update -> g2p
  //   musl: p2g -> grid_update -> g2p -> p2g_momentum -> grid_velocity -> stress_update
  // APIC adds p2g_affine after each momentum sum, about the positions x^n at which the step's
  // stencil was evaluated (MUSL's re-map too); XPIC and FMPM add their series (xpic.hpp)
  // between grid_update and g2p.
  // With `extremes`, the state check after the step: state_extremes of the state it leaves (with
  // the error over time at t_next when `with_error`), taken in the step's last pass where it can
  // (phases.hpp: g2p_and_stress, g2p, stress_update), else in a pass after the step; the same
  // values either way.
  void advance_to(double t_next, StateExtremes* extremes = nullptr, bool with_error = false);

  // max_p |u_p - u(X_p, t)| at the current time, u_p = x_p - X_p, u the scene's exact solution.
  double max_error() const;

  double time() const { return t_; }
  std::int64_t steps() const { return n_; }
  const RunParams& params() const { return params_; }
  const Scene& scene() const { return *scene_; }
  const Particles& particles() const { return P_; }
  Particles& particles() { return P_; }  // for tests that plant a state
  const Grid& grid() const { return G_; }
  // The body force per unit mass the last step applied at each particle (zeros for a scene
  // without one).
  const Eigen::ArrayXd& body_acceleration() const { return body_accel_; }

 private:
  // True if its last phase took the check (`check` given, where phases.hpp says it can).
  template <class Basis>
  bool step(const Basis& basis, Stencil<Basis::width>& S, double dt, double t_body,
            const StateCheck* check);
  // What max_error reads at time t; the state check takes the same error in its pass.
  ErrorTerms error_terms_at(double t) const;
  // XPIC's and FMPM's correction of the grid velocity, after grid_update (xpic.hpp).
  template <int W>
  void series_phase(const Stencil<W>& S);
  // The momentum treatment of small-mass nodes after grid_update (small_mass.hpp).
  template <int W>
  void small_mass_phase(const Stencil<W>& S, double dt);
  // FMPM's series after grid_velocity (USF's v^n, MUSL's re-mapped velocity).
  template <int W>
  void full_mass_velocity(const Stencil<W>& S);

  RunParams params_;
  std::unique_ptr<Scene> scene_;
  MaterialLaw law_;
  ParticleUpdate g2p_rule_;
  Particles P_;
  Grid G_;
  std::variant<LinearBasis, GimpBasis, CpGimpBasis, BSpline2Basis, BSpline3Basis, CpdiBasis> basis_;
  // One stencil per width; only the one of the run's basis is allocated.
  Stencil<2> stencil2_;
  Stencil<3> stencil3_;
  Stencil<4> stencil4_;
  template <int W>
  Stencil<W>& stencil();
  std::unique_ptr<BodyForceAtParticles> body_force_;  // b(X_p, t)
  Eigen::ArrayXd body_accel_;                         // b(X_p, t) for the current step
  ExactDisplacement exact_;                           // u(X_p, t)
  SeriesWork series_;                                 // XPIC and FMPM only
  // MUSL with APIC: the positions x^n at which the step's stencil was evaluated, kept across g2p
  // for the re-map's affine term (p2g_affine).
  Eigen::ArrayXd x_stencil_;
  double t_ = 0;
  std::int64_t n_ = 0;
};

}  // namespace mpmstab
