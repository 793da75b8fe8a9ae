// The quadratic and cubic B-spline bases: the spline formulas, partition of unity and linear
// reproduction at every position including next to the walls (ghost-node elimination), gradients
// as derivatives of the weights, spatial convergence on the bar, and what they refuse.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "base/params.hpp"
#include "run/run.hpp"
#include "scenes/validate.hpp"
#include "step/shape.hpp"
#include "support.hpp"

namespace mpmstab {
namespace {

// The uniform B-splines in r = (x - X_i) / h, written from their piecewise definitions: an oracle
// independent of the bases' local formulas.
double quadratic(double r) {
  r = std::abs(r);
  if (r <= 0.5) return 0.75 - r * r;
  if (r <= 1.5) return 0.5 * (1.5 - r) * (1.5 - r);
  return 0.0;
}
double cubic(double r) {
  r = std::abs(r);
  if (r <= 1.0) return 2.0 / 3.0 - r * r + 0.5 * r * r * r;
  if (r <= 2.0) return (2.0 - r) * (2.0 - r) * (2.0 - r) / 6.0;
  return 0.0;
}

std::vector<double> positions(int cells) {
  std::vector<double> xs;
  for (int i = 0; i <= 2000; ++i)
    xs.push_back(i / 2000.0);
  const double h = 1.0 / cells;
  for (int i = 0; i <= cells; ++i) {
    for (double d : {0.0, 1e-13, -1e-13, 0.5 * h, -0.5 * h}) {
      const double x = i * h + d;
      if (x >= 0 && x <= 1) xs.push_back(x);
    }
  }
  return xs;
}

template <class Basis>
void expect_reproduction(const Basis& basis, int cells, bool dirichlet) {
  const double h = 1.0 / cells;
  for (const double x : positions(cells)) {
    int base;
    double w[Basis::width], g[Basis::width];
    basis.eval(x, base, w, g);
    double sum_w = 0, sum_wx = 0, sum_g = 0, sum_gx = 0;
    for (int k = 0; k < Basis::width; ++k) {
      const int node = base + k;
      if (dirichlet && (node < 0 || node > cells)) {  // eliminated: carries nothing
        EXPECT_EQ(w[k], 0.0) << "x = " << x << ", node " << node;
        EXPECT_EQ(g[k], 0.0) << "x = " << x << ", node " << node;
      }
      sum_w += w[k];
      sum_wx += w[k] * node * h;
      sum_g += g[k];
      sum_gx += g[k] * node * h;
    }
    EXPECT_NEAR(sum_w, 1.0, 1e-14) << "x = " << x;
    EXPECT_NEAR(sum_wx, x, 1e-14) << "x = " << x;  // linear fields are reproduced
    EXPECT_NEAR(sum_g, 0.0, 1e-10 / h) << "x = " << x;
    EXPECT_NEAR(sum_gx, 1.0, 1e-12) << "x = " << x;  // and their gradients
  }
}

TEST(BSpline, PartitionOfUnityAndLinearReproductionEverywhereIncludingTheWalls) {
  for (const int cells : {4, 10, 37}) {
    const double h = 1.0 / cells;
    expect_reproduction(BSpline2Basis(h, cells, true), cells, true);
    expect_reproduction(BSpline3Basis(h, cells, true), cells, true);
    expect_reproduction(BSpline2Basis(h, cells, false), cells, false);
    expect_reproduction(BSpline3Basis(h, cells, false), cells, false);
  }
}

// Away from the walls (and everywhere on a periodic grid) the weights are the splines.
TEST(BSpline, WeightsAreTheSplinesAwayFromTheWalls) {
  const int cells = 10;
  const double h = 1.0 / cells;
  const BSpline2Basis b2(h, cells, true);
  const BSpline3Basis b3(h, cells, true);
  for (const double x : positions(cells)) {
    int base;
    double w[4], g[4];
    b2.eval(x, base, w, g);
    if (base >= 0 && base + 2 <= cells) {
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(w[k], quadratic(x / h - (base + k)), 1e-14) << x;
        EXPECT_GE(w[k], 0.0);
      }
    }
    b3.eval(x, base, w, g);
    if (base >= 0 && base + 3 <= cells) {
      for (int k = 0; k < 4; ++k) {
        EXPECT_NEAR(w[k], cubic(x / h - (base + k)), 1e-14) << x;
        EXPECT_GE(w[k], 0.0);
      }
    }
  }
}

// G_ip = dS_ip/dx, by central differences of the weights of each node (walls included: the
// eliminated weights are smooth too, inside a cell).
template <class Basis>
void expect_gradients_are_derivatives(const Basis& basis, int cells) {
  const double h = 1.0 / cells;
  const double d = 1e-6 * h;
  auto weight = [&](double x, int node) {
    int base;
    double w[Basis::width], g[Basis::width];
    basis.eval(x, base, w, g);
    const int k = node - base;
    return k >= 0 && k < Basis::width ? w[k] : 0.0;
  };
  for (int i = 0; i < cells; ++i) {
    for (const double f : {0.1, 0.3, 0.45, 0.55, 0.7, 0.9}) {  // inside a cell, off the knots
      const double x = (i + f) * h;
      int base;
      double w[Basis::width], g[Basis::width];
      basis.eval(x, base, w, g);
      for (int k = 0; k < Basis::width; ++k) {
        const double fd = (weight(x + d, base + k) - weight(x - d, base + k)) / (2 * d);
        EXPECT_NEAR(g[k], fd, 1e-6 / h) << "x = " << x << ", node " << base + k;
      }
    }
  }
}

TEST(BSpline, GradientsAreTheDerivativesOfTheWeights) {
  expect_gradients_are_derivatives(BSpline2Basis(0.1, 10, true), 10);
  expect_gradients_are_derivatives(BSpline3Basis(0.1, 10, true), 10);
}

// Continuity: the quadratic is C1, the cubic C2 (weights and gradients continuous at every knot
// away from the walls).
TEST(BSpline, WeightsAndGradientsAreContinuousAcrossKnots) {
  const int cells = 10;
  const double h = 1.0 / cells;
  const BSpline2Basis b2(h, cells, false);
  const BSpline3Basis b3(h, cells, false);
  auto check = [&](const auto& basis, double knot) {
    using B = std::decay_t<decltype(basis)>;
    for (int node = 2; node <= cells - 2; ++node) {
      double values[2][2];
      for (int side = 0; side < 2; ++side) {
        const double x = knot + (side ? 1e-12 : -1e-12);
        int base;
        double w[B::width], g[B::width];
        basis.eval(x, base, w, g);
        const int k = node - base;
        values[side][0] = k >= 0 && k < B::width ? w[k] : 0.0;
        values[side][1] = k >= 0 && k < B::width ? g[k] : 0.0;
      }
      EXPECT_NEAR(values[0][0], values[1][0], 1e-10) << knot << " node " << node;
      EXPECT_NEAR(values[0][1], values[1][1], 1e-9 / h) << knot << " node " << node;
    }
  };
  for (int i = 3; i < cells - 3; ++i) {
    check(b2, (i + 0.5) * h);  // the quadratic's knots are at cell middles
    check(b3, i * h);          // the cubic's at the nodes
  }
}

// The bar at a small amplitude and a small dt (time error negligible): the error at T falls at
// least as h^2 (measured: about h^3.3 for both between h = 1/25 and 1/100, ppc = 2).
TEST(BSpline, ConvergesAtLeastSecondOrderInH) {
  for (const Method m : {Method::bspline2, Method::bspline3}) {
    std::vector<double> errors;
    for (const int cells : {25, 50, 100}) {
      const RunParams p = test_support::small_amplitude_bar(m, cells);
      ASSERT_TRUE(validate(p).empty());
      const RunResult r = run(p);
      ASSERT_EQ(r.outcome, Outcome::stable) << to_string(m) << " cells " << cells;
      errors.push_back(*r.max_error);
    }
    for (std::size_t i = 1; i < errors.size(); ++i) {
      const double order = std::log2(errors[i - 1] / errors[i]);
      EXPECT_GE(order, 2.0) << to_string(m) << ": order " << order;
    }
  }
}

// eq. (108) is derived for mpm, gimp and cpgimp: a B-spline run does not measure it (null, not a
// number of another basis's formula), and the policies that step by it are refused, as are free
// ghost nodes (the B-splines eliminate theirs).
TEST(BSpline, RefusesWhatEq108AndTheWallNodesDoNotCover) {
  RunParams p = test_support::quick_case();
  p.method = Method::bspline2;
  p.T = 0.05;
  ASSERT_TRUE(validate(p).empty());
  const RunResult r = run(p);
  EXPECT_FALSE(r.dt_stable_min.has_value());
  for (const auto policy : {TimeStepPolicy::adaptive, TimeStepPolicy::min}) {
    RunParams q = p;
    q.stepping.policy = policy;
    const auto issues = validate(q);
    ASSERT_FALSE(issues.empty());
    EXPECT_EQ(issues.front().key, "policy");
  }
  RunParams ghost = p;
  ghost.walls = Walls::ghost;
  const auto issues = validate(ghost);
  ASSERT_FALSE(issues.empty());
  EXPECT_EQ(issues.front().key, "walls");
}

// Every new basis with every scene, both boundary kinds, every update order and the FLIP and
// APIC transfers: a verdict each, and at this small amplitude a stable one (72 runs).
TEST(NewBases, RunWithEverySceneBoundaryUpdateOrderAndTransfer) {
  int runs = 0;
  for (const Method m : {Method::bspline2, Method::bspline3, Method::cpdi}) {
    for (const SceneKind scene : {SceneKind::bar, SceneKind::steffen}) {
      for (const Boundary bc : {Boundary::dirichlet, Boundary::periodic}) {
        for (const UpdateOrder u : {UpdateOrder::usl, UpdateOrder::usf, UpdateOrder::musl}) {
          for (const Transfer t : {Transfer::flip, Transfer::apic}) {
            RunParams p;
            p.method = m;
            p.scene = scene;
            p.bc = bc;
            p.update = u;
            p.transfer = t;
            p.E = 64;
            p.A = 0.01;
            p.dt = 1e-4;
            p.T = 0.1;
            p.cells = 50;
            ASSERT_TRUE(validate(p).empty());
            const RunResult r = run(p);
            EXPECT_EQ(r.outcome, Outcome::stable)
                << to_string(m) << " " << to_string(scene) << " " << to_string(bc) << " "
                << to_string(u) << " " << to_string(t);
            ++runs;
          }
        }
      }
    }
  }
  EXPECT_EQ(runs, 72);
}

}  // namespace
}  // namespace mpmstab
