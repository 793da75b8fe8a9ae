// The phases of one step, symplectic Euler A (paper sections 2 and 4; docs/theory.md, "The
// scheme"). Equation numbers are the paper's.
//
//   p2g           mass, momentum and force to the grid                   eqs. (5)-(7)
//   grid_update   nodal acceleration and velocity, boundary conditions   eqs. (7), (8)
//   g2p           particle velocity and position                         eqs. (9), (10)
//   stress_update velocity gradient, F and sigma from the grid velocity  eqs. (11), (13), (14)
//
// The default step (update stress last, USL) runs them in this order. Update stress first (USF,
// the paper's section 6) and modified USL (MUSL) add two partial phases: grid_velocity, the
// nodal velocity q_i / m_i without the force, and p2g_force / p2g_momentum, which redo one
// sum of p2g over the stencil it kept (Simulation::step lists the order of each).
//
// Each phase is a loop over a struct of arrays. The shape functions are evaluated once per step,
// in p2g, at the positions x^n (and for cpGIMP with the half-widths of F^n); the other phases
// reuse them (Stencil).
//
// The kernels of the default choices live in phases.cpp, each compiled for three instruction sets
// and chosen when the program starts (MPMSTAB_SIMD_CLONES, simd.hpp); the other transfers and
// the partial sums of USF, MUSL and APIC live in transfers.cpp, with the same vector loops. Every
// version gives the same bits: loops are vectorized across particles or nodes, never inside a
// sum, and nothing is contracted to FMA. cpGIMP runs on the same kernels with stencils of four
// nodes. The neo-Hookean stress update is a plain loop.
#pragma once

#include "base/failure.hpp"
#include "base/material.hpp"
#include "base/params.hpp"
#include "base/particles.hpp"
#include "step/grid.hpp"
#include "step/shape.hpp"
#include "step/stencil.hpp"

namespace mpmstab {

// p2g: m_i = sum_p S_ip m_p,  q_i = sum_p S_ip m_p v_p,
//      f_i = sum_p ( -G_ip sigma_p V_p + S_ip m_p b_p ),  V_p = F_p V_p^0   (eqs. 5, 6)
// `body_accel[p]` is b(X_p, t) at the time the step evaluates it. The grid is cleared first;
// each node receives its contributions in particle order. With periodic boundaries the positions
// are kept unwrapped and the stencil is taken at the image in [0, 1). The state must be
// admissible (failure.hpp): finite positions and, for cpGIMP, 0 < F_p <= 2 m. With `body_accel`
// null, m_i and q_i only: f_i is not summed and left as it was (USF, which sums it after its
// stress update with p2g_force).
void p2g(const LinearBasis& basis, const Particles& P, const double* body_accel,
         Stencil<LinearBasis::width>& S, Grid& G);
void p2g(const GimpBasis& basis, const Particles& P, const double* body_accel,
         Stencil<GimpBasis::width>& S, Grid& G);
void p2g(const CpGimpBasis& basis, const Particles& P, const double* body_accel,
         Stencil<CpGimpBasis::width>& S, Grid& G);
void p2g(const CpdiBasis& basis, const Particles& P, const double* body_accel,
         Stencil<CpdiBasis::width>& S, Grid& G);
void p2g(const BSpline2Basis& basis, const Particles& P, const double* body_accel,
         Stencil<BSpline2Basis::width>& S, Grid& G);
void p2g(const BSpline3Basis& basis, const Particles& P, const double* body_accel,
         Stencil<BSpline3Basis::width>& S, Grid& G);

// The force sum of p2g alone, over the stencil p2g kept, with the current stress and volume:
// f_i = sum_p ( -G_ip sigma_p F_p V_p^0 + S_ip m_p b_p ). USF calls it after its stress update.
template <int W>
void p2g_force(const Stencil<W>& S, const Particles& P, const double* body_accel, Grid& G);

// The momentum sum of p2g alone, over the stencil p2g kept: q_i = sum_p S_ip m_p v_p. MUSL
// calls it after g2p to re-map the updated particle velocities.
template <int W>
void p2g_momentum(const Stencil<W>& S, const Particles& P, Grid& G);

// grid update: a_i = f_i / m_i, v_i = q_i / m_i + dt a_i where m_i > 0 (eqs. 7, 8); zero where
// m_i = 0. Dirichlet walls (nodes 0 and N) get a_i = v_i = 0. The padding slots beyond the walls
// (grid.hpp) are dropped (a = v = 0) with walls = clip; with walls = ghost nodes -1 and N + 1
// are free and updated like interior nodes. A node with a sliver of mass (Grid::small) then gets
// the cutoff or drop treatment of G.small_mass (the momentum treatment is small_mass.hpp's,
// after this phase). Periodic images are folded into their nodes before
// (their slots are left at zero) and copied back after, so that g2p can read every slot of a
// stencil.
void grid_update(Grid& G, double dt);

// The nodal velocity without the force: v_i = q_i / m_i where m_i > 0, zero elsewhere, with the
// boundary conditions and images of grid_update. USF's v_i^n; MUSL's re-mapped velocity.
void grid_velocity(Grid& G);

// How g2p updates a particle (params.hpp): the velocity transfer and the position update.
struct ParticleUpdate {
  Transfer transfer = Transfer::flip;
  double flip_fraction = 1.0;  // alpha of Transfer::blend
  PositionUpdate position = PositionUpdate::grid;
};

// g2p, particle velocity (eq. 9 for FLIP):
//   flip:  v_p += dt sum_i S_ip a_i
//   pic:   v_p  = sum_i S_ip v_i
//   blend: v_p  = alpha (v_p + dt sum_i S_ip a_i) + (1 - alpha) sum_i S_ip v_i
//   apic:  v_p  = sum_i S_ip v_i and C_p = sum_i G_ip v_i (P.C sized)
//   xpic:  v_p  = sum_i S_ip (v_i + w_i), w = G.correction (xpic.hpp)
//   fmpm:  as pic, with the velocity fmpm_velocity left in G (xpic.hpp)
// and position: x_p += dt sum_i S_ip v_i (default) or, with PositionUpdate::particle,
// x_p += dt v_p^{n+1} (eq. 10).
template <int W>
void g2p(const Stencil<W>& S, const Grid& G, double dt, const ParticleUpdate& rule, Particles& P);

// APIC's part of p2g, after p2g (or p2g_momentum): q_i += sum_p S_ip m_p C_p (X_i - x_p), over
// the stencil p2g kept, with x_p the positions `x_stencil` that stencil was evaluated at (taken
// in [0, 1) with periodic boundaries, as the stencil was): P.x before g2p has moved them, the
// start-of-step positions MUSL keeps after it. With C_p = dv/dx of an affine velocity field, the
// nodes then hold that field exactly: sum_p S_ip m_p (a + b x_p + b (X_i - x_p)) = m_i (a + b X_i)
// holds only when S_ip and x_p belong together.
template <int W>
void p2g_affine(const Stencil<W>& S, const double* x_stencil, const Particles& P, Grid& G);

// stress update: L_p = sum_i G_ip v_i with the velocity in G (eq. 11); F_p <- F_p (1 + dt L_p)
// (eq. 13); sigma_p = sigma(F_p) by the material law. For the linear law of eq. (109) this equals
// eq. (14)'s sigma_p + dt E L_p F_p.
template <int W>
void stress_update(const Stencil<W>& S, const Grid& G, double dt, const MaterialLaw& law,
                   Particles& P);

// The state check after a step (failure.hpp): `extremes`, to be filled with state_extremes's
// values for the state the step leaves, with the error over time when `error` is given.
struct StateCheck {
  const ErrorTerms* error = nullptr;
  StateExtremes* extremes = nullptr;
};

// USL's g2p then stress update as one pass over the particles, where the step allows it (FLIP,
// the linear law, a CPU with AVX-512 or AVX2): each particle's arithmetic is the two phases', and
// with a
// `check` the extremes are taken from the values as they are written, instead of in a pass of
// their own. Returns false, having done nothing, where it does not apply.
template <int W>
bool g2p_and_stress(const Stencil<W>& S, const Grid& G, double dt, const ParticleUpdate& rule,
                    const MaterialLaw& law, Particles& P, const StateCheck* check);

// g2p and stress_update as the last phase of a step (USF ends with g2p, MUSL and USL with
// another transfer than FLIP with the stress update), with a `check` (or none) to take in their
// own pass where they can (g2p: FLIP; the stress update: the linear law; both: a CPU with
// AVX-512 or AVX2). They always do the phase; true if they took the check.
template <int W>
bool g2p(const Stencil<W>& S, const Grid& G, double dt, const ParticleUpdate& rule, Particles& P,
         const StateCheck* check);
template <int W>
bool stress_update(const Stencil<W>& S, const Grid& G, double dt, const MaterialLaw& law,
                   Particles& P, const StateCheck* check);

}  // namespace mpmstab
