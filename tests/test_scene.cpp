// The scenes: initial states, the body force against the PDE, the declarations the solver
// follows, and convergence of the scheme.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

#include "run/run.hpp"
#include "scenes/bar.hpp"
#include "scenes/mode.hpp"
#include "scenes/scene_registry.hpp"
#include "scenes/steffen.hpp"
#include "step/simulation.hpp"

namespace mpmstab {
namespace {

constexpr double kPi = std::numbers::pi;

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

TEST(SteffenScene, InitialStateIsTheDeformedBarAtRest) {
  const SteffenScene scene(64.0, 0.015);
  const int cells = 10, ppc = 3;
  const Particles P = scene.initial_particles(cells, ppc);
  ASSERT_EQ(P.size(), cells * ppc);
  const double h = 1.0 / cells;
  for (int p = 0; p < cells * ppc; ++p) {
    const double X = P.X[p];
    EXPECT_NEAR(X, (p / ppc + (p % ppc + 0.5) / ppc) * h, 1e-15);
    EXPECT_NEAR(P.x[p], X + 0.015 * std::sin(2 * kPi * X), 1e-15);
    EXPECT_EQ(P.v[p], 0.0);
    const double F = 1 + 2 * kPi * 0.015 * std::cos(2 * kPi * X);
    EXPECT_NEAR(P.F[p], F, 1e-15);
    EXPECT_NEAR(P.sigma[p], 32.0 * (F - 1 / F), 1e-13);  // (E / 2) (F - 1 / F)
    EXPECT_DOUBLE_EQ(P.mass[p], h / ppc);
    EXPECT_DOUBLE_EQ(P.volume0[p], h / ppc);  // reference volume; V_p = F_p V_p^0
  }
  EXPECT_NEAR((P.F * P.volume0).sum(), 1.0, 1e-14);  // the deformed bar still fills [0, 1]
}

TEST(Scene, DeclarationsAndTheSceneOfARun) {
  RunParams p;
  p.E = 16;
  p.A = 0.01;
  const auto bar = make_scene(p);
  EXPECT_NE(dynamic_cast<const BarScene*>(bar.get()), nullptr);
  EXPECT_EQ(bar->material(), Material::linear);
  p.scene = SceneKind::steffen;
  const auto steffen = make_scene(p);
  EXPECT_NE(dynamic_cast<const SteffenScene*>(steffen.get()), nullptr);
  EXPECT_EQ(steffen->material(), Material::neo_hookean);
  for (const Scene* s : {bar.get(), steffen.get()})
    EXPECT_EQ(s->c, 4.0);
  for (SceneKind kind : {SceneKind::bar, SceneKind::steffen}) {
    EXPECT_TRUE(scene_supports(kind, Boundary::dirichlet));
    EXPECT_TRUE(scene_supports(kind, Boundary::periodic));
  }
  EXPECT_DOUBLE_EQ(steffen->law().stress(2.0), 8.0 * 1.5);
  EXPECT_DOUBLE_EQ(bar->law().stress(2.0), 16.0);
}

// Derivatives of the exact fields by central differences with one Richardson extrapolation:
// truncation error O(d^4), a relative 1e-8 at most for the fields and sample points below.
double d_dy(const std::function<double(double)>& f, double y, double d) {
  auto central = [&](double e) { return (f(y + e) - f(y - e)) / (2 * e); };
  return (4 * central(d / 2) - central(d)) / 3;
}
double d2_dy2(const std::function<double(double)>& f, double y, double d) {
  auto central = [&](double e) { return (f(y + e) - 2 * f(y) + f(y - e)) / (e * e); };
  return (4 * central(d / 2) - central(d)) / 3;
}

// rho0 u_tt = dP/dX + rho0 b, P = sigma(F) with F = 1 + u_X, v = u_t: each checked from the
// displacement alone, numerically, at points where no term vanishes.
void expect_exact_solution(const Scene& scene) {
  const double d = 1e-3;
  const MaterialLaw law = scene.law();
  for (double X : {0.1, 0.37, 0.62, 0.81}) {
    for (double t : {0.013, 0.2, 0.77}) {
      SCOPED_TRACE("X = " + std::to_string(X) + " t = " + std::to_string(t));
      auto u_of_t = [&](double s) { return scene.displacement(X, s); };
      auto u_of_X = [&](double Y) { return scene.displacement(Y, t); };
      auto P_of_X = [&](double Y) { return law.stress(1.0 + d_dy(u_of_X, Y, d)); };
      const double u_tt = d2_dy2(u_of_t, t, d);
      const double dP_dX = d_dy(P_of_X, X, d);
      const double b = scene.body_force(X, t);
      const double residual = scene.rho0 * u_tt - dP_dX - scene.rho0 * b;
      const double size = std::abs(scene.rho0 * u_tt) + std::abs(dP_dX) + std::abs(b);
      EXPECT_LT(std::abs(residual) / size, 1e-6);
      // The exact stress and velocity the scene reports are those of its displacement.
      const double sigma = scene.stress(X, t);
      EXPECT_LT(std::abs(sigma - P_of_X(X)), 1e-6 * (std::abs(sigma) + scene.E * scene.A));
      const double v = scene.velocity(X, t);
      EXPECT_LT(std::abs(v - d_dy(u_of_t, t, d)), 1e-6 * scene.A * scene.c * kPi);
    }
  }
}

TEST(BarScene, ExactSolutionSatisfiesTheBalanceOfMomentum) {
  for (double E : {4.0, 256.0}) {
    expect_exact_solution(BarScene(E, 0.05));
  }
}

TEST(SteffenScene, ExactSolutionSatisfiesTheBalanceOfMomentum) {
  // 2 pi A = 0.31: F from 0.69 to 1.31, where the neo-Hookean law is far from linear.
  for (double E : {4.0, 256.0}) {
    expect_exact_solution(SteffenScene(E, 0.05));
  }
}

// The solver's per-particle body force is the scene's pointwise one.
TEST(Scene, BodyForceAtTheParticlesIsThePointwiseBodyForce) {
  RunParams p;
  p.cells = 7;
  p.ppc = 3;
  p.A = 0.04;
  p.E = 64;
  for (SceneKind kind : {SceneKind::bar, SceneKind::steffen}) {
    p.scene = kind;
    const auto scene = make_scene(p);
    const Particles P = scene->initial_particles(p.cells, p.ppc);
    const auto b = scene->body_force_at(P.X);
    Eigen::ArrayXd values;
    for (double t : {0.0, 0.11, 0.5, 0.93}) {
      b->evaluate(t, values);
      ASSERT_EQ(values.size(), P.size());
      for (Eigen::Index q = 0; q < P.size(); ++q) {
        const double expected = scene->body_force(P.X[q], t);
        EXPECT_NEAR(values[q], expected, 1e-13 * (1 + std::abs(expected)))
            << to_string(kind) << " t " << t << " X " << P.X[q];
      }
    }
  }
}

RunParams steffen(int cells, double dt) {
  RunParams p;
  p.scene = SceneKind::steffen;
  p.method = Method::gimp;
  p.E = 4;
  p.A = 0.015;
  p.cells = cells;
  p.dt = dt;
  return p;
}

TEST(SteffenScene, RunIsStableAndItsErrorShrinksWithTheGridAndTheStep) {
  double previous = 0, previous_over_time = 0;
  for (int refine : {1, 2, 4}) {
    const RunResult r = run(steffen(25 * refine, 4e-3 / refine));
    ASSERT_TRUE(r.stable) << refine;
    EXPECT_LT(*r.max_error_over_time, 0.05 * 0.015) << refine;
    if (previous > 0) {
      EXPECT_LT(*r.max_error, 0.75 * previous) << refine;
      EXPECT_LT(*r.max_error_over_time, 0.75 * previous_over_time) << refine;
    }
    previous = *r.max_error;
    previous_over_time = *r.max_error_over_time;
  }
}

// The stress update follows the scene's material, and the error and the exact fields of the
// final state are the scene's.
TEST(SteffenScene, RunUsesTheNeoHookeanLawAndTheSteffenSolution) {
  RunParams p = steffen(100, 1e-3);
  p.T = 0.3;
  p.observe.final_state = true;
  const RunResult r = run(p);
  ASSERT_TRUE(r.stable);
  const FinalState& f = *r.final_state;
  const Eigen::ArrayXd neo_hookean = 0.5 * p.E * (f.F - 1.0 / f.F);
  EXPECT_LT((f.sigma - neo_hookean).abs().maxCoeff(), 1e-13);
  EXPECT_GT((f.sigma - p.E * (f.F - 1.0)).abs().maxCoeff(), 1e-3);  // not the linear law
  const SteffenScene scene(p.E, p.A);
  for (Eigen::Index q = 0; q < f.X.size(); q += 17) {
    EXPECT_EQ(f.u_exact[q], scene.displacement(f.X[q], p.T));
    EXPECT_EQ(f.v_exact[q], scene.velocity(f.X[q], p.T));
    EXPECT_EQ(f.sigma_exact[q], scene.stress(f.X[q], p.T));
  }
  EXPECT_DOUBLE_EQ(((f.x - f.X) - f.u_exact).abs().maxCoeff(), *r.max_error);
  EXPECT_LT(*r.max_error, 0.01 * p.A);
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
