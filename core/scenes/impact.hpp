// Two identical elastic bars meeting at speeds +v and -v (docs/theory.md, "Scenes"): the left
// bar [x0, m] moves right at v, the right bar [m, x0 + L] left at v, m = x0 + L / 2, touching at
// t = 0. One velocity field carries both (no contact algorithm): the grid sees one body.
//
// Linear material, rho0 = 1, each bar of length L_b = L / 2, v = A c / L_b (so that the ends'
// largest displacement, v L_b / c, is A). While the bars touch, the motion is that of one free
// bar [x0, x0 + L] with initial velocity v0(X) = v for X < m and -v for X > m: with v~ the even
// extension of v0 about both ends (period 2 L) and Psi its integral,
//   u(X, t) = (Psi(X + c t) - Psi(X - c t)) / (2 c),
//   v(X, t) = (v~(X + c t) + v~(X - c t)) / 2,  sigma = E (v~(X + c t) - v~(X - c t)) / (2 c).
// The contact stress is -rho0 c v (a compression E v / c, from the interface outwards); the
// release waves from the free ends meet at the interface at the separation time
// t_s = 2 L_b / c = L / c, when every particle has u = 0, the stress is zero and the bars move
// apart at -v and +v. After t_s the exact (contact) motion is that rigid separation,
// u = -+v (t - t_s). A single velocity field cannot separate: after t_s the bars stay joined and
// the interface goes into tension, so that the error against the exact motion grows from t_s;
// runs of this scene stop at T <= t_s to compare the contact.
#pragma once

#include <memory>

#include "scenes/scene.hpp"

namespace mpmstab {

class ImpactScene final : public Scene {
 public:
  static constexpr SceneInfo kInfo{.name = "impact",
                                   .periodic = false,
                                   .fills_grid = false,
                                   .body_start = 0.25,
                                   .body_length = 0.5,
                                   .free_surface = true};

  ImpactScene(double youngs_modulus, double amplitude, double start, double length);

  Material material() const override { return Material::linear; }
  double speed() const { return A * c / (L / 2); }  // v
  double interface() const { return x0 + L / 2; }   // m
  double contact_stress() const { return -rho0 * c * speed(); }
  double separation_time() const { return L / c; }  // t_s

  double displacement(double X, double t) const override;
  double velocity(double X, double t) const override;
  double stress(double X, double t) const override;
  bool separable() const override { return false; }

  std::unique_ptr<BodyForceAtParticles> body_force_at(const Eigen::ArrayXd& X) const override;
  bool has_body_force() const override { return false; }

  double period() const override { return 2 * L / c; }  // of the joined bar

  Particles initial_particles(int cells, int ppc, const Layout& layout = {}) const override;

 private:
  double extended_velocity(double s) const;  // v~(s)
  double Psi(double s) const;                // its integral, Psi(x0) = 0
};

}  // namespace mpmstab
