// A tip load added to a scene: a traction held on the free end of a bar fixed at X = 0 from
// t = 0 on (RunParams::tip_load; docs/theory.md, "Scenes", "A tip load on any free end").
//
// The scenes that take one (SceneInfo::tip_load: vibration, impulsive, compaction) are posed on
// the same bar [0, L], fixed at X = 0 and free at X = L, with the linear law sigma = E u_X. Their
// balance of momentum, rho0 u_tt = E u_XX + rho0 b, and their boundary conditions, u(0, t) = 0
// and E u_X(L, t) = traction, are linear in (u, b, traction). The impulsive bar with amplitude
// tip_load * A is the motion from rest under the traction tip_load * E A / (2 L) alone; the
// sum of the scene's motion and that one therefore satisfies the balance with the sum of their
// loads, both boundary conditions and the scene's initial state (the impulsive bar starts at
// rest, undeformed). The exact displacement, velocity and stress are the sums; the loads are
// the scene's plus the impulsive bar's force on the last particle. The exact energies are by
// quadrature (they are not sums: the energy is quadratic in the motion).
#pragma once

#include <memory>

#include "scenes/impulsive.hpp"
#include "scenes/scene.hpp"

namespace mpmstab {

class TipLoadedScene final : public Scene {
 public:
  // `scene` must declare SceneInfo::tip_load; `tip_load` > 0.
  TipLoadedScene(std::unique_ptr<Scene> scene, double tip_load);

  Material material() const override { return scene_->material(); }
  double traction() const { return tip_.traction(); }  // tip_load * E A / (2 L)

  double displacement(double X, double t) const override;
  double velocity(double X, double t) const override;
  double stress(double X, double t) const override;
  double body_force(double X, double t) const override { return scene_->body_force(X, t); }
  bool separable() const override { return false; }
  void displacements(const Eigen::ArrayXd& X, double t, Eigen::ArrayXd& u) const override;

  // The scene's loads (when it has any) plus the traction's force on the last particle.
  std::unique_ptr<BodyForceAtParticles> body_force_at(const Eigen::ArrayXd& X) const override;

  double period() const override { return scene_->period(); }

  // The scene's: the tip's motion starts at rest, undeformed.
  Particles initial_particles(int cells, int ppc, const Layout& layout = {}) const override {
    return scene_->initial_particles(cells, ppc, layout);
  }

 private:
  std::unique_ptr<Scene> scene_;
  ImpulsiveScene tip_;
};

}  // namespace mpmstab
