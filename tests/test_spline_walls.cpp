// The boundary-modified B-splines of Steffen, Kirby and Berzins (2008) (walls = modified): the
// weights against an independent oracle (Cox-de Boor recursion on the open knot vector, the first
// two splines merged into the wall node's), partition of unity at every position, the wall
// values, gradients as derivatives, and where linear reproduction is lost.
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

// B-spline j of degree p on `knots` at x, by the Cox-de Boor recursion (right-open intervals;
// the last knot closes the last non-empty interval).
double cox_de_boor(const std::vector<double>& knots, int j, int p, double x) {
  if (p == 0) {
    const double lo = knots[j], hi = knots[j + 1];
    if (lo == hi) return 0.0;
    const bool last = hi == knots.back();
    return (x >= lo && (x < hi || (last && x == hi))) ? 1.0 : 0.0;
  }
  double value = 0.0;
  const double d1 = knots[j + p] - knots[j];
  const double d2 = knots[j + p + 1] - knots[j + 1];
  if (d1 > 0) value += (x - knots[j]) / d1 * cox_de_boor(knots, j, p - 1, x);
  if (d2 > 0) value += (knots[j + p + 1] - x) / d2 * cox_de_boor(knots, j + 1, p - 1, x);
  return value;
}

// The open knot vector on [0, 1] with `cells` cells: the wall knots repeated p + 1 times; the
// interior knots at the nodes (cubic) or at the cell middles (quadratic).
std::vector<double> open_knots(int p, int cells) {
  const double h = 1.0 / cells;
  std::vector<double> k(p + 1, 0.0);
  if (p == 3) {
    for (int i = 1; i < cells; ++i)
      k.push_back(i * h);
  } else {
    for (int i = 0; i < cells; ++i)
      k.push_back((i + 0.5) * h);
  }
  for (int i = 0; i <= p; ++i)
    k.push_back(1.0);
  return k;
}

// Weight of grid node i (0..cells) at x: the open-knot splines with the first two (and the last
// two) merged, one function per node.
double oracle(int p, int cells, int node, double x) {
  const auto knots = open_knots(p, cells);
  const int count = static_cast<int>(knots.size()) - p - 1;  // number of splines = cells + 3
  auto B = [&](int j) { return j >= 0 && j < count ? cox_de_boor(knots, j, p, x) : 0.0; };
  if (node == 0) return B(0) + B(1);
  if (node == cells) return B(count - 1) + B(count - 2);
  return B(node + 1);
}

template <class Basis>
double weight_of(const Basis& basis, double x, int node, double* gradient = nullptr) {
  int base;
  double w[Basis::width], g[Basis::width];
  basis.eval(x, base, w, g);
  const int k = node - base;
  if (gradient) *gradient = k >= 0 && k < Basis::width ? g[k] : 0.0;
  return k >= 0 && k < Basis::width ? w[k] : 0.0;
}

std::vector<double> positions(int cells) {
  std::vector<double> xs;
  for (int i = 0; i <= 1000; ++i)
    xs.push_back(i / 1000.0);
  const double h = 1.0 / cells;
  for (int i = 0; i <= cells; ++i)
    for (double d : {0.0, 1e-13, -1e-13, 0.25 * h, 0.5 * h, -0.5 * h})
      if (i * h + d >= 0 && i * h + d <= 1) xs.push_back(i * h + d);
  return xs;
}

template <class Basis>
void expect_oracle_and_unity(const Basis& basis, int p, int cells) {
  for (const double x : positions(cells)) {
    double sum = 0.0;
    for (int node = -1; node <= cells + 2; ++node) {
      const double w = weight_of(basis, x, node);
      if (node < 0 || node > cells) {
        EXPECT_EQ(w, 0.0) << "x = " << x << ", node " << node << " beyond a wall";
        continue;
      }
      EXPECT_NEAR(w, oracle(p, cells, node, x), 1e-13)
          << "p = " << p << ", x = " << x << ", node " << node;
      EXPECT_GE(w, -1e-15);
      sum += w;
    }
    EXPECT_NEAR(sum, 1.0, 1e-14) << "x = " << x;
  }
}

TEST(SplineWalls, ModifiedSplinesAreTheOpenKnotSplinesAndSumToOne) {
  for (const int cells : {4, 5, 10, 23}) {
    const double h = 1.0 / cells;
    expect_oracle_and_unity(BSpline2Basis(h, cells, SplineWalls::modified), 2, cells);
    expect_oracle_and_unity(BSpline3Basis(h, cells, SplineWalls::modified), 3, cells);
  }
}

// On the wall only the wall node's function is nonzero (it is 1), and every function's slope
// vanishes there; gradients are the derivatives of the weights everywhere.
template <class Basis>
void expect_wall_values_and_gradients(const Basis& basis, int cells) {
  const double h = 1.0 / cells;
  for (const double x : {0.0, 1.0}) {
    const int wall = x == 0.0 ? 0 : cells;
    for (int node = 0; node <= cells; ++node) {
      double g = 0.0;
      const double w = weight_of(basis, x, node, &g);
      EXPECT_DOUBLE_EQ(w, node == wall ? 1.0 : 0.0) << "x = " << x << ", node " << node;
      EXPECT_NEAR(g, 0.0, 1e-12 / h) << "x = " << x << ", node " << node;
    }
  }
  const double d = 1e-6 * h;
  for (int i = 0; i < cells; ++i) {
    for (const double f : {0.1, 0.3, 0.45, 0.55, 0.7, 0.9}) {
      const double x = (i + f) * h;
      for (int node = 0; node <= cells; ++node) {
        double g = 0.0;
        weight_of(basis, x, node, &g);
        const double fd = (weight_of(basis, x + d, node) - weight_of(basis, x - d, node)) / (2 * d);
        EXPECT_NEAR(g, fd, 1e-6 / h) << "x = " << x << ", node " << node;
      }
    }
  }
}

TEST(SplineWalls, WallValuesAndGradients) {
  expect_wall_values_and_gradients(BSpline2Basis(0.1, 10, SplineWalls::modified), 10);
  expect_wall_values_and_gradients(BSpline3Basis(0.1, 10, SplineWalls::modified), 10);
}

// Linear fields: reproduced where only uniform splines are active, not in the first cells next to
// a wall (the documented cost of the modification; ghost elimination keeps it, test_bspline).
template <class Basis>
void expect_reproduction_lost_only_near_walls(const Basis& basis, int cells, double reach) {
  const double h = 1.0 / cells;
  double worst_near = 0.0;
  for (const double x : positions(cells)) {
    double sum_wx = 0.0;
    for (int node = 0; node <= cells; ++node)
      sum_wx += weight_of(basis, x, node) * node * h;
    const bool near = x < reach * h || x > 1.0 - reach * h;
    if (near) {
      worst_near = std::max(worst_near, std::abs(sum_wx - x));
    } else {
      EXPECT_NEAR(sum_wx, x, 1e-14) << "x = " << x;
    }
  }
  EXPECT_GT(worst_near, 1e-3 * h);  // lost next to the walls, by a fraction of h
}

TEST(SplineWalls, LinearReproductionLostOnlyNextToTheWalls) {
  expect_reproduction_lost_only_near_walls(BSpline2Basis(0.1, 10, SplineWalls::modified), 10, 1.5);
  expect_reproduction_lost_only_near_walls(BSpline3Basis(0.1, 10, SplineWalls::modified), 10, 2.0);
}

// On the bar both wall treatments converge: the error at least halves from 25 to 50 cells.
TEST(SplineWalls, BarRunsConvergeWithEitherWallTreatment) {
  for (const Method m : {Method::bspline2, Method::bspline3}) {
    for (const Walls walls : {Walls::clip, Walls::modified}) {
      std::vector<double> errors;
      for (const int cells : {25, 50}) {
        RunParams p = test_support::small_amplitude_bar(m, cells);
        p.walls = walls;
        ASSERT_TRUE(validate(p).empty());
        const RunResult r = run(p);
        ASSERT_EQ(r.outcome, Outcome::stable);
        errors.push_back(*r.max_error);
      }
      EXPECT_LT(errors[1], errors[0] / 2.0) << to_string(m) << " walls " << to_string(walls) << ": "
                                            << errors[0] << " -> " << errors[1];
    }
  }
}

TEST(SplineWalls, RefusedWhereTheyDoNotApply) {
  RunParams p;
  p.walls = Walls::modified;
  for (const Method m : {Method::mpm, Method::gimp, Method::cpgimp, Method::cpdi}) {
    p.method = m;
    const auto issues = validate(p);
    ASSERT_EQ(issues.size(), 1u) << to_string(m);
    EXPECT_EQ(issues[0].key, "walls");
  }
  p.method = Method::bspline3;
  EXPECT_TRUE(validate(p).empty());
  p.bc = Boundary::periodic;
  ASSERT_FALSE(validate(p).empty());
  EXPECT_EQ(validate(p)[0].key, "walls");
  p.bc = Boundary::dirichlet;
  p.cells = 3;
  ASSERT_FALSE(validate(p).empty());
  EXPECT_EQ(validate(p)[0].key, "cells");
}

}  // namespace
}  // namespace mpmstab
