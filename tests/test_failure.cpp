// Failure detection: each failure mode is caught and named, with its step and time.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "base/failure.hpp"
#include "run/run.hpp"
#include "scenes/bar.hpp"
#include "scenes/scene_registry.hpp"
#include "scenes/validate.hpp"
#include "step/simulation.hpp"

namespace mpmstab {
namespace {

Particles healthy() {
  return BarScene(4.0, 0.015).initial_particles(10, 2);
}

TEST(DetectFailure, AHealthyStateIsAdmissible) {
  EXPECT_FALSE(detect_failure(healthy(), Boundary::dirichlet));
  EXPECT_FALSE(detect_failure(healthy(), Boundary::periodic));
}

TEST(DetectFailure, ParticleOutsideTheDomain) {
  for (double x : {-1e-12, 1.0 + 1e-12, 5.0}) {
    Particles P = healthy();
    P.x[7] = x;
    const auto f = detect_failure(P, Boundary::dirichlet);
    ASSERT_TRUE(f) << x;
    EXPECT_EQ(f->reason, FailureReason::left_domain);
    EXPECT_EQ(f->particle, 7);
    // With periodic boundaries the same position is fine.
    EXPECT_FALSE(detect_failure(P, Boundary::periodic)) << x;
  }
}

TEST(DetectFailure, NonFiniteValuesInEveryField) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (Eigen::ArrayXd Particles::*field :
       {&Particles::x, &Particles::v, &Particles::F, &Particles::sigma}) {
    for (double bad : {nan, inf, -inf}) {
      Particles P = healthy();
      (P.*field)[3] = bad;
      for (Boundary bc : {Boundary::dirichlet, Boundary::periodic}) {
        const auto f = detect_failure(P, bc);
        ASSERT_TRUE(f);
        EXPECT_EQ(f->reason, FailureReason::non_finite);
        EXPECT_EQ(f->particle, 3);
      }
    }
  }
}

TEST(DetectFailure, NonPositiveDeformationGradient) {
  for (double F : {0.0, -0.0, -0.5}) {
    Particles P = healthy();
    P.F[11] = F;
    const auto f = detect_failure(P, Boundary::dirichlet);
    ASSERT_TRUE(f) << F;
    EXPECT_EQ(f->reason, FailureReason::nonpositive_F);
    EXPECT_EQ(f->particle, 11);
  }
}

// A subnormal F_p (below the smallest normal double) is a collapsed particle: the run stops, and
// the smallest normal value itself, or a non-positive F elsewhere, decides as before.
TEST(DetectFailure, SubnormalDeformationGradientIsACollapse) {
  const double smallest = std::numeric_limits<double>::min();
  for (double F :
       {smallest / 2, std::numeric_limits<double>::denorm_min(), std::nextafter(smallest, 0.0)}) {
    Particles P = healthy();
    P.F[7] = F;
    for (Boundary bc : {Boundary::dirichlet, Boundary::periodic}) {
      const auto f = detect_failure(P, bc);
      ASSERT_TRUE(f) << F;
      EXPECT_EQ(f->reason, FailureReason::collapsed_F);
      EXPECT_EQ(f->particle, 7);
      EXPECT_EQ(to_string(f->reason), "collapsed_F");
    }
    P.F[12] = 0.0;  // a non-positive F is named first
    EXPECT_EQ(detect_failure(P, Boundary::dirichlet)->reason, FailureReason::nonpositive_F);
  }
  Particles P = healthy();
  P.F[7] = smallest;  // normal: admissible
  EXPECT_FALSE(detect_failure(P, Boundary::dirichlet));
}

TEST(DetectFailure, SupportWiderThanTwoCellsForCpGimp) {
  const int ppc = 2;
  const double limit = max_admissible_F(Method::cpgimp, ppc);
  EXPECT_EQ(limit, 4.0);  // lp = F h / (2 m) <= h
  EXPECT_TRUE(std::isinf(max_admissible_F(Method::gimp, ppc)));
  EXPECT_TRUE(std::isinf(max_admissible_F(Method::mpm, ppc)));
  Particles P = healthy();
  P.F[8] = limit;  // lp = h exactly: admissible
  EXPECT_FALSE(detect_failure(P, Boundary::dirichlet, limit));
  P.F[8] = 4.0000001;
  const auto f = detect_failure(P, Boundary::periodic, limit);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->reason, FailureReason::support_too_wide);
  EXPECT_EQ(f->particle, 8);
  EXPECT_EQ(to_string(f->reason), "support_too_wide");
  // Without a limit (uGIMP, MPM) the same state is admissible.
  EXPECT_FALSE(detect_failure(P, Boundary::dirichlet));
  // A non-positive F is named first.
  P.F[12] = -1.0;
  EXPECT_EQ(detect_failure(P, Boundary::dirichlet, limit)->reason, FailureReason::nonpositive_F);
}

TEST(DetectFailure, NanIsReportedBeforeOtherReasons) {
  Particles P = healthy();
  P.F[2] = -1.0;
  P.x[5] = 2.0;
  P.v[9] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(detect_failure(P, Boundary::dirichlet)->reason, FailureReason::non_finite);
}

// The state's extremes, whichever version this CPU runs (AVX-512, AVX2 or the portable pass),
// equal their definitions bit for bit: for every particle count from 1 to 21 (full vectors and
// every tail), with and without the error terms, and a value that is not finite is seen in
// every array and at every position.
TEST(StateExtremes, EqualTheirDefinitionsForEveryCountAndTail) {
  for (Eigen::Index n = 1; n <= 21; ++n) {
    Particles P;
    P.resize(n);
    Eigen::ArrayXd X(n), u(n);
    for (Eigen::Index p = 0; p < n; ++p) {
      const double t = static_cast<double>(p);
      P.x[p] = 0.5 + 0.4 * std::sin(1.3 * t + 0.2);
      P.v[p] = std::cos(0.7 * t);
      P.F[p] = 1.0 + 0.3 * std::sin(2.1 * t);
      P.sigma[p] = -3.0 + 5.0 * std::cos(1.9 * t + 0.5);
      X[p] = P.x[p] + 0.01 * std::sin(3.7 * t);
      u[p] = 0.02 * std::cos(2.9 * t);
    }
    const ErrorTerms terms{X.data(), u.data(), 0.37};
    for (const bool with_error : {false, true}) {
      SCOPED_TRACE(testing::Message() << "n " << n << " error " << with_error);
      const StateExtremes got = state_extremes(P, with_error ? &terms : nullptr);
      EXPECT_TRUE(got.finite);
      EXPECT_EQ(got.F_min, P.F.minCoeff());
      EXPECT_EQ(got.F_max, P.F.maxCoeff());
      EXPECT_EQ(got.F_abs_max, P.F.abs().maxCoeff());
      EXPECT_EQ(got.sigma_abs_max, P.sigma.abs().maxCoeff());
      EXPECT_EQ(got.sigmaF_abs_max, (P.sigma * P.F).abs().maxCoeff());
      EXPECT_EQ(got.x_min, P.x.minCoeff());
      EXPECT_EQ(got.x_max, P.x.maxCoeff());
      double error = 0;
      for (Eigen::Index p = 0; with_error && p < n; ++p)
        error = std::max(error, std::abs((P.x[p] - X[p]) - u[p] * terms.factor));
      EXPECT_EQ(got.error_max, error);
    }
    for (Eigen::Index p = 0; p < n; ++p) {
      for (Eigen::ArrayXd* a : {&P.x, &P.v, &P.F, &P.sigma}) {
        for (const double bad :
             {std::numeric_limits<double>::quiet_NaN(), -std::numeric_limits<double>::infinity()}) {
          const double kept = (*a)[p];
          (*a)[p] = bad;
          EXPECT_FALSE(state_extremes(P).finite) << "n " << n << " particle " << p;
          EXPECT_FALSE(state_extremes(P, &terms).finite) << "n " << n << " particle " << p;
          (*a)[p] = kept;
        }
      }
    }
  }
}

TEST(Run, FarAboveTheCflLimitIsUnstableWithAReason) {
  RunParams p;
  p.method = Method::gimp;
  p.E = 1000;   // c = 31.6, h / c = 3.2e-4
  p.dt = 1e-3;  // Courant 3.2
  const RunResult r = run(p);
  EXPECT_GT(r.courant, 3.0);
  EXPECT_FALSE(r.stable);
  ASSERT_TRUE(r.failure);
  EXPECT_GE(r.failure->step, 1);
  EXPECT_LT(r.failure->step, r.steps_planned);
  EXPECT_DOUBLE_EQ(r.failure->time, r.failure->step * p.dt);
  EXPECT_EQ(r.steps, r.failure->step);
  EXPECT_FALSE(r.max_error);  // no error is reported for a run that failed
  EXPECT_FALSE(r.meaningless);
  for (Method m : {Method::mpm, Method::gimp}) {
    p.method = m;
    EXPECT_FALSE(run(p).stable) << to_string(m);
  }
}

// A run whose particle is crushed slowly (APIC on 1000 cells, one particle per cell, A = 30 cells)
// stops at the first step that leaves some F_p subnormal, and not before: the step before it is
// admissible. Without the rule it ran on to T with the collapsed particle (meaningless).
TEST(Run, ACrushedParticleStopsTheRunAsCollapsed) {
  RunParams p;
  p.method = Method::gimp;
  p.transfer = Transfer::apic;
  p.E = 100;
  p.A = 0.3;
  p.dt = 2e-5;
  p.T = 0.1;
  p.cells = 1000;
  p.ppc = 1;
  ASSERT_TRUE(validate(p).empty());
  const RunResult r = run(p);
  ASSERT_TRUE(r.failure);
  EXPECT_EQ(r.failure->reason, FailureReason::collapsed_F);
  const std::int64_t step = r.failure->step;
  EXPECT_GT(step, 1000);  // a slow crush, not a blow-up
  Simulation sim(p);
  for (std::int64_t n = 1; n < step; ++n)
    sim.advance_to(double(n) * p.dt);
  EXPECT_GE(sim.particles().F.minCoeff(), std::numeric_limits<double>::min());
  sim.advance_to(double(step) * p.dt);
  const double F = sim.particles().F[r.failure->particle];
  EXPECT_GT(F, 0.0);
  EXPECT_LT(F, std::numeric_limits<double>::min());
}

TEST(Simulation, PlantedBadStatesAreCaughtAfterTheNextStep) {
  RunParams p;
  p.cells = 10;
  // F <= 0 planted in one particle: the step keeps F_p (1 + dt L_p) <= 0 for small dt.
  {
    Simulation sim(p);
    sim.particles().F[4] = -0.2;
    sim.advance_to(p.dt);
    const auto f = detect_failure(sim.particles(), p.bc);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->reason, FailureReason::nonpositive_F);
  }
  // A NaN velocity spreads through the grid to the neighbours.
  {
    Simulation sim(p);
    sim.particles().v[6] = std::numeric_limits<double>::quiet_NaN();
    sim.advance_to(p.dt);
    const auto f = detect_failure(sim.particles(), p.bc);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->reason, FailureReason::non_finite);
  }
  // A particle pushed out through the wall.
  {
    Simulation sim(p);
    sim.particles().v[19] = 1e3;
    sim.particles().x[19] = 0.99;
    sim.advance_to(p.dt);
    sim.advance_to(2 * p.dt);
    const auto f = detect_failure(sim.particles(), p.bc);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->reason, FailureReason::left_domain);
  }
}

}  // namespace
}  // namespace mpmstab
