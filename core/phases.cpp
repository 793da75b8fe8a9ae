#include "phases.hpp"

#include <array>

namespace mpmstab {

namespace {
std::array<int, 3> image_slots(int N) {
  return {-1, N, N + 1};
}
int wrap(int i, int N) {
  return ((i % N) + N) % N;
}
}  // namespace

void grid_update(Grid& G, double dt) {
  constexpr int o = Grid::kOffset;
  const int N = G.cells;
  double* m = G.mass.data();
  double* q = G.momentum.data();
  double* f = G.force.data();
  double* v = G.velocity.data();
  double* a = G.accel.data();
  const Eigen::Index slots = G.mass.size();

  int first = 0, last = N;  // real nodes whose velocity is computed
  if (G.bc == Boundary::periodic) {
    // Padding slots -1, N and N + 1 are images of nodes (i mod N): fold them in.
    for (const int i : image_slots(N))
      for (double* arr : {m, q, f})
        arr[o + wrap(i, N)] += arr[o + i];
    last = N - 1;
  } else {
    // Fixed nodes 0 and N: a = v = 0. Contributions to the slots beyond the walls are dropped.
    first = 1;
    last = N - 1;
  }

  for (Eigen::Index s = 0; s < slots; ++s)
    v[s] = a[s] = 0.0;
  for (int i = first; i <= last; ++i) {
    const int s = o + i;
    if (m[s] > 0.0) {
      const double inv_m = 1.0 / m[s];
      a[s] = f[s] * inv_m;
      v[s] = q[s] * inv_m + dt * a[s];
    }
  }

  if (G.bc == Boundary::periodic) {
    for (const int i : image_slots(N))
      for (double* arr : {v, a})
        arr[o + i] = arr[o + wrap(i, N)];
  }
}

}  // namespace mpmstab
