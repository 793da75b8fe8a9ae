// The shape-function values of one step, kept from p2g for g2p and the stress update.
//
// All three phases use S_ip and G_ip at the particle positions x^n of the start of the step, so
// they are evaluated once (in p2g) and kept here. The values of one particle sit together (one
// row), since every consumer reads all of them at once.
#pragma once

#include <vector>

namespace mpmstab {

template <int W>
struct Stencil {
  struct Row {
    double w[W];  // S_ip for nodes base + k
    double g[W];  // G_ip for nodes base + k
  };
  std::vector<int> base;  // storage index (Grid) of the first node touched
  std::vector<Row> rows;

  void resize(std::size_t n) {
    base.resize(n);
    rows.resize(n);
  }
};

}  // namespace mpmstab
