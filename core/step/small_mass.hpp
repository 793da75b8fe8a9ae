// The momentum treatment of small-mass nodes (params.hpp, SmallMass::momentum; docs/theory.md,
// "Small-mass nodes"), after grid_update: each node with 0 < m_i < G.mass_cutoff takes as its
// new velocity the mass-weighted mean of the particles' FLIP-updated velocities,
//   v_i = sum_p S_ip m_p v_p* / m_i,  v_p* = v_p + dt sum_j S_jp a_j,
// and the acceleration (v_i - q_i / m_i) / dt that gives it. This is the velocity that modified
// USL re-maps for every node; here only the small-mass nodes take it, so that a node whose
// a_i = f_i / m_i is huge moves no faster than the particles around it. Other nodes are left
// as grid_update set them. Sums in particle order, as every grid sum.
#pragma once

#include "base/particles.hpp"
#include "step/grid.hpp"
#include "step/stencil.hpp"

namespace mpmstab {

template <int W>
void small_mass_momentum(const Stencil<W>& S, const Particles& P, double dt, Grid& G);

}  // namespace mpmstab
