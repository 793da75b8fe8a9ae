// Which storage slots of a Grid are free nodes, fixed nodes or periodic images (grid.hpp), for
// the phases that write nodal velocities: grid_update and grid_velocity (phases.cpp) and the
// series of XPIC and FMPM (xpic.cpp). Internal to the solver library.
#pragma once

#include <initializer_list>

#include "step/grid.hpp"

namespace mpmstab::detail {

inline int wrap(int i, int N) {
  return ((i % N) + N) % N;
}

// Periodic images (grid.hpp): slot -1 and every padding slot from node N on, in that order.
template <class Visit>
void for_each_image(const Grid& G, Visit&& visit) {
  visit(-1);
  for (int i = G.cells; i < G.slots() - Grid::kOffset; ++i)
    visit(i);
}

// Adds each image slot into its node and clears the slot: folding twice adds nothing.
inline void fold_images(const Grid& G, std::initializer_list<double*> arrays) {
  constexpr int o = Grid::kOffset;
  for_each_image(G, [&](int i) {
    for (double* arr : arrays) {
      arr[o + wrap(i, G.cells)] += arr[o + i];
      arr[o + i] = 0.0;
    }
  });
}

inline void copy_to_images(const Grid& G, std::initializer_list<double*> arrays) {
  constexpr int o = Grid::kOffset;
  for_each_image(G, [&](int i) {
    for (double* arr : arrays)
      arr[o + i] = arr[o + wrap(i, G.cells)];
  });
}

// Runs update(lo, hi) on the slots [lo, hi) of free nodes and fixed(lo, hi) on the others: the
// Dirichlet walls, the padding slots (dropped with walls = clip) and the periodic images (copied
// from their nodes after).
template <class Update, class Fixed>
void on_node_ranges(const Grid& G, Update&& update, Fixed&& fixed) {
  constexpr int o = Grid::kOffset;
  const int N = G.cells;
  if (G.bc == Boundary::periodic) {  // nodes 0 .. N-1; the images are copied after
    fixed(0, o);
    update(o, o + N);
    fixed(o + N, G.slots());
  } else if (!G.ghost_nodes()) {  // nodes 1 .. N-1; the walls 0 and N and the padding fixed
    fixed(0, o + 1);
    update(o + 1, o + N);
    fixed(o + N, G.slots());
  } else {
    // Ghost nodes -1 and N + 1 are free too. Fixing them as well would give the same results
    // as clip: what p2g puts on a node acts only through that node's a_i and v_i, which would
    // be zero.
    update(o - 1, o);
    fixed(o, o + 1);
    update(o + 1, o + N);
    fixed(o + N, o + N + 1);
    update(o + N + 1, o + N + 2);
    fixed(o + N + 2, G.slots());
  }
}

// out_s = num_s / m_s where m_s > 0, else 0, on slots [lo, hi) (phases.cpp: vectorized for each
// instruction set; the quotients where m_s = 0 are computed and dropped). `out` may be `num`.
void divide_where_mass(const double* m, const double* num, double* out, int lo, int hi);

// out_i = num_i / m_i on free nodes with mass, 0 on the others and on fixed slots; periodic images
// copied from their nodes. `num` and the masses must be folded already; `out` may be `num`.
inline void divide_by_mass(const Grid& G, const double* num, double* out) {
  const double* m = G.mass.data();
  on_node_ranges(
      G, [&](int lo, int hi) { divide_where_mass(m, num, out, lo, hi); },
      [&](int lo, int hi) {
        for (int s = lo; s < hi; ++s)
          out[s] = 0.0;
      });
  if (G.bc == Boundary::periodic) copy_to_images(G, {out});
}

// on_node_ranges with v = a = 0 on the fixed slots.
template <class Update>
void on_free_nodes(Grid& G, Update&& update) {
  double* v = G.velocity.data();
  double* a = G.accel.data();
  on_node_ranges(G, update, [&](int lo, int hi) {
    for (int s = lo; s < hi; ++s)
      v[s] = a[s] = 0.0;
  });
}

// The storage slot of the node next to the node in slot `s`, on its left (d = -1) or right
// (d = +1): on a periodic grid nodes N - 1 and 0 are neighbours across the seam (the image slots
// are zero between fold_images and copy_to_images, so a neighbour is always read at its node);
// otherwise the next slot, -1 past the storage.
inline int neighbour_slot(const Grid& G, int s, int d) {
  constexpr int o = Grid::kOffset;
  if (G.bc == Boundary::periodic) return o + wrap(s - o + d, G.cells);
  const int n = s + d;
  return n >= 0 && n < G.slots() ? n : -1;
}

// Grid::extend_to_empty: each free node without mass beside a node with mass takes that node's
// values of `arrays` (its left neighbour's first), from the values before any was copied.
inline void extend_to_empty_nodes(const Grid& G, std::initializer_list<double*> arrays) {
  const double* m = G.mass.data();
  on_node_ranges(
      G,
      [&](int lo, int hi) {
        for (int s = lo; s < hi; ++s) {
          if (m[s] > 0.0) continue;
          int from = -1;
          for (const int d : {-1, +1}) {
            const int n = neighbour_slot(G, s, d);
            if (n >= 0 && m[n] > 0.0) {
              from = n;
              break;
            }
          }
          if (from < 0) continue;
          for (double* arr : arrays)
            arr[s] = arr[from];
        }
      },
      [](int, int) {});
}

}  // namespace mpmstab::detail
