// The bar scene: initial state, the body force against the PDE, and convergence of the scheme.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "run.hpp"
#include "scene.hpp"
#include "simulation.hpp"

namespace mpmstab {
namespace {

TEST(BarScene, InitialStateMatchesTheExactSolution) {
  const BarScene scene(64.0, 0.015);
  const int cells = 10, ppc = 3;
  const Particles P = scene.initial_particles(cells, ppc);
  ASSERT_EQ(P.size(), cells * ppc);
  const double h = 1.0 / cells;
  for (int i = 0; i < cells; ++i) {
    for (int k = 0; k < ppc; ++k) {
      const int p = i * ppc + k;
      EXPECT_NEAR(P.X[p], (i + (k + 0.5) / ppc) * h, 1e-15);
      EXPECT_EQ(P.x[p], P.X[p]);
      EXPECT_NEAR(P.x[p] - P.X[p], scene.displacement(P.X[p], 0.0), 1e-15);  // u(X, 0) = 0
      EXPECT_DOUBLE_EQ(P.v[p], scene.velocity(P.X[p], 0.0));
      EXPECT_NEAR(P.v[p], 0.015 * 8 * std::numbers::pi * std::sin(2 * std::numbers::pi * P.X[p]),
                  1e-15);
      EXPECT_EQ(P.F[p], 1.0);
      EXPECT_EQ(P.sigma[p], 0.0);
      EXPECT_DOUBLE_EQ(P.mass[p], h / ppc);
      EXPECT_DOUBLE_EQ(P.volume0[p], h / ppc);
    }
  }
  EXPECT_NEAR(P.mass.sum(), 1.0, 1e-14);  // rho0 = 1 on [0, 1]
}

// rho0 u_tt = d sigma / dX + rho0 b with sigma = E u_X: checked with central differences.
TEST(BarScene, BodyForceMakesTheManufacturedSolutionExact) {
  const BarScene scene(256.0, 0.05);
  const double d = 1e-4;
  for (double X : {0.1, 0.37, 0.5, 0.81}) {
    for (double t : {0.013, 0.2, 0.77}) {
      const double u_tt = (scene.displacement(X, t + d) - 2 * scene.displacement(X, t) +
                           scene.displacement(X, t - d)) /
                          (d * d);
      const double dsigma_dX = (scene.stress(X + d, t) - scene.stress(X - d, t)) / (2 * d);
      const double residual = scene.rho0 * u_tt - dsigma_dX - scene.rho0 * scene.body_force(X, t);
      const double size = std::abs(dsigma_dX) + std::abs(scene.rho0 * u_tt) + 1.0;
      EXPECT_LT(std::abs(residual) / size, 1e-5) << "X = " << X << " t = " << t;
      // and sigma = E du/dX
      const double u_X = (scene.displacement(X + d, t) - scene.displacement(X - d, t)) / (2 * d);
      EXPECT_NEAR(scene.stress(X, t), scene.E * u_X, 1e-6 * scene.E);
    }
  }
}

RunParams small_amplitude_gimp(int cells) {
  RunParams p;
  p.method = Method::gimp;
  p.E = 4;
  p.A = 1e-4;  // no particle crosses a cell boundary
  p.dt = 1e-4;
  p.cells = cells;
  return p;
}

// With A so small that no particle crosses a cell, GIMP converges at second order in h.
TEST(Convergence, GimpErrorFallsAtOrderAtLeastOneAndAHalfInSpace) {
  double previous = 0, previous_over_time = 0;
  for (int cells : {32, 64, 128}) {
    const RunResult r = run(small_amplitude_gimp(cells));
    ASSERT_TRUE(r.stable);
    EXPECT_EQ(*r.crossings, 0);
    if (previous > 0) {
      const double order = std::log2(previous / *r.max_error);
      const double order_over_time = std::log2(previous_over_time / *r.max_error_over_time);
      EXPECT_GE(order, 1.5) << "cells " << cells;
      EXPECT_GE(order_over_time, 1.5) << "cells " << cells;
    }
    previous = *r.max_error;
    previous_over_time = *r.max_error_over_time;
  }
}

// No absolute tolerance hides in the scheme: with no cell crossed, the error relative to A is
// the same for a tiny amplitude as for a moderate one (the problem is linear in A there).
// The floor is the rounding of the stored positions, eps |x| per step: at A = 1e-12 it is 13
// times the discretization error (README, "Limits"), so the test stops at A = 1e-8.
TEST(Convergence, TinyAmplitudeKeepsTheRelativeErrorOfAModerateOne) {
  auto relative_error = [](double A) {
    RunParams p = small_amplitude_gimp(32);
    p.A = A;
    const RunResult r = run(p);
    EXPECT_TRUE(r.stable);
    EXPECT_EQ(*r.crossings, 0);
    return *r.max_error_over_time / A;
  };
  const double moderate = relative_error(1e-4);
  for (double tiny : {1e-6, 1e-8}) {
    const double rel = relative_error(tiny);
    EXPECT_NEAR(rel / moderate, 1.0, 0.05) << tiny;
  }
}

// Symplectic Euler is first order in dt: on a fixed grid the particle positions approach the
// small-dt solution at order about one.
TEST(Convergence, PositionsConvergeAtFirstOrderInTime) {
  RunParams p = small_amplitude_gimp(32);
  p.A = 1e-3;
  p.T = 0.25;
  auto positions = [&](double dt) {
    p.dt = dt;
    Simulation sim(p);
    const auto n = *step_count(p.T, dt);
    for (std::int64_t k = 1; k <= n; ++k)
      sim.advance_to(k == n ? p.T : k * dt);
    return Eigen::ArrayXd(sim.particles().x);
  };
  const Eigen::ArrayXd reference = positions(1e-6);
  double previous = 0;
  for (double dt : {2e-3, 1e-3, 5e-4}) {
    const double error = (positions(dt) - reference).abs().maxCoeff();
    if (previous > 0) {
      EXPECT_GE(std::log2(previous / error), 0.9) << "dt " << dt;
    }
    previous = error;
  }
}

}  // namespace
}  // namespace mpmstab
