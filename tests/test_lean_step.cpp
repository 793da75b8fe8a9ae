// The lean loop of `make bench-versions` (lean_step.cpp) computes what the solver computes: the
// same run from the same state ends at the same particle state, up to the rounding of sums
// taken in another order, for every basis it has. Without this, its speed would not be that of
// the same algorithm.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "lean_step.hpp"
#include "run/run.hpp"

namespace {

using mpmstab::Method;

TEST(LeanStep, EndsWhereTheSolverEndsForEveryBasisItHas) {
  for (Method m : {Method::mpm, Method::gimp, Method::bspline2, Method::bspline3}) {
    ASSERT_TRUE(mpmstab::lean::supports(m));
    mpmstab::RunParams p;
    p.method = m;
    p.E = 64;
    p.A = 0.015;
    p.dt = 1e-4;
    p.T = 0.05;  // 500 steps, 0.4 wave passes: every particle moves across its cell's nodes
    p.observe.final_state = true;
    const mpmstab::RunResult solver = mpmstab::run(p);
    ASSERT_TRUE(solver.final_state);
    const mpmstab::lean::State start = mpmstab::lean::bar_state(p);
    mpmstab::lean::State end;
    const auto timing = mpmstab::lean::run(p, start, &end);
    EXPECT_EQ(timing.particle_steps, solver.steps * solver.particles) << to_string(m);
    const auto& f = *solver.final_state;
    double dx = 0, dv = 0, dF = 0, moved = 0;
    for (std::size_t i = 0; i < end.x.size(); ++i) {
      const auto j = static_cast<Eigen::Index>(i);
      dx = std::max(dx, std::abs(end.x[i] - f.x[j]));
      dv = std::max(dv, std::abs(end.v[i] - f.v[j]));
      dF = std::max(dF, std::abs(end.F[i] - f.F[j]));
      moved = std::max(moved, std::abs(f.x[j] - start.x[i]));
    }
    EXPECT_GT(moved, 1e-3) << to_string(m);  // the comparison is of a run that did something
    EXPECT_LT(dx, 1e-12) << to_string(m);
    EXPECT_LT(dv, 1e-10) << to_string(m);
    EXPECT_LT(dF, 1e-11) << to_string(m);
  }
}

TEST(LeanStep, HasOnlyTheBasesItImplements) {
  EXPECT_FALSE(mpmstab::lean::supports(Method::cpdi));
  EXPECT_FALSE(mpmstab::lean::supports(Method::cpgimp));
}

}  // namespace
