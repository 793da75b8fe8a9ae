// CPDI in 1D: partition of unity and linear reproduction for every stretch, where it equals
// cpGIMP (a domain inside one cell, and the gradients always) and where it differs (a node inside
// the domain, by a closed form), and a run of the bar.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "base/params.hpp"
#include "run/run.hpp"
#include "scenes/validate.hpp"
#include "step/shape.hpp"

namespace mpmstab {
namespace {

constexpr int kCells = 10;
constexpr double kH = 1.0 / kCells;
constexpr double kLp0 = kH / 4;  // m = 2 particles per cell

std::vector<double> interior_positions(double lp) {
  std::vector<double> xs;
  for (int i = 0; i <= 997; ++i) {
    const double x = lp + (1.0 - 2 * lp) * i / 997.0;  // the whole domain inside [0, 1]
    xs.push_back(x);
  }
  return xs;
}

TEST(Cpdi, PartitionOfUnityAndLinearReproductionForEveryStretch) {
  const CpdiBasis cpdi(kH, kLp0);
  for (const double F : {0.3, 1.0, 1.7, 2.5, 3.99}) {
    for (const double x : interior_positions(F * kLp0)) {
      int base;
      double w[4], g[4];
      cpdi.eval(x, F, base, w, g);
      double sw = 0, swx = 0, sg = 0, sgx = 0;
      for (int k = 0; k < 4; ++k) {
        EXPECT_GE(w[k], -1e-15) << "F = " << F << ", x = " << x;
        sw += w[k];
        swx += w[k] * (base + k) * kH;
        sg += g[k];
        sgx += g[k] * (base + k) * kH;
      }
      EXPECT_NEAR(sw, 1.0, 1e-14) << "F = " << F << ", x = " << x;
      EXPECT_NEAR(swx, x, 1e-14) << "F = " << F << ", x = " << x;
      EXPECT_NEAR(sg, 0.0, 1e-11) << "F = " << F << ", x = " << x;
      EXPECT_NEAR(sgx, 1.0, 1e-12) << "F = " << F << ", x = " << x;
    }
  }
}

// The gradients are cpGIMP's everywhere; the weights are cpGIMP's exactly when no node lies
// strictly inside the particle's domain (the hat is linear there), and not otherwise.
TEST(Cpdi, EqualsCpGimpWhereTheHatIsLinearOverTheDomainAndOnlyThere) {
  const CpdiBasis cpdi(kH, kLp0);
  const CpGimpBasis cpgimp(kH, kLp0);
  int equal = 0, different = 0;
  for (const double F : {0.5, 1.0, 1.9, 3.5}) {
    const double lp = F * kLp0;
    for (const double x : interior_positions(lp)) {
      int b1, b2;
      double w1[4], g1[4], w2[4], g2[4];
      cpdi.eval(x, F, b1, w1, g1);
      cpgimp.eval(x, F, b2, w2, g2);
      ASSERT_EQ(b1, b2);
      // A node strictly inside (x - lp, x + lp), with a margin for rounding?
      const double lo = (x - lp) / kH, hi = (x + lp) / kH;
      const bool node_inside = std::floor(hi - 1e-9) >= std::ceil(lo + 1e-9);
      const bool near_node =
          std::abs(lo - std::round(lo)) < 1e-9 || std::abs(hi - std::round(hi)) < 1e-9;
      double max_diff = 0;
      for (int k = 0; k < 4; ++k) {
        EXPECT_NEAR(g1[k], g2[k], 1e-9) << "F = " << F << ", x = " << x;
        max_diff = std::max(max_diff, std::abs(w1[k] - w2[k]));
      }
      if (near_node) continue;
      if (node_inside) {
        EXPECT_GT(max_diff, 1e-12) << "F = " << F << ", x = " << x;
        ++different;
      } else {
        EXPECT_LT(max_diff, 1e-14) << "F = " << F << ", x = " << x;
        ++equal;
      }
    }
  }
  EXPECT_GT(equal, 100);
  EXPECT_GT(different, 100);
}

// A domain of half-width a h centred on node i: cpGIMP's weight is the hat's average over it,
// 1 - a / 2; CPDI's the average of its two corner values, 1 - a.
TEST(Cpdi, WeightOfTheNodeAtTheCentreOfTheDomain) {
  const CpdiBasis cpdi(kH, kLp0);
  const CpGimpBasis cpgimp(kH, kLp0);
  for (const double F : {1.0, 2.0, 3.0, 4.0}) {
    const double a = F * kLp0 / kH;
    const double x = 5 * kH;  // node 5
    int base;
    double w[4], g[4];
    cpdi.eval(x, F, base, w, g);
    EXPECT_NEAR(w[5 - base], 1.0 - a, 1e-14) << "F = " << F;
    cpgimp.eval(x, F, base, w, g);
    EXPECT_NEAR(w[5 - base], 1.0 - a / 2, 1e-14) << "F = " << F;
  }
}

// The bar at a small amplitude: stable, and its error close to cpGIMP's (their weights differ
// only for particles over a node). Measured at h = 1/100: cpdi 2.3e-6, cpgimp 2.0e-6 (A = 0.015).
TEST(Cpdi, RunsTheBarCloseToCpGimp) {
  RunParams p;
  p.E = 4;
  p.A = 0.015;
  p.dt = 1e-4;
  p.T = 1;
  p.cells = 100;
  p.method = Method::cpdi;
  ASSERT_TRUE(validate(p).empty());
  const RunResult cpdi = run(p);
  p.method = Method::cpgimp;
  const RunResult cpgimp = run(p);
  ASSERT_EQ(cpdi.outcome, Outcome::stable);
  ASSERT_EQ(cpgimp.outcome, Outcome::stable);
  EXPECT_LT(*cpdi.max_error, 2 * *cpgimp.max_error);
  EXPECT_GT(*cpdi.max_error, 0.5 * *cpgimp.max_error);
  EXPECT_FALSE(cpdi.dt_stable_min.has_value());  // eq. (108) is not derived for CPDI
}

}  // namespace
}  // namespace mpmstab
