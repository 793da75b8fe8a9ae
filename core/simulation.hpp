// One simulation of the bar: the state, and a step that reads as its four phases.
#pragma once

#include <cstdint>
#include <variant>

#include "grid.hpp"
#include "params.hpp"
#include "particles.hpp"
#include "scene.hpp"
#include "shape.hpp"
#include "stencil.hpp"

namespace mpmstab {

class Simulation {
 public:
  // `p` must be valid (validate(p) empty).
  explicit Simulation(const RunParams& p);

  // One USL step from time() to t_next:
  //   p2g -> grid_update -> g2p -> stress_update   (phases.hpp)
  void advance_to(double t_next);

  // max_p |u_p - u(X_p, t)| at the current time, u_p = x_p - X_p.
  double max_error() const;

  double time() const { return t_; }
  std::int64_t steps() const { return n_; }
  const RunParams& params() const { return params_; }
  const BarScene& scene() const { return scene_; }
  const Particles& particles() const { return P_; }
  Particles& particles() { return P_; }  // for tests that plant a state
  const Grid& grid() const { return G_; }

 private:
  template <class Basis, class StencilT>
  void step(const Basis& basis, StencilT& stencil, double dt);

  RunParams params_;
  BarScene scene_;
  Particles P_;
  Grid G_;
  std::variant<LinearBasis, GimpBasis> basis_;
  Stencil<LinearBasis::width> stencil_mpm_;
  Stencil<GimpBasis::width> stencil_gimp_;
  Eigen::ArrayXd body_profile_;  // 3 (c pi)^2 A sin(2 pi X_p)
  Eigen::ArrayXd body_accel_;    // b(X_p, t^n) for the current step
  Eigen::ArrayXd u_profile_;     // A sin(2 pi X_p)
  double t_ = 0;
  std::int64_t n_ = 0;
};

}  // namespace mpmstab
