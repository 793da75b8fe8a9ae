// Shape functions: the linear hat ("mpm"), uGIMP ("gimp", Bardenhagen & Kober 2004), cpGIMP
// ("cpgimp", the uGIMP average over a particle domain that follows the deformation), CPDI
// ("cpdi", the corner interpolation of Sadeghirad et al. 2011 over that domain) and the
// uniform quadratic and cubic B-splines ("bspline2", "bspline3"; Steffen, Kirby & Berzins 2008).
//
// Each basis evaluates, for one particle at x, the first node `base` it touches and the weights
// S_ip and gradients G_ip = dS_ip/dx_p of the `width` consecutive nodes base, base+1, ...
// These are the only definitions of S and G: p2g, g2p and the stress update all read them.
#pragma once

#include <cmath>

#include "base/simd.hpp"

namespace mpmstab {

// floor(s) as a double, exactly, for |s| < 2^51. With SSE4.1 (every x86-64-v2 CPU and up, so
// every kernel version) or on ARM, std::floor: one rounding instruction, vectorized because the
// build has -fno-trapping-math. Elsewhere, adding and subtracting 1.5 * 2^52 rounds s to the
// nearest integer (both operations stay: FMA contraction is off and fast-math is not used), one
// step down if that is above s: no libm call, so it vectorizes too. The two agree on every s
// but -0.0 (std::floor keeps its sign, the sum gives +0.0): a cell index, and u = s - floor(s)
// for the bases' s = x / h - lp with lp > 0 or x >= 0 not -0.0, are the same either way.
inline double floor_exact(double s) {
#if defined(__SSE4_1__) || defined(__aarch64__)
  return std::floor(s);
#else
  constexpr double kRound = 6755399441055744.0;  // 1.5 * 2^52
  const double r = (s + kRound) - kRound;
  return r > s ? r - 1.0 : r;
#endif
}

// x - floor(x), bit for bit as with std::floor, for every x (the periodic wrap of a position).
// std::floor's loop does not vectorize without -fno-trapping-math; this one does. Adding and
// subtracting 2^52 with x's sign rounds x to an integer exactly for |x| < 2^52; from 2^52 up
// (and for inf and NaN) x is its own floor. The + 0.0 turns the -0.0 that x = -0.0 gives here
// into the +0.0 that -0.0 - floor(-0.0) gives; it leaves every other value as it is.
inline double fractional_part(double x) {
  const double k = std::copysign(4503599627370496.0, x);  // 2^52
  const double r = (x + k) - k;
  const double below = r > x ? r - 1.0 : r;
  const double fl = std::abs(x) < 4503599627370496.0 ? below : x;
  return (x - fl) + 0.0;
}

// floor(s) as an int, for s well inside int range.
inline int floor_to_int(double s) {
  return static_cast<int>(floor_exact(s));
}

// max(d, 0), one select (maxpd on x86): d, or +0.0 where d < 0; NaN stays NaN. Bit for bit the
// (d + |d|) / 2 it replaces for every d but -0.0, which no caller's difference of two values
// gives (a - b is -0.0 only for a = -0.0, b = +0.0).
inline double positive_part(double d) {
  return d < 0.0 ? 0.0 : d;
}

// Linear hat N_i(x) = max(0, 1 - |x - X_i| / h): two nodes per particle (the standard MPM of the
// paper's section 2 with delta-function particles).
struct LinearBasis {
  static constexpr int width = 2;
  double inv_h;

  explicit LinearBasis(double h) : inv_h(1.0 / h) {}

  MPMSTAB_INLINE void eval(double x, int& base, double* w, double* g) const {
    const double s = x * inv_h;
    const double cell = floor_exact(s);
    base = static_cast<int>(cell);
    const double xi = s - cell;
    w[0] = 1.0 - xi;
    w[1] = xi;
    g[0] = -inv_h;
    g[1] = inv_h;
  }
};

// uGIMP: S_ip is the average of the hat N_i over the particle's support [x - lp, x + lp],
//   S_ip = (1 / 2lp) * integral_{x-lp}^{x+lp} N_i(y) dy,
//   G_ip = (N_i(x + lp) - N_i(x - lp)) / 2lp.
// This is the piecewise formula of Bardenhagen & Kober (five branches in r = x - X_i) written as
// an integral, evaluated without branches. With lp <= h / 2 a particle touches at most three
// nodes: base = floor((x - lp) / h), base + 1, base + 2.
struct GimpBasis {
  static constexpr int width = 3;
  double inv_h;
  double w;         // support width 2 lp in cell units
  double inv_w;     // 1 / w
  double inv_2lp;   // 1 / (2 lp)
  double lp_cells;  // lp in cell units

  GimpBasis(double h, double lp)
      : inv_h(1.0 / h),
        w(2.0 * lp / h),
        inv_w(h / (2.0 * lp)),
        inv_2lp(1.0 / (2.0 * lp)),
        lp_cells(lp / h) {}

  MPMSTAB_INLINE void eval(double x, int& base, double* wt, double* g) const {
    // Left edge of the support in cell units, relative to node `base`: u in [0, 1).
    const double s = x * inv_h - lp_cells;
    const double cell = floor_exact(s);
    base = static_cast<int>(cell);
    const double u = s - cell;
    const double b = u + w;                   // right edge, in [w, 1 + w)
    const double e = positive_part(b - 1.0);  // length of the part in cell [base+1, base+2]
    const double b0 = b - e;                  // right end of the part in cell [base, base+1]
    // integral over [u, b0] of (1 - y) and of y; integral over [0, e] of (1 - y) and of y.
    const double right0 = 0.5 * (b0 * b0 - u * u);
    const double right1 = 0.5 * e * e;
    wt[0] = ((b0 - u) - right0) * inv_w;
    wt[1] = (right0 + e - right1) * inv_w;
    wt[2] = right1 * inv_w;
    // N at the right edge minus N at the left edge, per node.
    g[0] = (positive_part(1.0 - b) - (1.0 - u)) * inv_2lp;
    g[1] = (b0 - e - u) * inv_2lp;
    g[2] = e * inv_2lp;
  }
};

// cpGIMP in 1D: the uGIMP average of the hat over [x - lp, x + lp] with the particle's current
// half-width lp_p = F_p lp0, lp0 = h / (2 m): the particle domain stretches with F_p (in 1D the
// deformed domain of a particle is exactly its reference domain times F_p). The formulas are
// GimpBasis's, carried over up to three cells:
//   S_ip = (1 / 2lp) * integral_{x-lp}^{x+lp} N_i(y) dy,
//   G_ip = (N_i(x + lp) - N_i(x - lp)) / 2lp.
// Valid while 2 lp <= 2 h (F_p <= 2 m): the support then covers at most four nodes,
// base = floor((x - lp) / h) .. base + 3. A wider particle is a failure of the run (failure.hpp,
// support_too_wide). With lp = lp0 the values are GimpBasis's up to rounding, and S = G = 0 on
// node base + 3.
struct CpGimpBasis {
  static constexpr int width = 4;
  double inv_h;
  double lp0_cells;  // reference half-width lp0 = h / (2 m) in cell units

  CpGimpBasis(double h, double lp0) : inv_h(1.0 / h), lp0_cells(lp0 / h) {}

  MPMSTAB_INLINE void eval(double x, double F, int& base, double* wt, double* g) const {
    const double lp_cells = F * lp0_cells;
    const double w = 2.0 * lp_cells;  // support width in cell units, <= 2
    const double inv_w = 1.0 / w;
    const double inv_2lp = inv_w * inv_h;
    // Left edge u in [0, 1) relative to node `base`, right edge b = u + w in [w, 3). The
    // support's parts in cells [base, base+1], [base+1, base+2] and [base+2, base+3] are
    // [u, b0], [0, e1] and [0, e2] in local coordinates.
    const double s = x * inv_h - lp_cells;
    const double cell = floor_exact(s);
    base = static_cast<int>(cell);
    const double u = s - cell;
    const double b = u + w;
    const double e2 = positive_part(b - 2.0);
    const double e1 = positive_part(b - 1.0 - e2);
    const double b0 = b - e1 - e2;
    // In each cell, the integrals of (1 - y) and of y over the part.
    const double right0 = 0.5 * (b0 * b0 - u * u);
    const double right1 = 0.5 * e1 * e1;
    const double right2 = 0.5 * e2 * e2;
    wt[0] = ((b0 - u) - right0) * inv_w;
    wt[1] = (right0 + e1 - right1) * inv_w;
    wt[2] = (right1 + e2 - right2) * inv_w;
    wt[3] = right2 * inv_w;
    // N at the right edge minus N at the left edge, per node.
    g[0] = (positive_part(1.0 - b) - (1.0 - u)) * inv_2lp;
    g[1] = (b0 - e1 - u) * inv_2lp;
    g[2] = (e1 - e2) * inv_2lp;
    g[3] = e2 * inv_2lp;
  }
};

// Ghost-node elimination at a Dirichlet wall, for bases wider than a cell: a B-spline of a
// particle next to the wall X = 0 touches the node X_{-1} = -h beyond it (and, at X = 1, the node
// X_{N+1} = 1 + h). That node is not a degree of freedom: its value is extrapolated linearly from
// the first two nodes inside, c_{-1} = 2 c_0 - c_1 (c_{N+1} = 2 c_N - c_{N-1}), so its weight is
// moved onto them: S_0 += 2 S_{-1}, S_1 -= S_{-1}, and the same for the gradients. This keeps
// partition of unity and the reproduction of linear fields, and with the wall's velocity fixed at
// 0 it makes the ghost velocity the odd reflection -c_1. (Plain truncation, dropping S_{-1},
// would lose partition of unity.) The weight folded in can make S_1 negative next to a wall.
// base (the first node touched) and cells are whole numbers held as doubles: compared as doubles,
// they give masks of the doubles' width, and a loop over particles that calls this vectorizes.
template <int W>
MPMSTAB_INLINE void eliminate_ghost_nodes(double base, double cells, double* w_io, double* g_io) {
  double w[W], g[W];
  for (int k = 0; k < W; ++k) {
    w[k] = w_io[k];
    g[k] = g_io[k];
  }
  // Left: only node -1 can be beyond the wall, at slot 0 when base == -1.
  const double left = base == -1.0 ? 1.0 : 0.0;
  const double wl = left * w[0], gl = left * g[0];
  w[0] -= wl;
  w[1] += 2.0 * wl;
  w[2] -= wl;
  g[0] -= gl;
  g[1] += 2.0 * gl;
  g[2] -= gl;
  // Right: node N + 1, at slot k = N + 1 - base (2 <= k < W when touched).
  for (int k = 2; k < W; ++k) {
    const double right = base + k == cells + 1.0 ? 1.0 : 0.0;
    const double wr = right * w[k], gr = right * g[k];
    w[k] -= wr;
    w[k - 1] += 2.0 * wr;
    w[k - 2] -= wr;
    g[k] -= gr;
    g[k - 1] += 2.0 * gr;
    g[k - 2] -= gr;
  }
  for (int k = 0; k < W; ++k) {
    w_io[k] = w[k];
    g_io[k] = g[k];
  }
}

// How a B-spline basis meets a Dirichlet wall (params.hpp, walls):
//  - none:      periodic grid, no wall;
//  - eliminate: the uniform splines, with the ghost node beyond each wall eliminated by linear
//               extrapolation (eliminate_ghost_nodes; walls = clip);
//  - modified:  the boundary-modified splines of Steffen, Kirby and Berzins (2008) (walls =
//               modified): the B-splines of the open knot vector that repeats the wall's knot
//               p + 1 times, the first two of them merged into the wall node's function, so
//               that each node keeps one function (BSpline2Wall, BSpline3Wall). Partition of
//               unity holds, every function but the wall node's vanishes on the wall, and every
//               derivative vanishes there; linear fields are not reproduced in the first cells
//               (sum_i X_i S_ip != x_p there), which the tests show.
enum class SplineWalls { none, eliminate, modified };

// The modified functions of the two nodes next to the left wall X_0 = 0, as functions of
// xi = (x - X_i) / h; value and d/dxi. The right wall uses them mirrored.
struct BSpline2Wall {
  // Node 0: 4/3 of the uniform quadratic spline on [0, 3/2).
  static void node0(double xi, double& w, double& d) {
    if (xi < 0.5) {
      w = (3.0 - 4.0 * xi * xi) / 3.0;
      d = -8.0 * xi / 3.0;
    } else if (xi < 1.5) {
      const double r = 3.0 - 2.0 * xi;
      w = r * r / 6.0;
      d = -2.0 * r / 3.0;
    } else {
      w = d = 0.0;
    }
  }
  // Node 1, on [-1, 3/2).
  static void node1(double xi, double& w, double& d) {
    if (xi < -1.0) {
      w = d = 0.0;
    } else if (xi < -0.5) {
      const double r = 1.0 + xi;
      w = 4.0 * r * r / 3.0;
      d = 8.0 * r / 3.0;
    } else if (xi < 0.5) {
      w = (17.0 + 4.0 * xi - 28.0 * xi * xi) / 24.0;
      d = (4.0 - 56.0 * xi) / 24.0;
    } else if (xi < 1.5) {
      const double r = 3.0 - 2.0 * xi;
      w = r * r / 8.0;
      d = -r / 2.0;
    } else {
      w = d = 0.0;
    }
  }
};

struct BSpline3Wall {
  // Node 0: 3/2 of the uniform cubic spline on [0, 2).
  static void node0(double xi, double& w, double& d) {
    if (xi < 1.0) {
      w = (3.0 * xi * xi * xi - 6.0 * xi * xi + 4.0) / 4.0;
      d = (9.0 * xi * xi - 12.0 * xi) / 4.0;
    } else if (xi < 2.0) {
      const double r = 2.0 - xi;
      w = r * r * r / 4.0;
      d = -3.0 * r * r / 4.0;
    } else {
      w = d = 0.0;
    }
  }
  // Node 1, on [-1, 2).
  static void node1(double xi, double& w, double& d) {
    if (xi < -1.0) {
      w = d = 0.0;
    } else if (xi < 0.0) {
      const double r = 1.0 + xi;
      w = r * r * (7.0 - 11.0 * xi) / 12.0;
      d = r * (3.0 - 33.0 * xi) / 12.0;
    } else if (xi < 1.0) {
      w = (7.0 * xi * xi * xi - 15.0 * xi * xi + 3.0 * xi + 7.0) / 12.0;
      d = (21.0 * xi * xi - 30.0 * xi + 3.0) / 12.0;
    } else if (xi < 2.0) {
      const double r = 2.0 - xi;
      w = r * r * r / 6.0;
      d = -r * r / 2.0;
    } else {
      w = d = 0.0;
    }
  }
};

// Replaces the uniform values of the nodes next to each wall by the modified functions of Wall:
// nodes 0 and 1 (N and N - 1, mirrored) get Wall's functions, nodes beyond the walls get 0. The
// nodes from 2 to N - 2 keep the uniform spline (needs cells >= 4, which validate() asks).
template <class Wall, int W>
inline void modify_at_walls(double x, double inv_h, int base, int cells, double* w, double* g) {
  if (base >= 2 && base + W - 1 <= cells - 2) return;  // no node next to a wall
  const double s = x * inv_h;
  for (int k = 0; k < W; ++k) {
    const int i = base + k;
    double value = 0.0, slope = 0.0;
    if (i < 0 || i > cells) {
      w[k] = g[k] = 0.0;
      continue;
    }
    if (i == 0) {
      Wall::node0(s, value, slope);
    } else if (i == 1) {
      Wall::node1(s - 1.0, value, slope);
    } else if (i == cells) {
      Wall::node0(cells - s, value, slope);
      slope = -slope;
    } else if (i == cells - 1) {
      Wall::node1(cells - 1 - s, value, slope);
      slope = -slope;
    } else {
      continue;  // uniform
    }
    w[k] = value;
    g[k] = slope * inv_h;
  }
}

// p2g evaluates a B-spline in two parts (p2g_kernel.hpp): eval_vector<kEliminate>, the uniform
// splines, with the ghost nodes eliminated when kEliminate (walls == eliminate, chosen once per
// loop rather than per particle, so that the loop over particles is free of control flow and
// vectorizes); then, with modified walls only, modify() on the particles next to a wall, one at a
// time. eval() is the two together.

// Uniform quadratic B-spline, N(r) in units of h (as in Steffen, Kirby & Berzins 2008):
//   N = 3/4 - r^2 for |r| <= 1/2,  (3/2 - |r|)^2 / 2 for 1/2 <= |r| <= 3/2,  0 beyond.
// C1 across cells; a particle touches three nodes, base = floor(x / h - 1/2). With t the
// particle's position from node base + 1/2 in cell units, t in [0, 1):
//   S = ((1 - t)^2 / 2, 3/4 - (t - 1/2)^2, t^2 / 2),  G = (t - 1, 1 - 2t, t) / h.
// With Dirichlet walls the ghost node beyond each wall is eliminated (eliminate_ghost_nodes) or
// the splines are the boundary-modified ones (BSpline2Wall).
struct BSpline2Basis {
  static constexpr int width = 3;
  double inv_h;
  int cells;
  SplineWalls walls;
  bool eliminate;  // walls == eliminate

  BSpline2Basis(double h, int n_cells, SplineWalls wall_kind)
      : inv_h(1.0 / h),
        cells(n_cells),
        walls(wall_kind),
        eliminate(wall_kind == SplineWalls::eliminate) {}
  // Dirichlet: eliminate the ghost nodes.
  BSpline2Basis(double h, int n_cells, bool dirichlet)
      : BSpline2Basis(h, n_cells, dirichlet ? SplineWalls::eliminate : SplineWalls::none) {}

  MPMSTAB_INLINE void eval(double x, int& base, double* w, double* g) const {
    eliminate ? eval_vector<true>(x, base, w, g) : eval_vector<false>(x, base, w, g);
    if (modifies()) modify(x, base, w, g);
  }
  template <bool kEliminate>
  MPMSTAB_INLINE void eval_vector(double x, int& base, double* w, double* g) const {
    const double s = x * inv_h - 0.5;
    const double cell = floor_exact(s);
    base = static_cast<int>(cell);
    const double t = s - cell;
    const double c = t - 0.5;
    w[0] = 0.5 * (1.0 - t) * (1.0 - t);
    w[1] = 0.75 - c * c;
    w[2] = 0.5 * t * t;
    g[0] = (t - 1.0) * inv_h;
    g[1] = -2.0 * c * inv_h;
    g[2] = t * inv_h;
    if constexpr (kEliminate) eliminate_ghost_nodes<width>(cell, cells, w, g);
  }
  bool modifies() const { return walls == SplineWalls::modified; }
  void modify(double x, int base, double* w, double* g) const {
    modify_at_walls<BSpline2Wall, width>(x, inv_h, base, cells, w, g);
  }
};

// Uniform cubic B-spline, N(r) in units of h (as in Steffen, Kirby & Berzins 2008):
//   N = 2/3 - r^2 + |r|^3 / 2 for |r| <= 1,  (2 - |r|)^3 / 6 for 1 <= |r| <= 2,  0 beyond.
// C2 across cells; a particle touches four nodes, base = floor(x / h) - 1. With t the position
// in its cell, t in [0, 1):
//   S = ((1 - t)^3, 3t^3 - 6t^2 + 4, -3t^3 + 3t^2 + 3t + 1, t^3) / 6,
//   G = (-(1 - t)^2, 3t^2 - 4t, -3t^2 + 2t + 1, t^2) / (2h).
// With Dirichlet walls the ghost node beyond each wall is eliminated (eliminate_ghost_nodes) or
// the splines are the boundary-modified ones (BSpline3Wall); a particle exactly on the wall
// X = 1 also touches node N + 2, with weight 0.
struct BSpline3Basis {
  static constexpr int width = 4;
  double inv_h;
  int cells;
  SplineWalls walls;
  bool eliminate;  // walls == eliminate

  BSpline3Basis(double h, int n_cells, SplineWalls wall_kind)
      : inv_h(1.0 / h),
        cells(n_cells),
        walls(wall_kind),
        eliminate(wall_kind == SplineWalls::eliminate) {}
  BSpline3Basis(double h, int n_cells, bool dirichlet)
      : BSpline3Basis(h, n_cells, dirichlet ? SplineWalls::eliminate : SplineWalls::none) {}

  MPMSTAB_INLINE void eval(double x, int& base, double* w, double* g) const {
    eliminate ? eval_vector<true>(x, base, w, g) : eval_vector<false>(x, base, w, g);
    if (modifies()) modify(x, base, w, g);
  }
  template <bool kEliminate>
  MPMSTAB_INLINE void eval_vector(double x, int& base, double* w, double* g) const {
    const double s = x * inv_h;
    const double cell = floor_exact(s);
    base = static_cast<int>(cell) - 1;
    const double t = s - cell;
    const double u = 1.0 - t;
    const double t2 = t * t, t3 = t2 * t;
    constexpr double sixth = 1.0 / 6.0;
    w[0] = u * u * u * sixth;
    w[1] = (3.0 * t3 - 6.0 * t2 + 4.0) * sixth;
    w[2] = (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) * sixth;
    w[3] = t3 * sixth;
    const double half_inv_h = 0.5 * inv_h;
    g[0] = -u * u * half_inv_h;
    g[1] = (3.0 * t2 - 4.0 * t) * half_inv_h;
    g[2] = (-3.0 * t2 + 2.0 * t + 1.0) * half_inv_h;
    g[3] = t2 * half_inv_h;
    if constexpr (kEliminate) eliminate_ghost_nodes<width>(cell - 1.0, cells, w, g);
  }
  bool modifies() const { return walls == SplineWalls::modified; }
  void modify(double x, int base, double* w, double* g) const {
    modify_at_walls<BSpline3Wall, width>(x, inv_h, base, cells, w, g);
  }
};

// CPDI in 1D (Sadeghirad, Brannon and Burghardt 2011, CPDI1): the particle domain is the segment
// between its two corners x_1,2 = x -/+ lp, lp = F_p lp0 (corners carried by F_p, as cpGIMP's
// half-width), and inside it the hat N_i is replaced by its linear interpolant between the
// corners. Integrated over the domain, that gives
//   S_ip = (N_i(x_1) + N_i(x_2)) / 2,   G_ip = (N_i(x_2) - N_i(x_1)) / (x_2 - x_1).
// G is cpGIMP's exactly; S equals cpGIMP's (the exact average of N_i) while the domain lies in
// one cell, where N_i is linear, and differs when a node lies inside the domain (N_i has its
// kink there, which the interpolant cuts off). Valid, as cpGIMP, while 2 lp <= 2 h (F_p <= 2 m):
// four nodes, base = floor((x - lp) / h) .. base + 3.
struct CpdiBasis {
  static constexpr int width = 4;
  double inv_h;
  double lp0_cells;  // reference half-width lp0 = h / (2 m) in cell units

  CpdiBasis(double h, double lp0) : inv_h(1.0 / h), lp0_cells(lp0 / h) {}

  MPMSTAB_INLINE void eval(double x, double F, int& base, double* wt, double* g) const {
    const double lp_cells = F * lp0_cells;
    const double s1 = x * inv_h - lp_cells;  // corners in cell units
    const double cell = floor_exact(s1);
    base = static_cast<int>(cell);
    const double u = s1 - cell;           // corner 1, relative to node base, in [0, 1)
    const double v = u + 2.0 * lp_cells;  // corner 2, relative to node base, in [0, 3)
    const double inv_2lp = 0.5 / lp_cells * inv_h;
    for (int k = 0; k < width; ++k) {
      // The hat of node base + k at the corners: N(corner) = max(0, 1 - |corner - k|).
      const double n1 = positive_part(1.0 - std::abs(u - k));
      const double n2 = positive_part(1.0 - std::abs(v - k));
      wt[k] = 0.5 * (n1 + n2);
      g[k] = (n2 - n1) * inv_2lp;
    }
  }
};

}  // namespace mpmstab
