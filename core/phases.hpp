// The four phases of one update-stress-last (USL) step, symplectic Euler A (paper sections 2
// and 4; DESIGN.md section 2). Equation numbers are the paper's.
//
//   p2g           mass, momentum and force to the grid                   eqs. (5)-(7)
//   grid_update   nodal acceleration and velocity, boundary conditions   eqs. (7), (8)
//   g2p           particle velocity and position                         eqs. (9), (10)
//   stress_update velocity gradient, F and sigma with the new velocities eqs. (11), (13), (14)
//
// Each phase is one loop over a struct of arrays. The shape functions are evaluated once per
// step, in p2g, at the positions x^n; g2p and the stress update reuse them (Stencil).
#pragma once

#include <cmath>

#include "grid.hpp"
#include "params.hpp"
#include "particles.hpp"
#include "stencil.hpp"

namespace mpmstab {

// p2g: m_i = sum_p S_ip m_p,  q_i = sum_p S_ip m_p v_p,
//      f_i = sum_p ( -G_ip sigma_p V_p + S_ip m_p b_p ),  V_p = F_p V_p^0   (eqs. 5, 6)
// `body_accel[p]` is b(X_p, t^n). The grid is cleared first. With periodic boundaries the
// positions are kept unwrapped and the stencil is taken at the image in [0, 1).
namespace detail {
template <bool kPeriodic, class Basis>
void p2g(const Basis basis, const Particles& P, const double* body_accel, Stencil<Basis::width>& S,
         Grid& G) {
  constexpr int W = Basis::width;
  const Eigen::Index n = P.size();
  const double* __restrict x = P.x.data();
  int* __restrict base = S.base.data();
  auto* __restrict rows = S.rows.data();

  // S_ip and G_ip at x^n, for every particle (independent iterations: no scatter here).
  for (Eigen::Index p = 0; p < n; ++p) {
    double xp = x[p];
    if constexpr (kPeriodic) xp -= std::floor(xp);
    basis.eval(xp, base[p], rows[p].w, rows[p].g);
    base[p] += Grid::kOffset;
  }

  // Scatter to the grid.
  G.mass.setZero();
  G.momentum.setZero();
  G.force.setZero();
  double* __restrict m_i = G.mass.data();
  double* __restrict q_i = G.momentum.data();
  double* __restrict f_i = G.force.data();
  const double* __restrict v = P.v.data();
  const double* __restrict F = P.F.data();
  const double* __restrict sig = P.sigma.data();
  const double* __restrict m_p = P.mass.data();
  const double* __restrict V0 = P.volume0.data();
  for (Eigen::Index p = 0; p < n; ++p) {
    const int b = base[p];
    const auto row = rows[p];  // a copy: the stores below cannot alias it
    const double mass = m_p[p];
    const double mom = mass * v[p];
    const double stress_volume = -sig[p] * F[p] * V0[p];
    const double body = mass * body_accel[p];
    for (int k = 0; k < W; ++k) {
      m_i[b + k] += row.w[k] * mass;
      q_i[b + k] += row.w[k] * mom;
      f_i[b + k] += row.g[k] * stress_volume + row.w[k] * body;
    }
  }
}

}  // namespace detail

template <class Basis>
void p2g(const Basis& basis, const Particles& P, const double* body_accel, Stencil<Basis::width>& S,
         Grid& G) {
  if (G.bc == Boundary::periodic) {
    detail::p2g<true>(basis, P, body_accel, S, G);
  } else {
    detail::p2g<false>(basis, P, body_accel, S, G);
  }
}

// grid update: a_i = f_i / m_i, v_i = q_i / m_i + dt a_i where m_i > 0 (eqs. 7, 8); zero where
// m_i = 0. Dirichlet nodes 0 and N get a_i = v_i = 0; periodic images are folded before and
// copied back after, so that g2p can read every slot of a stencil.
void grid_update(Grid& G, double dt);

// g2p: v_p += dt sum_i S_ip a_i (eq. 9); x_p += dt sum_i S_ip v_i (default) or, with
// PositionUpdate::particle, x_p += dt v_p^{n+1} (eq. 10).
template <int W>
void g2p(const Stencil<W>& S, const Grid& G, double dt, PositionUpdate mode, Particles& P) {
  const double* __restrict a_i = G.accel.data();
  const double* __restrict v_i = G.velocity.data();
  double* __restrict x = P.x.data();
  double* __restrict v = P.v.data();
  const Eigen::Index n = P.size();
  if (mode == PositionUpdate::grid) {
    for (Eigen::Index p = 0; p < n; ++p) {
      const int b = S.base[p];
      const double* w = S.rows[p].w;
      double a = 0, vg = 0;
      for (int k = 0; k < W; ++k) {
        a += w[k] * a_i[b + k];
        vg += w[k] * v_i[b + k];
      }
      v[p] += dt * a;
      x[p] += dt * vg;
    }
  } else {
    for (Eigen::Index p = 0; p < n; ++p) {
      const int b = S.base[p];
      const double* w = S.rows[p].w;
      double a = 0;
      for (int k = 0; k < W; ++k)
        a += w[k] * a_i[b + k];
      v[p] += dt * a;
      x[p] += dt * v[p];
    }
  }
}

// stress update (last): L_p = sum_i G_ip v_i^{n+1} (eq. 11); F_p <- F_p (1 + dt L_p) (eq. 13);
// sigma_p = E (F_p - 1), the material law of eq. (109); for this law it equals eq. (14)'s
// sigma_p + dt E L_p F_p.
template <int W>
void stress_update(const Stencil<W>& S, const Grid& G, double dt, double E, Particles& P) {
  const double* __restrict v_i = G.velocity.data();
  double* __restrict F = P.F.data();
  double* __restrict sig = P.sigma.data();
  const Eigen::Index n = P.size();
  for (Eigen::Index p = 0; p < n; ++p) {
    const int b = S.base[p];
    double L = 0;
    const double* g = S.rows[p].g;
    for (int k = 0; k < W; ++k)
      L += g[k] * v_i[b + k];
    F[p] *= 1.0 + dt * L;
    sig[p] = E * (F[p] - 1.0);
  }
}

}  // namespace mpmstab
