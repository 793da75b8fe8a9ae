// Shape functions: partition of unity, gradients, the five uGIMP branches, continuity, and
// cpGIMP's supports that follow F.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "step/shape.hpp"

namespace mpmstab {
namespace {

// Weight and gradient of node `node` (at X = node * h) for a particle at x, 0 if not touched.
template <class Basis>
std::pair<double, double> weight_of(const Basis& basis, double x, int node) {
  int base;
  double w[Basis::width], g[Basis::width];
  basis.eval(x, base, w, g);
  const int k = node - base;
  if (k < 0 || k >= Basis::width) return {0.0, 0.0};
  return {w[k], g[k]};
}

// The piecewise uGIMP formula of Bardenhagen & Kober (2004), as printed in Steffen et al.
// (2008), in r = x_p - X_i: an oracle written independently of GimpBasis.
std::pair<double, double> gimp_reference(double r, double h, double lp) {
  if (r <= -h - lp || r >= h + lp) return {0.0, 0.0};
  if (r <= -h + lp)
    return {(h + lp + r) * (h + lp + r) / (4 * h * lp), (h + lp + r) / (2 * h * lp)};
  if (r <= -lp) return {1 + r / h, 1 / h};
  if (r <= lp) return {1 - (r * r + lp * lp) / (2 * h * lp), -r / (h * lp)};
  if (r <= h - lp) return {1 - r / h, -1 / h};
  return {(h + lp - r) * (h + lp - r) / (4 * h * lp), -(h + lp - r) / (2 * h * lp)};
}

// Positions in [0, 1]: a fine sweep plus every node and cell edge and their neighbours.
std::vector<double> probe_positions(double h) {
  std::vector<double> xs;
  for (int i = 0; i <= 1000; ++i)
    xs.push_back(i / 1000.0);
  for (double X = 0; X <= 1.0 + 1e-12; X += h) {
    for (double d : {0.0, 1e-14, -1e-14, 1e-9, -1e-9}) {
      if (X + d >= 0 && X + d <= 1) xs.push_back(X + d);
    }
  }
  return xs;
}

template <class Basis>
void expect_partition_of_unity(const Basis& basis, double h) {
  for (double x : probe_positions(h)) {
    int base;
    double w[Basis::width], g[Basis::width];
    basis.eval(x, base, w, g);
    double sum_w = 0, sum_g = 0;
    for (int k = 0; k < Basis::width; ++k) {
      EXPECT_GE(w[k], -1e-15) << "x = " << x;
      sum_w += w[k];
      sum_g += g[k];
    }
    EXPECT_NEAR(sum_w, 1.0, 1e-14) << "x = " << x;
    EXPECT_NEAR(sum_g * h, 0.0, 1e-13) << "x = " << x;
  }
}

TEST(LinearBasis, PartitionOfUnityAndZeroGradientSum) {
  for (int cells : {1, 7, 100}) {
    const double h = 1.0 / cells;
    expect_partition_of_unity(LinearBasis(h), h);
  }
}

TEST(LinearBasis, HandValues) {
  const LinearBasis basis(0.1);
  // x = 0.325: cell 3, xi = 0.25; node 3 weight 0.75, node 4 weight 0.25; gradients -+10.
  auto [w3, g3] = weight_of(basis, 0.325, 3);
  auto [w4, g4] = weight_of(basis, 0.325, 4);
  EXPECT_NEAR(w3, 0.75, 1e-14);
  EXPECT_NEAR(w4, 0.25, 1e-14);
  EXPECT_NEAR(g3, -10.0, 1e-12);
  EXPECT_NEAR(g4, 10.0, 1e-12);
  // Exactly on node 5: weight 1 there, 0 at the neighbours.
  EXPECT_NEAR(weight_of(basis, 0.5, 5).first, 1.0, 1e-14);
  EXPECT_NEAR(weight_of(basis, 0.5, 6).first, 0.0, 1e-14);
  EXPECT_EQ(weight_of(basis, 0.5, 4).first, 0.0);
}

TEST(GimpBasis, PartitionOfUnityAndZeroGradientSumForEveryParticleWidth) {
  for (int cells : {1, 10, 100}) {
    for (int ppc : {1, 2, 3, 4, 8}) {
      const double h = 1.0 / cells;
      SCOPED_TRACE("cells " + std::to_string(cells) + " ppc " + std::to_string(ppc));
      expect_partition_of_unity(GimpBasis(h, h / (2 * ppc)), h);
    }
  }
}

// h = 1, lp = 1/4, node 2 at X = 2: one position in each of the five non-zero branches and one
// outside, worked by hand from the piecewise formula.
TEST(GimpBasis, HandValuesInEachBranch) {
  const GimpBasis basis(1.0, 0.25);
  struct Case {
    double r, weight, gradient;
  };
  const Case cases[] = {
      {-1.10, 0.0225, 0.3},  // (h + lp + r)^2 / (4 h lp) = 0.15^2 / 1;  0.3 / 1
      {-0.50, 0.5, 1.0},     // 1 + r / h;  1 / h
      {0.10, 0.855, -0.4},   // 1 - (r^2 + lp^2) / (2 h lp) = 1 - 0.0725 / 0.5;  -r / (h lp)
      {0.60, 0.4, -1.0},     // 1 - r / h;  -1 / h
      {0.90, 0.1225, -0.7},  // (h + lp - r)^2 / (4 h lp) = 0.35^2;  -0.7 / 1
      {1.30, 0.0, 0.0},      // beyond h + lp
  };
  for (const auto& c : cases) {
    const auto [w, g] = weight_of(basis, 2.0 + c.r, 2);
    EXPECT_NEAR(w, c.weight, 1e-14) << "r = " << c.r;
    EXPECT_NEAR(g, c.gradient, 1e-13) << "r = " << c.r;
  }
}

TEST(GimpBasis, AgreesWithThePiecewiseFormulaEverywhere) {
  for (int ppc : {1, 2, 4}) {
    const double h = 0.1, lp = h / (2 * ppc);
    const GimpBasis basis(h, lp);
    for (double x : probe_positions(h)) {
      for (int node = 0; node <= 10; ++node) {
        const auto [w, g] = weight_of(basis, x, node);
        const auto [w_ref, g_ref] = gimp_reference(x - node * h, h, lp);
        EXPECT_NEAR(w, w_ref, 1e-13) << "x = " << x << " node " << node << " ppc " << ppc;
        EXPECT_NEAR(g * h, g_ref * h, 1e-11) << "x = " << x << " node " << node << " ppc " << ppc;
      }
    }
  }
}

TEST(GimpBasis, WeightsAndGradientsAreContinuousAcrossBranchBoundaries) {
  const double h = 0.1, lp = 0.025;
  const GimpBasis basis(h, lp);
  const double X = 0.5;  // node 5
  const double eps = 1e-9;
  for (double rb : {-h - lp, -h + lp, -lp, lp, h - lp, h + lp}) {
    const auto [w_left, g_left] = weight_of(basis, X + rb - eps, 5);
    const auto [w_right, g_right] = weight_of(basis, X + rb + eps, 5);
    // |dS/dx| <= 1/h, so S moves by at most 2 eps / h across the boundary.
    EXPECT_LE(std::abs(w_right - w_left), 2 * eps / h + 1e-14) << "boundary r = " << rb;
    // uGIMP is C1: G moves by at most 2 eps * max|S''| = 2 eps / (h lp).
    EXPECT_LE(std::abs(g_right - g_left), 2 * eps / (h * lp) + 1e-9) << "boundary r = " << rb;
  }
}

TEST(GimpBasis, TouchesAtMostThreeNodesAndNothingBeyond) {
  const double h = 0.1;
  for (int ppc : {1, 2, 8}) {
    const GimpBasis basis(h, h / (2 * ppc));
    for (double x : probe_positions(h)) {
      int base;
      double w[3], g[3];
      basis.eval(x, base, w, g);
      // Nodes outside base..base+2 carry no weight by the reference formula (up to the
      // rounding of r at the very edge of the support, where the weight is ~1e-31).
      for (int node = -2; node <= 12; ++node) {
        if (node >= base && node <= base + 2) continue;
        EXPECT_LE(gimp_reference(x - node * h, h, h / (2 * ppc)).first, 1e-20)
            << "x = " << x << " node " << node;
      }
    }
  }
}

// cpGIMP at a fixed F, with the eval signature of the other bases.
struct CpGimpAt {
  static constexpr int width = CpGimpBasis::width;
  CpGimpBasis basis;
  double F;
  void eval(double x, int& base, double* w, double* g) const { basis.eval(x, F, base, w, g); }
};

// An oracle for any half-width: S_i = (H(x + lp) - H(x - lp)) / 2lp with H the antiderivative of
// the hat N_i, G_i = (N_i(x + lp) - N_i(x - lp)) / 2lp, in r = (y - X_i) / h.
std::pair<double, double> average_of_hat(double x, double X_i, double h, double lp) {
  auto hat = [&](double y) { return std::max(0.0, 1.0 - std::abs(y - X_i) / h); };
  auto antiderivative = [&](double y) {
    const double r = (y - X_i) / h;
    if (r <= -1) return 0.0;
    if (r <= 0) return h * (1 + r) * (1 + r) / 2;
    if (r <= 1) return h * (1 - (1 - r) * (1 - r) / 2);
    return h;
  };
  return {(antiderivative(x + lp) - antiderivative(x - lp)) / (2 * lp),
          (hat(x + lp) - hat(x - lp)) / (2 * lp)};
}

// F from compressed to the widest admissible support (lp = h at F = 2 m).
constexpr double kStretches[] = {0.3, 0.9, 1.0, 1.7, 2.0, 2.6, 3.3, 4.0};

TEST(CpGimpBasis, PartitionOfUnityAndZeroGradientSumForEveryStretch) {
  const int ppc = 2;
  for (int cells : {1, 10, 100}) {
    const double h = 1.0 / cells;
    for (double F : kStretches) {
      SCOPED_TRACE("cells " + std::to_string(cells) + " F " + std::to_string(F));
      expect_partition_of_unity(CpGimpAt{CpGimpBasis(h, h / (2 * ppc)), F}, h);
    }
  }
}

TEST(CpGimpBasis, IsTheAverageOfTheHatOverTheStretchedParticle) {
  const double h = 0.1;
  for (int ppc : {1, 2}) {
    for (double F : kStretches) {
      if (F > 2 * ppc) continue;
      const double lp = F * h / (2 * ppc);
      const CpGimpAt basis{CpGimpBasis(h, h / (2 * ppc)), F};
      for (double x : probe_positions(h)) {
        for (int node = -1; node <= 11; ++node) {
          const auto [w, g] = weight_of(basis, x, node);
          const auto [w_ref, g_ref] = average_of_hat(x, node * h, h, lp);
          EXPECT_NEAR(w, w_ref, 1e-13) << "x = " << x << " node " << node << " F " << F;
          EXPECT_NEAR(g * h, g_ref * h, 1e-11) << "x = " << x << " node " << node << " F " << F;
        }
      }
    }
  }
}

TEST(CpGimpBasis, SupportWidensWithF) {
  // A particle at x = 0.5 + h / 8 (h = 0.1, m = 1): the nodes with a non-zero weight.
  const double h = 0.1, x = 0.5125;
  int previous = 0;
  for (double F : kStretches) {
    if (F > 2) continue;
    const CpGimpAt basis{CpGimpBasis(h, h / 2), F};
    int touched = 0;
    for (int node = 0; node <= 10; ++node)
      touched += weight_of(basis, x, node).first > 1e-12;
    EXPECT_GE(touched, previous) << "F = " << F;
    previous = touched;
  }
  // F = 0.3: [0.4975, 0.5275] meets the hats of nodes 4, 5, 6; F = 2 (lp = h):
  // [0.4125, 0.6125] meets those of nodes 4 to 7.
  EXPECT_EQ(previous, 4);
}

TEST(CpGimpBasis, UndeformedIsUGimpToRounding) {
  const double h = 0.1;
  for (int ppc : {1, 2, 4}) {
    const GimpBasis gimp(h, h / (2 * ppc));
    const CpGimpAt cpgimp{CpGimpBasis(h, h / (2 * ppc)), 1.0};
    for (double x : probe_positions(h)) {
      int base_g, base_c;
      double wg[3], gg[3], wc[4], gc[4];
      gimp.eval(x, base_g, wg, gg);
      cpgimp.eval(x, base_c, wc, gc);
      ASSERT_EQ(base_c, base_g) << x;
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(wc[k], wg[k], 1e-14) << "x = " << x << " k " << k;
        EXPECT_NEAR(gc[k] * h, gg[k] * h, 1e-12) << "x = " << x << " k " << k;
      }
      EXPECT_EQ(wc[3], 0.0) << x;
      EXPECT_EQ(gc[3], 0.0) << x;
    }
  }
}

TEST(FloorToInt, MatchesFloor) {
  for (double s : {-2.5, -1.0, -0.5, -1e-300, 0.0, 0.5, 1.0, 99.999999, 100.0}) {
    EXPECT_EQ(floor_to_int(s), static_cast<int>(std::floor(s))) << s;
  }
}

// The periodic wrap must give the bits std::floor gives, sign of zero included, everywhere: at
// the edges of the exact range (2^51, 2^52), past it, at +-0, inf and NaN, and at random values.
TEST(FractionalPart, IsXMinusFloorXBitForBit) {
  const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
  std::vector<double> xs = {0.0,  -0.0,           1e-300,          -1e-300, 0.5,   -0.5,       1.0,
                            -1.0, 0.999999999999, -0.999999999999, 99.5,    -99.5, 1.0 - 1e-16};
  for (double e : {0x1p51, 0x1p52, 0x1p53, 1e300}) {
    for (double d : {-1.5, -1.0, -0.5, 0.0, 0.5, 1.0, 1.5}) {
      xs.push_back(e + d);
      xs.push_back(-(e + d));
    }
  }
  xs.push_back(std::numeric_limits<double>::infinity());
  xs.push_back(-std::numeric_limits<double>::infinity());
  xs.push_back(std::numeric_limits<double>::quiet_NaN());
  xs.push_back(std::numeric_limits<double>::denorm_min());
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  std::uniform_int_distribution<int> scale(-60, 60);
  for (int i = 0; i < 20000; ++i)
    xs.push_back(std::ldexp(u(rng), scale(rng)));
  for (double x : xs) {
    const double expected = x - std::floor(x);
    EXPECT_EQ(bits(fractional_part(x)), bits(expected)) << x;
  }
}

}  // namespace
}  // namespace mpmstab
