// Shape functions: the linear hat ("mpm") and uGIMP ("gimp", Bardenhagen & Kober 2004).
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

}  // namespace mpmstab
