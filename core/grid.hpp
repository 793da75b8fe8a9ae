// Background grid as a struct of arrays over nodes.
//
// Nodes X_i = i h, i = 0..N. Every array has one padding slot on each side (storage index
// i + 1 holds node i), so that a particle stencil never needs a bounds check:
//  - Dirichlet: real nodes 0..N; slots -1 and N + 1 collect nothing (their contributions are
//    dropped after p2g) and hold zero velocity and acceleration.
//  - Periodic: real nodes 0..N-1; slots -1, N and N + 1 are images of nodes N-1, 0 and 1.
#pragma once

#include <Eigen/Core>

#include "params.hpp"

namespace mpmstab {

struct Grid {
  int cells = 0;
  double h = 0;
  Boundary bc = Boundary::dirichlet;

  Eigen::ArrayXd mass;      // m_i
  Eigen::ArrayXd momentum;  // q_i
  Eigen::ArrayXd force;     // f_i (internal + body)
  Eigen::ArrayXd velocity;  // v_i^{n+1}
  Eigen::ArrayXd accel;     // a_i^{n+1}

  static constexpr int kOffset = 1;  // storage index of node 0

  Grid() = default;
  Grid(int n_cells, Boundary boundary) : cells(n_cells), h(1.0 / n_cells), bc(boundary) {
    const Eigen::Index slots = n_cells + 3;  // nodes -1 .. N + 1
    for (Eigen::ArrayXd* a : {&mass, &momentum, &force, &velocity, &accel})
      a->setZero(slots);
  }

  // Number of distinct nodes: N + 1 (Dirichlet) or N (periodic).
  int nodes() const { return bc == Boundary::periodic ? cells : cells + 1; }
};

}  // namespace mpmstab
