// XPIC(m) and FMPM(k): PIC with the grid velocity corrected by the series that approximates the
// inverse of the full (consistent) mass matrix.
//
// With lumped masses the nodal velocity is v_i = q_i / m_i. The full mass matrix is
// M_ij = sum_p m_p S_ip S_jp, and M_L^{-1} M = Q is the grid field taken to the particles and
// back, mass-weighted:
//
//   (Q y)_i = (1 / m_i) sum_p S_ip m_p (sum_j S_jp y_j).
//
// The full-mass velocity M^{-1} q = (I - (I - Q))^{-1} v is approximated by the first terms of
// its Neumann series,
//
//   v^(k) = sum_{r=0}^{k-1} (I - Q)^r v                                           (series)
//
// which is what both methods compute, with the walls' and the periodic images' conditions of
// grid_update applied to every term (a fixed node stays at zero):
//
//  - XPIC(m), Hammerquist and Nairn (2017), CMAME 318, 724-738: the particle velocity is
//    V^{n+1} = S (v^{n+1} - v^n) + S v^(m)(v^n), i.e. FLIP's increment on the series applied to
//    the velocity v^n = q / m of p2g; with P = S S^+ the particle-to-particle projection this is
//    V^{n+1} = S a dt + (I - (I - P)^m) V^n. XPIC(1) is PIC; as m grows only the part of V^n in
//    the null space of P (the noise that FLIP keeps and PIC removes with the signal) is dropped.
//    XPIC acts on g2p alone, through a correction field w = v^(m)(v^n) - v^n on the grid
//    (Grid::correction): v_p = sum_i S_ip (v_i^{n+1} + w_i). The grid velocity of the stress
//    update and of the position update stays the lumped one.
//  - FMPM(k), Nairn and Hammerquist (2021), CMAME 377, 113667: the lumped velocity is replaced by
//    the series wherever a nodal velocity is used: after grid_update (v^{n+1}, so that g2p is
//    PIC with it, V^{n+1} = S v^(k)(v^{n+1}), and the position and USL's stress update use it
//    too) and after grid_velocity (USF's v^n, MUSL's re-mapped velocity). The forces and the
//    accelerations stay lumped. FMPM(1) is PIC.
//
// The sum is computed from its r >= 1 terms alone, so that order 1 adds exactly zero: XPIC(1)
// and FMPM(1) give PIC's results to the bit. A fixed node's term is set to zero at every r (the
// velocity condition applied inside the series, as Nairn's revised FMPM loop does); each term
// keeps the walls' and the periodic images' conditions of grid_update.
//
// Not offered: XPIC's and FMPM's own position updates (X^{n+1} = X^n + dt (S v^n + (V^{n+1} -
// V^n) / 2) and X^n + dt (V^{n+1} + V^n) / 2 in Nairn's code); the position follows the run's
// position_update, as with every transfer.
#pragma once

#include <Eigen/Core>

#include "base/particles.hpp"
#include "step/grid.hpp"
#include "step/stencil.hpp"

namespace mpmstab {

// Work arrays of the series, sized on first use (only XPIC and FMPM runs have them).
struct SeriesWork {
  Eigen::ArrayXd start;         // XPIC's v^n; FMPM's sum
  Eigen::ArrayXd term;          // (I - Q)^r v on the grid
  Eigen::ArrayXd projected;     // Q applied to the previous term
  Eigen::ArrayXd at_particles;  // sum_j S_jp y_j per particle
};

// w = sum_{r=1}^{order-1} (I - Q)^r v on the grid (zero on fixed slots, images copied), over the
// stencil p2g kept and the folded nodal masses of grid_update. `v` must satisfy the boundary
// conditions (zero on fixed slots, images copied).
template <int W>
void series_correction(const Stencil<W>& S, const Particles& P, const Grid& G, int order,
                       const Eigen::ArrayXd& v, Eigen::ArrayXd& w, SeriesWork& work);

// XPIC(m), after grid_update: G.correction = the series of v^n = q_i / m_i (the velocity of
// p2g, before the force), so that g2p gives V^{n+1} = S (v^{n+1} + w).
template <int W>
void xpic_correction(const Stencil<W>& S, const Particles& P, int m, Grid& G, SeriesWork& work);

// FMPM(k), after grid_update or grid_velocity: G.velocity <- v^(k)(G.velocity).
template <int W>
void fmpm_velocity(const Stencil<W>& S, const Particles& P, int k, Grid& G, SeriesWork& work);

}  // namespace mpmstab
