// E only rescales time. With rho0 = 1 and c = sqrt(E), the substitution tau = c t turns the
// balance of momentum, the body force and the exact solution of both scenes into equations free
// of E (docs/theory.md, "Dimensionless coordinates"), and a fixed dt into the Courant number
// c dt / h. A run is therefore fixed by c dt / h, A / h, the wave passes c T, the grid, the
// particles per cell and the method: two runs that share them at different E are the same run.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "run/run.hpp"

namespace mpmstab {
namespace {

// The relative difference of two results of the same dimensionless run. The two runs add the
// same terms scaled by powers of c, so they differ by rounding only.
double rel(double a, double b) {
  return std::abs(a - b) / std::max(std::abs(a), std::abs(b));
}
constexpr double kRounding = 1e-9;

// `a` at modulus E: the same c dt / h and c T.
RunParams at_modulus(RunParams a, double E) {
  const double slow = std::sqrt(a.E / E);  // c_a / c
  a.dt *= slow;
  a.T *= slow;
  a.E = E;
  return a;
}

void expect_same_run(const RunParams& stiff, double E) {
  const RunParams soft = at_modulus(stiff, E);
  const RunResult a = run(stiff), b = run(soft);
  const std::string what = std::string(to_string(stiff.method)) + " " +
                           std::string(to_string(stiff.scene)) + " E=" + std::to_string(E);
  // The coordinates every record carries agree (to the rounding of sqrt and the products).
  EXPECT_LT(rel(*courant_number(stiff), *courant_number(soft)), 1e-14) << what;
  EXPECT_LT(rel(wave_passes(stiff), wave_passes(soft)), 1e-14) << what;
  EXPECT_EQ(amplitude_per_cell(stiff), amplitude_per_cell(soft)) << what;
  EXPECT_EQ(a.steps, b.steps) << what;
  EXPECT_EQ(a.stable, b.stable) << what;
  EXPECT_LT(rel(a.courant, b.courant), 1e-14) << what;
  if (!a.stable || !b.stable) {  // both failed at the same step: the errors before it agree
    ASSERT_TRUE(a.failure && b.failure) << what;
    EXPECT_EQ(a.failure->reason, b.failure->reason) << what;
  } else {
    ASSERT_TRUE(a.max_error && b.max_error) << what;
    EXPECT_LT(rel(*a.max_error, *b.max_error), kRounding)
        << what << ": " << *a.max_error << " against " << *b.max_error;
  }
  ASSERT_TRUE(a.max_error_over_time && b.max_error_over_time) << what;
  EXPECT_LT(rel(*a.max_error_over_time, *b.max_error_over_time), kRounding) << what;
  ASSERT_TRUE(a.crossings && b.crossings) << what;
  EXPECT_EQ(*a.crossings, *b.crossings) << what;
}

// The case: E = 1e4 to T = 1 is E = 4 to T = 50 at the same Courant number.
TEST(Scaling, EOnlyRescalesTimeOnTheBar) {
  for (const Method m : {Method::gimp, Method::mpm}) {
    RunParams stiff;
    stiff.method = m;
    stiff.E = 1e4;
    stiff.A = 0.015;
    stiff.dt = 2e-5;  // c dt / h = 0.2
    stiff.T = 1;
    stiff.cells = 100;
    expect_same_run(stiff, 4);
  }
}

TEST(Scaling, EOnlyRescalesTimeOnTheSecondScene) {
  RunParams stiff;
  stiff.scene = SceneKind::steffen;
  stiff.E = 1e4;
  stiff.A = 0.015;
  stiff.dt = 2e-5;
  stiff.T = 0.5;
  stiff.cells = 50;
  expect_same_run(stiff, 4);
}

}  // namespace
}  // namespace mpmstab
