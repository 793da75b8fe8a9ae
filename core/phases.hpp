// The four phases of one update-stress-last (USL) step, symplectic Euler A (paper sections 2
// and 4; DESIGN.md section 2). Equation numbers are the paper's.
//
//   p2g           mass, momentum and force to the grid                   eqs. (5)-(7)
//   grid_update   nodal acceleration and velocity, boundary conditions   eqs. (7), (8)
//   g2p           particle velocity and position                         eqs. (9), (10)
//   stress_update velocity gradient, F and sigma with the new velocities eqs. (11), (13), (14)
//
// Each phase is a loop over a struct of arrays. The shape functions are evaluated once per step,
// in p2g, at the positions x^n; g2p and the stress update reuse them (Stencil).
//
// The kernels live in phases.cpp, each compiled for three instruction sets and chosen when the
// program starts (see MPMSTAB_SIMD_CLONES there). Every version gives the same bits: loops are
// vectorized across particles or nodes, never inside a sum, and nothing is contracted to FMA.
#pragma once

#include "grid.hpp"
#include "params.hpp"
#include "particles.hpp"
#include "shape.hpp"
#include "stencil.hpp"

namespace mpmstab {

// p2g: m_i = sum_p S_ip m_p,  q_i = sum_p S_ip m_p v_p,
//      f_i = sum_p ( -G_ip sigma_p V_p + S_ip m_p b_p ),  V_p = F_p V_p^0   (eqs. 5, 6)
// `body_accel[p]` is b(X_p, t^n). The grid is cleared first; each node receives its
// contributions in particle order. With periodic boundaries the positions are kept unwrapped and
// the stencil is taken at the image in [0, 1).
void p2g(const LinearBasis& basis, const Particles& P, const double* body_accel,
         Stencil<LinearBasis::width>& S, Grid& G);
void p2g(const GimpBasis& basis, const Particles& P, const double* body_accel,
         Stencil<GimpBasis::width>& S, Grid& G);

// grid update: a_i = f_i / m_i, v_i = q_i / m_i + dt a_i where m_i > 0 (eqs. 7, 8); zero where
// m_i = 0. Dirichlet nodes 0 and N get a_i = v_i = 0; periodic images are folded before and
// copied back after, so that g2p can read every slot of a stencil.
void grid_update(Grid& G, double dt);

// g2p: v_p += dt sum_i S_ip a_i (eq. 9); x_p += dt sum_i S_ip v_i (default) or, with
// PositionUpdate::particle, x_p += dt v_p^{n+1} (eq. 10).
template <int W>
void g2p(const Stencil<W>& S, const Grid& G, double dt, PositionUpdate mode, Particles& P);

// stress update (last): L_p = sum_i G_ip v_i^{n+1} (eq. 11); F_p <- F_p (1 + dt L_p) (eq. 13);
// sigma_p = E (F_p - 1), the material law of eq. (109); for this law it equals eq. (14)'s
// sigma_p + dt E L_p F_p.
template <int W>
void stress_update(const Stencil<W>& S, const Grid& G, double dt, double E, Particles& P);

}  // namespace mpmstab
