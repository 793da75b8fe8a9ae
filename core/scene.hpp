// The paper's model problem (section 5.1, DESIGN.md section 1): a 1D bar on [0, 1] with the
// manufactured solution
//   u(X, t) = A sin(2 pi X) sin(c pi t),  c = sqrt(E / rho0),
// the linear material sigma = E (F - 1), and the body force per unit mass that makes u exact,
//   b(X, t) = 3 (c pi)^2 A sin(2 pi X) sin(c pi t)
// (the paper's eq. 114 prints "3 A (c pi)^2 u", which counts A twice; substituting u into
// rho0 u_tt = dP/dX + rho0 b gives this form).
//
// Every field is the product of a profile in X and a factor in t. The solver uses that: it keeps
// the profiles per particle and evaluates the time factors once per step.
#pragma once

#include <numbers>

#include "particles.hpp"

namespace mpmstab {

struct BarScene {
  double E;
  double A;
  double rho0 = 1.0;
  double c;  // wave speed sqrt(E / rho0)

  BarScene(double youngs_modulus, double amplitude);

  // Exact fields at reference position X and time t.
  double displacement(double X, double t) const;
  double velocity(double X, double t) const;
  double stress(double X, double t) const;
  double body_force(double X, double t) const;  // per unit mass

  // Separable forms: field(X, t) = profile(X) * factor(t).
  double displacement_profile(double X) const;  // A sin(2 pi X)
  double displacement_factor(double t) const;   // sin(c pi t)
  double body_force_profile(double X) const;    // 3 (c pi)^2 A sin(2 pi X)
  double body_force_factor(double t) const;     // sin(c pi t)

  // m particles per cell at cell-relative positions (k + 1/2) / m, mass rho0 h / m, volume h / m,
  // F = 1, sigma = 0, velocity v(X_p, 0).
  Particles initial_particles(int cells, int ppc) const;
};

}  // namespace mpmstab
