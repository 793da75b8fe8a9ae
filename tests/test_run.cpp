// The run driver: observers compute only what is asked, verdicts, determinism, landing on T.
#include <gtest/gtest.h>

#include <set>

#include "observers/crossings.hpp"
#include "run/run.hpp"
#include "support.hpp"

namespace mpmstab {
namespace {

using test_support::quick_case;

TEST(Run, StableRunReportsEveryQuantity) {
  const RunResult r = run(quick_case());
  EXPECT_TRUE(r.stable);
  EXPECT_FALSE(r.failure);
  EXPECT_EQ(r.steps, 200);
  EXPECT_EQ(r.particles, 40);
  ASSERT_TRUE(r.max_error && r.max_error_over_time && r.crossings && r.dt_stable_min);
  EXPECT_GT(*r.max_error, 0);
  EXPECT_GE(*r.max_error_over_time, *r.max_error);
  EXPECT_GT(*r.dt_stable_min, 0);
  EXPECT_EQ(r.meaningless, false);
  EXPECT_DOUBLE_EQ(r.dt_cfl, 0.05 / 2.0);  // h / c with h = 1/20, c = 2
  EXPECT_DOUBLE_EQ(r.dt_sound, 0.5);
  EXPECT_DOUBLE_EQ(r.courant, 2.0 * 1e-3 / 0.05);
  EXPECT_GT(r.wall_seconds, 0);
  EXPECT_GT(r.ns_per_particle_step, 0);
  EXPECT_TRUE(r.history.empty());  // no history unless asked
}

TEST(Run, ObserversThatAreOffComputeNothingAndChangeNothing) {
  RunParams lean = quick_case();
  lean.observe.error_over_time = false;
  lean.observe.dt_stable = false;
  lean.observe.crossings = false;
  const RunResult a = run(lean);
  const RunResult b = run(quick_case());
  EXPECT_FALSE(a.max_error_over_time);
  EXPECT_FALSE(a.crossings);
  EXPECT_FALSE(a.dt_stable_min);
  EXPECT_FALSE(a.meaningless);
  ASSERT_TRUE(a.max_error && b.max_error);
  EXPECT_EQ(*a.max_error, *b.max_error);  // bit for bit: observers only read the state
}

// One run observing eq. (108) under every option gives, for each, the minimum a run with that
// option gives, bit for bit, and the same trajectory; the options' minima differ.
TEST(Run, EveryOptionOfEq108IsWhatARunWithThatOptionMeasures) {
  RunParams shared = quick_case();
  shared.A = 0.05;  // a stress and a velocity large enough to tell the options apart
  shared.observe.dt_stable_every_option = true;
  const RunResult all = run(shared);
  ASSERT_TRUE(all.dt_stable_min && all.max_error);
  std::set<double> minima;
  for (const StressScaling sigma : {StressScaling::scaled, StressScaling::raw}) {
    for (const VelocityNorm vnorm : {VelocityNorm::l2, VelocityNorm::max}) {
      RunParams own = shared;
      own.observe.dt_stable_every_option = false;
      own.stable = {sigma, vnorm};
      const RunResult r = run(own);
      const auto& of_option = all.dt_stable_min_of_option[option_index(own.stable)];
      ASSERT_TRUE(r.dt_stable_min && of_option);
      EXPECT_EQ(*of_option, *r.dt_stable_min);
      EXPECT_EQ(*r.max_error, *all.max_error);
      EXPECT_EQ(*r.crossings, *all.crossings);
      minima.insert(*r.dt_stable_min);
    }
  }
  EXPECT_EQ(minima.size(), 4u);
  EXPECT_EQ(*all.dt_stable_min, *all.dt_stable_min_of_option[option_index(shared.stable)]);
  // Not asked: none kept.
  EXPECT_FALSE(run(quick_case()).dt_stable_min_of_option[0]);
}

TEST(Run, HistoryHasOneRowPerKeptStepWithOnlyTheObservedFields) {
  RunParams p = quick_case();
  p.observe.history = true;
  const RunResult all = run(p);
  ASSERT_EQ(all.history.size(), 200u);
  EXPECT_EQ(all.history.front().step, 1);
  EXPECT_DOUBLE_EQ(all.history.back().time, p.T);
  EXPECT_EQ(*all.history.back().crossings, *all.crossings);
  double max_error = 0, min_dt = 1e300;
  for (const auto& row : all.history) {
    max_error = std::max(max_error, *row.error);
    min_dt = std::min(min_dt, *row.dt_stable);
  }
  EXPECT_EQ(max_error, *all.max_error_over_time);
  EXPECT_EQ(min_dt, *all.dt_stable_min);

  p.observe.history_stride = 30;
  p.observe.dt_stable = false;
  const RunResult strided = run(p);
  ASSERT_EQ(strided.history.size(), 7u);  // steps 30, 60, ..., 180 and the last, 200
  EXPECT_EQ(strided.history[5].step, 180);
  EXPECT_EQ(strided.history[6].step, 200);
  EXPECT_FALSE(strided.history[0].dt_stable);
}

TEST(Run, FinalStateHoldsTheParticlesAndTheExactSolutionAtT) {
  RunParams p = quick_case();
  EXPECT_FALSE(run(p).final_state);
  p.observe.final_state = true;
  const RunResult r = run(p);
  ASSERT_TRUE(r.final_state);
  const FinalState& f = *r.final_state;
  EXPECT_DOUBLE_EQ(f.time, p.T);
  ASSERT_EQ(f.x.size(), r.particles);
  // max_error is computed from the same state: max |x - X - u_exact|.
  EXPECT_DOUBLE_EQ(((f.x - f.X) - f.u_exact).abs().maxCoeff(), *r.max_error);
  EXPECT_TRUE(((f.sigma - p.E * (f.F - 1.0)).abs() < 1e-12).all());
}

TEST(Run, HistoryOfAFailedRunEndsWithTheLastAdmissibleStep) {
  RunParams p = quick_case();
  p.E = 1000;  // Courant 3.2 on 20 cells: fails within a few steps
  p.dt = 2e-3;
  p.observe.history = true;
  p.observe.history_stride = 1000;
  const RunResult r = run(p);
  ASSERT_FALSE(r.stable);
  ASSERT_EQ(r.history.size(), 1u);
  EXPECT_EQ(r.history.back().step, r.failure->step - 1);
}

TEST(Run, IsDeterministic) {
  const RunResult a = run(quick_case());
  const RunResult b = run(quick_case());
  EXPECT_EQ(*a.max_error, *b.max_error);
  EXPECT_EQ(*a.max_error_over_time, *b.max_error_over_time);
  EXPECT_EQ(*a.dt_stable_min, *b.dt_stable_min);
  EXPECT_EQ(*a.crossings, *b.crossings);
}

TEST(Run, LastStepIsShortenedToLandOnT) {
  RunParams p = quick_case();
  p.dt = 0.03;  // 6.67 steps in T = 0.2 -> 7 steps, the last one 0.02
  p.E = 0.01;
  p.observe.history = true;
  const RunResult r = run(p);
  EXPECT_EQ(r.steps, 7);
  EXPECT_DOUBLE_EQ(r.history.back().time, 0.2);
  EXPECT_DOUBLE_EQ(r.history[5].time, 0.18);
}

TEST(Run, FlagsARunWhoseErrorReachesTheAmplitudeAsMeaningless) {
  RunParams p;
  p.method = Method::gimp;
  p.E = 16;
  p.A = 0.2;  // two cells of displacement on a 10-cell grid
  p.cells = 10;
  p.bc = Boundary::periodic;
  const RunResult r = run(p);
  ASSERT_TRUE(r.stable);
  EXPECT_GE(*r.max_error_over_time, p.A);
  EXPECT_EQ(r.meaningless, true);
}

TEST(Run, PositionUpdateOptionChangesTheResultButNotTheVerdict) {
  RunParams p = quick_case();
  const RunResult grid = run(p);
  p.position_update = PositionUpdate::particle;
  const RunResult particle = run(p);
  ASSERT_TRUE(grid.stable && particle.stable);
  EXPECT_NE(*grid.max_error, *particle.max_error);
  EXPECT_LT(*particle.max_error, 10 * *grid.max_error + 1e-4);
}

TEST(Run, OneAndEightParticlesPerCellBothWork) {
  for (int ppc : {1, 8}) {
    for (Method m : {Method::mpm, Method::gimp}) {
      RunParams p = quick_case();
      p.ppc = ppc;
      p.method = m;
      p.A = 1e-3;
      const RunResult r = run(p);
      EXPECT_TRUE(r.stable) << ppc << " " << to_string(m);
      EXPECT_LT(*r.max_error, 1e-3) << ppc << " " << to_string(m);
      EXPECT_EQ(r.particles, 20 * ppc);
    }
  }
}

TEST(Run, PeriodicBarStaysStableAndAccurate) {
  RunParams p = quick_case();
  p.bc = Boundary::periodic;
  const RunResult r = run(p);
  ASSERT_TRUE(r.stable);
  EXPECT_LT(*r.max_error_over_time, 0.1 * p.A);
}

}  // namespace
}  // namespace mpmstab

namespace mpmstab {
namespace {

RunParams policy_case(TimeStepPolicy policy) {
  RunParams p;
  p.method = Method::gimp;
  p.E = 64;
  p.A = 0.015;
  p.T = 0.3;
  p.cells = 40;
  p.stepping.policy = policy;
  p.stepping.cfl_factor = 0.3;
  p.stepping.safety = 2.0;
  p.dt = 7e-4;  // used by the fixed policy only
  p.observe.history = true;
  return p;
}

TEST(Policies, EveryPolicyEndsExactlyAtT) {
  for (auto policy : {TimeStepPolicy::fixed, TimeStepPolicy::cfl, TimeStepPolicy::adaptive,
                      TimeStepPolicy::min}) {
    const RunResult r = run(policy_case(policy));
    ASSERT_TRUE(r.stable) << to_string(policy);
    EXPECT_EQ(r.history.back().time, 0.3) << to_string(policy);  // exactly, not nearly
    EXPECT_EQ(r.history.size(), static_cast<std::size_t>(r.steps));
    EXPECT_GT(r.dt_min, 0);
    EXPECT_LE(r.dt_min, r.dt_max);
  }
}

TEST(Policies, CflStepIsTheCourantFactorTimesHOverC) {
  const RunResult r = run(policy_case(TimeStepPolicy::cfl));
  const double dt = 0.3 * (1.0 / 40) / 8.0;  // C h / c, c = sqrt(64)
  EXPECT_DOUBLE_EQ(r.dt_max, dt);
  EXPECT_DOUBLE_EQ(r.dt_min, dt);
  EXPECT_EQ(r.steps, static_cast<std::int64_t>(std::ceil(0.3 / dt - 1e-9)));
  EXPECT_NEAR(r.courant, 0.3, 1e-12);
}

TEST(Policies, AdaptiveStepFollowsTheBoundOfTheCurrentState) {
  RunParams p = policy_case(TimeStepPolicy::adaptive);
  const RunResult r = run(p);
  // dt_n = s * bound after step n - 1: compare every step with the recorded bounds.
  for (std::size_t k = 1; k + 1 < r.history.size(); ++k) {
    const double dt = r.history[k].time - r.history[k - 1].time;
    EXPECT_NEAR(dt, p.stepping.safety * *r.history[k - 1].dt_stable, 1e-12 * dt) << k;
  }
  EXPECT_LT(r.dt_min, r.dt_max);  // the bound moves with the state
}

TEST(Policies, MinPolicyNeverExceedsEitherLimit) {
  const RunResult r = run(policy_case(TimeStepPolicy::min));
  EXPECT_LE(r.dt_max, 0.3 * (1.0 / 40) / 8.0 * (1 + 1e-12));
  const RunResult adaptive = run(policy_case(TimeStepPolicy::adaptive));
  EXPECT_GE(r.steps, adaptive.steps);
}

TEST(Policies, AnAdaptiveRunThatNeedsTooManyStepsStopsWithAVerdict) {
  RunParams p = policy_case(TimeStepPolicy::adaptive);
  p.max_steps = 50;
  const RunResult r = run(p);
  EXPECT_FALSE(r.stable);
  ASSERT_TRUE(r.failure);
  EXPECT_EQ(r.failure->reason, FailureReason::step_limit);
  EXPECT_EQ(r.steps, 50);
}

// The exact motion's crossings (Table 2's counting rules): a full period of the bar's motion
// crosses every boundary as often rightward as leftward, no boundary is crossed by two particles
// in one small step, and GIMP's count at a small step is the exact motion's to within the
// solver's error.
TEST(Run, ExactCrossingsAreWhatASmallStepCountsAndEachRuleIsConsistent) {
  RunParams p;
  p.E = 4;  // c = 2: T = 1 is one period of sin(c pi t)
  p.A = 0.015;
  p.T = 1;
  p.dt = 1e-4;
  const ExactCrossings x = exact_crossings(p, 10000);
  EXPECT_GT(x.every, 0);
  EXPECT_EQ(2 * x.rightward, x.every);
  EXPECT_EQ(x.per_boundary, x.every);
  EXPECT_EQ(x.changes, x.every);
  EXPECT_LE(x.particles_moved, p.cells * p.ppc);
  // Sampled at the quarter periods only, the motion is seen at its extremes: the same count.
  EXPECT_EQ(exact_crossings(p, 4).every, x.every);
  // Sampled at the half periods only, every particle is seen at rest: nothing crossed.
  EXPECT_EQ(exact_crossings(p, 2).every, 0);
  const RunResult r = run(p);
  ASSERT_TRUE(r.crossings);
  EXPECT_NEAR(double(*r.crossings), double(x.every), 0.05 * double(x.every));
}

}  // namespace
}  // namespace mpmstab
