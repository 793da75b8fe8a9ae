// Shape functions: the linear hat ("mpm"), uGIMP ("gimp", Bardenhagen & Kober 2004) and cpGIMP
// ("cpgimp", the uGIMP average over a particle domain that follows the deformation).
//
// Each basis evaluates, for one particle at x, the first node `base` it touches and the weights
// S_ip and gradients G_ip = dS_ip/dx_p of the `width` consecutive nodes base, base+1, ...
// These are the only definitions of S and G: p2g, g2p and the stress update all read them.
#pragma once

#include <cmath>

namespace mpmstab {

// floor(s) as a double, exactly, for |s| < 2^51. Adding and subtracting 1.5 * 2^52 rounds s to
// the nearest integer (both operations stay: FMA contraction is off and fast-math is not used);
// one step down if that is above s. No libm call and no round trip through an integer register,
// so it vectorizes and its dependency chain is short.
inline double floor_exact(double s) {
  constexpr double kRound = 6755399441055744.0;  // 1.5 * 2^52
  const double r = (s + kRound) - kRound;
  return r > s ? r - 1.0 : r;
}

// floor(s) as an int, for s well inside int range.
inline int floor_to_int(double s) {
  return static_cast<int>(floor_exact(s));
}

// max(d, 0) without a branch, exactly: (d + |d|) / 2 is d or 0 with no rounding.
inline double positive_part(double d) {
  return 0.5 * (d + std::abs(d));
}

// Linear hat N_i(x) = max(0, 1 - |x - X_i| / h): two nodes per particle (the standard MPM of the
// paper's section 2 with delta-function particles).
struct LinearBasis {
  static constexpr int width = 2;
  double inv_h;

  explicit LinearBasis(double h) : inv_h(1.0 / h) {}

  void eval(double x, int& base, double* w, double* g) const {
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

  void eval(double x, int& base, double* wt, double* g) const {
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

  void eval(double x, double F, int& base, double* wt, double* g) const {
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

}  // namespace mpmstab
