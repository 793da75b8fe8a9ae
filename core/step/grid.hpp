// Background grid as a struct of arrays over nodes.
//
// Nodes X_i = i h, i = 0..N. Every array has padding slots on each side (storage index i + 1
// holds node i), so that a particle stencil never needs a bounds check. A particle on [0, 1]
// with half-width lp <= h has its first node, floor((x - lp) / h), in -1..N (N - 1 unless
// lp = 0), so its stencil of W nodes stays within nodes -1..N + 1 for the hat (W = 2) and uGIMP
// (W = 3) and within -1..N + 2 for cpGIMP (W = 4): one padding slot on the left, and one or two
// on the right (right_padding).
//  - Dirichlet, walls = clip: real nodes 0..N; the padding slots collect what p2g puts there,
//    which the grid update drops: they hold zero velocity and acceleration.
//  - Dirichlet, walls = ghost: nodes -1 and N + 1 are real free nodes too (see grid_update);
//    further padding (cpGIMP's node N + 2, which a particle on [0, 1] never weights) is dropped.
//  - Periodic: real nodes 0..N-1; slot -1 is the image of node N-1 and slots N, N + 1, ... are
//    images of nodes 0, 1, ...
#pragma once

#include <algorithm>

#include <Eigen/Core>

#include "base/params.hpp"

namespace mpmstab {

struct Grid {
  int cells = 0;
  double h = 0;
  Boundary bc = Boundary::dirichlet;
  Walls walls = Walls::clip;

  Eigen::ArrayXd mass;      // m_i
  Eigen::ArrayXd momentum;  // q_i
  Eigen::ArrayXd force;     // f_i (internal + body)
  Eigen::ArrayXd velocity;  // v_i^{n+1}
  Eigen::ArrayXd accel;     // a_i^{n+1}
  // XPIC and FMPM (xpic.hpp): the correction w_i that g2p adds to v_i. Sized only for them.
  Eigen::ArrayXd correction;

  // Small-mass nodes (params.hpp, SmallMass; small_mass.hpp): the treatment and the mass below
  // which a node is treated (small_mass_fraction * rho0 h). None by default.
  SmallMass small_mass = SmallMass::none;
  double mass_cutoff = 0;
  bool small(double m) const { return m > 0.0 && m < mass_cutoff; }
  // A body with ends inside the grid (scene.hpp, SceneInfo::fills_grid false): a free node
  // without mass beside one with mass takes that node's velocity and acceleration (its left
  // neighbour's where both have mass). No particle weights such a node (S_ip = 0), but a linear
  // or CPDI particle exactly on the node between them has G_ip = 1 / h there: with v_i = 0 a
  // block in rigid translation would read a velocity gradient of -v / h.
  bool extend_to_empty = false;

  static constexpr int kOffset = 1;  // storage index of node 0

  // Padding slots right of node N for stencils of `width` nodes.
  static constexpr int right_padding(int width) { return std::max(1, width - 2); }

  Grid() = default;
  // `stencil_width`: the number of nodes a particle touches (Basis::width).
  Grid(int n_cells, Boundary boundary, Walls wall_nodes = Walls::clip, int stencil_width = 3)
      : cells(n_cells), h(1.0 / n_cells), bc(boundary), walls(wall_nodes) {
    const Eigen::Index slots = kOffset + n_cells + 1 + right_padding(stencil_width);
    for (Eigen::ArrayXd* a : {&mass, &momentum, &force, &velocity, &accel})
      a->setZero(slots);
  }

  bool ghost_nodes() const { return bc == Boundary::dirichlet && walls == Walls::ghost; }

  // The distinct nodes, as consecutive storage slots from first_node_slot(): N + 1 (Dirichlet),
  // N + 3 (Dirichlet with ghost nodes -1 and N + 1) or N (periodic).
  int first_node_slot() const { return ghost_nodes() ? kOffset - 1 : kOffset; }
  int nodes() const {
    if (bc == Boundary::periodic) return cells;
    return ghost_nodes() ? cells + 3 : cells + 1;
  }
  int slots() const { return static_cast<int>(mass.size()); }
};

}  // namespace mpmstab
