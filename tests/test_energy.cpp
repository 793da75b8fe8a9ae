// The energy observer (core/observers/energy.hpp), the L2 error over time
// (core/observers/error_l2.hpp) and the time error (core/analysis/time_error.hpp): closed-form
// energies that balance, the observer against them on a fine grid, a balance that converges with
// dt, observers that change nothing, and a time error of the order the leapfrog form of symplectic
// Euler has.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/time_error.hpp"
#include "observers/energy.hpp"
#include "run/run.hpp"
#include "scenes/scene_registry.hpp"

namespace mpmstab {
namespace {

RunParams bar(Method m, double E, double A, int cells, double courant, double T) {
  RunParams p;
  p.method = m;
  p.E = E;
  p.A = A;
  p.cells = cells;
  p.T = T;
  p.stepping.policy = TimeStepPolicy::cfl;
  p.stepping.cfl_factor = courant;
  return p;
}

// K + U - work is constant in time for the exact solution of both scenes: the closed forms of
// scene.hpp balance (the bar's work is computed on its own, not from the balance).
TEST(Energy, TheExactEnergiesBalance) {
  for (const SceneKind kind : {SceneKind::bar, SceneKind::steffen}) {
    RunParams p;
    p.scene = kind;
    p.E = 64;
    p.A = 0.02;
    const auto scene = make_scene(p);
    const ExactEnergy e0 = scene->exact_energy(0);
    const double total0 = e0.kinetic + e0.strain - e0.work;
    ASSERT_GT(total0, 0);
    for (const double t : {0.013, 0.1, 0.37, 0.5, 0.91}) {
      const ExactEnergy e = scene->exact_energy(t);
      EXPECT_NEAR(e.kinetic + e.strain - e.work, total0, 1e-12 * total0) << to_string(kind);
      EXPECT_GE(e.kinetic, 0);
      EXPECT_GE(e.strain, 0);
    }
  }
  // The bar's closed forms against a quadrature of their definitions at one t.
  RunParams p;
  p.E = 4;
  p.A = 0.01;
  const auto scene = make_scene(p);
  const double t = 0.3;
  double K = 0, U = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double X = (i + 0.5) / n, dX = 1.0 / n;
    const double v = scene->velocity(X, t);
    const double eps = (scene->displacement(X + 1e-6, t) - scene->displacement(X - 1e-6, t)) / 2e-6;
    K += 0.5 * v * v * dX;
    U += 0.5 * p.E * eps * eps * dX;
  }
  const ExactEnergy e = scene->exact_energy(t);
  EXPECT_NEAR(e.kinetic, K, 1e-6 * K);
  EXPECT_NEAR(e.strain, U, 1e-6 * U);
}

TEST(Energy, TheStrainEnergyDensityIsTheIntegralOfTheStress) {
  for (const Material m : {Material::linear, Material::neo_hookean}) {
    const MaterialLaw law{m, 7.0};
    EXPECT_DOUBLE_EQ(law.energy(1.0), 0.0);
    for (const double F : {0.6, 0.95, 1.1, 1.7}) {
      const double d = 1e-6;
      EXPECT_NEAR((law.energy(F + d) - law.energy(F - d)) / (2 * d), law.stress(F), 1e-6);
    }
  }
}

// On a fine grid the particles' energies are those of the exact solution within 1%, on both
// scenes, and the balance holds within 1%.
TEST(Energy, TheObserverMatchesTheClosedFormOnAFineGrid) {
  for (const SceneKind kind : {SceneKind::bar, SceneKind::steffen}) {
    RunParams p = bar(Method::gimp, 4, 1e-3, 200, 0.1, 0.5);
    p.scene = kind;
    p.observe.energy = true;
    const RunResult r = run(p);
    ASSERT_TRUE(r.stable) << to_string(kind);
    ASSERT_TRUE(r.energy_exact_error_max && r.energy_error_max && r.energy_drift);
    EXPECT_LT(*r.energy_exact_error_max, 0.01) << to_string(kind);
    EXPECT_LT(*r.energy_error_max, 0.01) << to_string(kind);
    EXPECT_FALSE(r.energy_warning_step) << to_string(kind);
  }
}

// The linear bar: the balance error falls with dt at a fixed grid (the discrete balance is not
// exact: symplectic Euler keeps a nearby energy, and the error has a part of first order in dt and
// one of first order in h; on a fine grid the first shows).
TEST(Energy, TheBalanceOfTheLinearBarConvergesWithDt) {
  double before = 0;
  for (const double C : {0.4, 0.2, 0.1}) {
    RunParams p = bar(Method::mpm, 16, 1e-3, 200, C, 0.5);
    p.observe.energy = true;
    const RunResult r = run(p);
    ASSERT_TRUE(r.stable && r.energy_error_max);
    if (before > 0) {
      EXPECT_LT(*r.energy_error_max, before / 1.6) << "C = " << C;
    }
    before = *r.energy_error_max;
  }
}

// The energy and L2 observers read the state and change nothing: the same trajectory, bit for
// bit; off, their values are null.
TEST(Energy, ObserversChangeNothingAndAreNullWhenOff) {
  RunParams p = bar(Method::gimp, 64, 0.015, 50, 0.3, 0.3);
  const RunResult off = run(p);
  EXPECT_FALSE(off.energy_error_max || off.energy_exact_error_max || off.energy_drift ||
               off.energy_warning_step || off.error_l2_time);
  p.observe.energy = p.observe.error_l2 = true;
  const RunResult on = run(p);
  ASSERT_TRUE(on.max_error && off.max_error);
  EXPECT_EQ(*on.max_error, *off.max_error);
  EXPECT_EQ(*on.max_error_over_time, *off.max_error_over_time);
  EXPECT_EQ(on.steps, off.steps);
  ASSERT_TRUE(on.error_l2_time);
  // An RMS over the body and the run is at most the largest error of any step.
  EXPECT_GT(*on.error_l2_time, 0);
  EXPECT_LE(*on.error_l2_time, *on.max_error_over_time);
}

// A failing run warns through its energy before it fails.
TEST(Energy, AFailingRunLeavesItsBalanceBeforeItFails) {
  RunParams p;
  p.method = Method::mpm;
  p.E = 64;
  p.A = 0.05;
  p.dt = 1e-4;
  p.observe.energy = true;
  const RunResult r = run(p);
  ASSERT_FALSE(r.stable);
  ASSERT_TRUE(r.failure);
  ASSERT_TRUE(r.energy_warning_step);
  EXPECT_LE(*r.energy_warning_step, r.failure->step);
}

// The time error: zero against itself; first order for USF (its stress is updated with the
// velocity of the start of the step), and at least first order, with a constant hundreds of times
// smaller, for USL (the leapfrog form).
TEST(TimeError, IsZeroAgainstItselfAndFallsWithDt) {
  RunParams p = bar(Method::gimp, 4, 1e-3, 25, 0.5, 0.25);
  const TimeErrorStudy same = time_errors(p, 0.5, {8}, 8);
  ASSERT_EQ(same.points.size(), 1u);
  ASSERT_TRUE(same.points[0].max_difference);
  EXPECT_EQ(*same.points[0].max_difference, 0.0);
  const TimeErrorStudy usl = time_errors(p, 0.5, {1, 2, 4}, 64);
  p.update = UpdateOrder::usf;
  const TimeErrorStudy usf = time_errors(p, 0.5, {1, 2, 4}, 64);
  ASSERT_EQ(usl.points.size(), 3u);
  ASSERT_EQ(usf.points.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    ASSERT_TRUE(usl.points[k].stable && usl.points[k].max_difference);
    ASSERT_TRUE(usf.points[k].stable && usf.points[k].max_difference);
    EXPECT_LT(*usl.points[k].max_difference * 100, *usf.points[k].max_difference);
  }
  for (std::size_t k = 1; k < 3; ++k) {
    const double q_usf =
        std::log2(*usf.points[k - 1].max_difference / *usf.points[k].max_difference);
    const double q_usl =
        std::log2(*usl.points[k - 1].max_difference / *usl.points[k].max_difference);
    EXPECT_NEAR(q_usf, 1.0, 0.1);
    EXPECT_GT(q_usl, 0.9);
  }
}

}  // namespace
}  // namespace mpmstab
