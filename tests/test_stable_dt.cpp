// Eq. (108) against a state worked by hand, for each interpretation option and method.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "analysis/stable_dt.hpp"

namespace mpmstab {
namespace {

// Two particles, F = {1.1, 0.8}, E = 16 so sigma = E (F - 1) = {1.6, -3.2},
// sigma F = {1.76, -2.56}; three nodes with v = {0, 3, -4}: ||v||_2 = 5, ||v||_max = 4.
// h = 0.01, m = 2, l = h / m = 0.005.
struct HandState {
  Particles P;
  Grid G;
  HandState() : G(2, Boundary::dirichlet) {
    P.resize(2);
    P.F << 1.1, 0.8;
    P.sigma = 16.0 * (P.F - 1.0);
    G.velocity.setZero();
    G.velocity.segment(Grid::kOffset, 3) << 0.0, 3.0, -4.0;
    G.velocity[0] = 99.0;  // a padding slot: not a node, must not enter ||v||
  }
};

TEST(StableDt, InputsAreTheMaximaAndTheNodalNorm) {
  HandState s;
  const auto l2 = stable_dt_inputs(s.P, s.G, VelocityNorm::l2, Method::gimp);
  EXPECT_DOUBLE_EQ(l2.F_max, 1.1);
  EXPECT_NEAR(l2.sigma_max, 3.2, 1e-14);
  EXPECT_NEAR(l2.sigmaF_max, 2.56, 1e-14);
  EXPECT_DOUBLE_EQ(l2.v_norm, 5.0);
  EXPECT_DOUBLE_EQ(stable_dt_inputs(s.P, s.G, VelocityNorm::max, Method::gimp).v_norm, 4.0);
}

// dt = h sqrt(m) / (4 m (sqrt(E) + F_max + ||v||) + 9 h sqrt(E) (F_max + s sigma_max + P))
// with s = 1/sqrt(E) = 1/4 (scaled) or 1 (raw), and for GIMP P = 2 / (l sqrt m) s (sigma F)_max
// = 282.8427 s 2.56, for MPM P = 0. Worked out:
//   gimp scaled l2: 0.0141421 / (8 (4 + 1.1 + 5) + 0.36 (1.1 + 0.8 + 181.019)) = 9.64340e-5
//   gimp scaled max:                  ... ||v|| = 4 ...                          = 1.01998e-4
//   gimp raw l2:   0.0141421 / (80.8 + 0.36 (1.1 + 3.2 + 724.077))              = 4.12288e-5
//   gimp raw max:                                                               = 4.22133e-5
//   mpm scaled l2: 0.0141421 / (80.8 + 0.36 (1.1 + 0.8))                        = 1.73557e-4
//   mpm scaled max: 0.0141421 / (72.8 + 0.684)                                  = 1.92452e-4
//   mpm raw l2:    0.0141421 / (80.8 + 0.36 (1.1 + 3.2))                        = 1.71736e-4
//   mpm raw max:                                                                = 1.90215e-4
TEST(StableDt, Eq108ByHandForEveryOption) {
  HandState s;
  struct Case {
    Method method;
    StressScaling sigma;
    VelocityNorm vnorm;
    double expected;
  };
  const Case cases[] = {
      {Method::gimp, StressScaling::scaled, VelocityNorm::l2, 9.643397855505521e-05},
      {Method::gimp, StressScaling::scaled, VelocityNorm::max, 1.0199810752416884e-04},
      {Method::gimp, StressScaling::raw, VelocityNorm::l2, 4.122881166763816e-05},
      {Method::gimp, StressScaling::raw, VelocityNorm::max, 4.221333374153046e-05},
      {Method::mpm, StressScaling::scaled, VelocityNorm::l2, 1.7355720906841776e-04},
      {Method::mpm, StressScaling::scaled, VelocityNorm::max, 1.924519027778966e-04},
      {Method::mpm, StressScaling::raw, VelocityNorm::l2, 1.7173623674808074e-04},
      {Method::mpm, StressScaling::raw, VelocityNorm::max, 1.902154143182191e-04},
  };
  for (const auto& c : cases) {
    const StableDtGeometry geo{c.method, 16.0, 0.01, 2, 0.005};
    const double dt = stable_dt(stable_dt_inputs(s.P, s.G, c.vnorm, c.method), geo, c.sigma);
    EXPECT_NEAR(dt / c.expected, 1.0, 1e-12)
        << to_string(c.method) << " " << to_string(c.sigma) << " " << to_string(c.vnorm);
  }
}

// cpGIMP: l = min_p F_p h / m = 0.8 * 0.005 = 0.004 in the position term
// 2 / (l sqrt m) s (sigma F)_max = 353.553 s 2.56:
//   scaled l2:  0.0141421 / (80.8 + 0.36 (1.1 + 0.8 + 226.274))   = 8.67921e-5
//   scaled max: 0.0141421 / (72.8 + 0.36 (1.1 + 0.8 + 226.274))   = 9.12733e-5
//   raw l2:     0.0141421 / (80.8 + 0.36 (1.1 + 3.2 + 905.097))   = 3.46466e-5
TEST(StableDt, CpGimpUsesTheSmallestCurrentParticleWidth) {
  HandState s;
  struct Case {
    StressScaling sigma;
    VelocityNorm vnorm;
    double expected;
  };
  const Case cases[] = {
      {StressScaling::scaled, VelocityNorm::l2, 8.679207795264768e-05},
      {StressScaling::scaled, VelocityNorm::max, 9.127332565438801e-05},
      {StressScaling::raw, VelocityNorm::l2, 3.464657368816234e-05},
  };
  const StableDtGeometry geo{Method::cpgimp, 16.0, 0.01, 2, 0.005};
  for (const auto& c : cases) {
    const auto in = stable_dt_inputs(s.P, s.G, c.vnorm, Method::cpgimp);
    EXPECT_DOUBLE_EQ(in.F_min, 0.8);
    EXPECT_NEAR(stable_dt(in, geo, c.sigma) / c.expected, 1.0, 1e-12)
        << to_string(c.sigma) << " " << to_string(c.vnorm);
  }
  // Undeformed, cpGIMP's bound is uGIMP's.
  s.P.F.setConstant(1.0);
  s.P.sigma.setConstant(2.0);
  const StableDtGeometry gimp{Method::gimp, 16.0, 0.01, 2, 0.005};
  const auto in = stable_dt_inputs(s.P, s.G, VelocityNorm::l2, Method::cpgimp);
  EXPECT_EQ(stable_dt(in, geo, StressScaling::scaled), stable_dt(in, gimp, StressScaling::scaled));
}

TEST(StableDt, FiniteAndPositiveForEveryFiniteStateEvenWhenSigmaTimesFOverflows) {
  for (double F : {1e-300, 1e-10, 1.0, 1e200, 1e308}) {
    for (double sigma : {0.0, 1e-300, 1.0, 1e200, 1e308}) {
      Particles P;
      P.resize(2);
      P.F << F, 0.5 * F;
      P.sigma << sigma, -sigma;
      Grid G(1, Boundary::dirichlet);
      G.velocity.setConstant(1e300);
      for (auto scaling : {StressScaling::scaled, StressScaling::raw}) {
        const StableDtGeometry geo{Method::gimp, 1e8, 1e-5, 1, 1e-5};
        const double dt =
            stable_dt(stable_dt_inputs(P, G, VelocityNorm::l2, Method::gimp), geo, scaling);
        EXPECT_TRUE(std::isfinite(dt)) << F << " " << sigma;
        EXPECT_GT(dt, 0.0) << F << " " << sigma;
      }
    }
  }
}

TEST(StableDt, FinitePositiveAndMonotoneAtExtremeStates) {
  const StableDtGeometry geo{Method::gimp, 1e8, 1e-5, 8, 1e-5 / 8};
  double previous = std::numeric_limits<double>::infinity();
  for (double scale : {0.0, 1e-300, 1e-10, 1.0, 1e10, 1e100, 1e300}) {
    const StableDtInputs in{scale, scale, scale, scale};
    const double dt = stable_dt(in, geo, StressScaling::raw);
    EXPECT_TRUE(std::isfinite(dt)) << scale;
    EXPECT_GE(dt, 0.0) << scale;
    EXPECT_LE(dt, previous) << scale;  // a larger state never allows a larger step
    previous = dt;
  }
  // At rest the bound is h sqrt(m) / (4 m sqrt(E)) = sqrt(m) h / (4 m c).
  const double at_rest = stable_dt({0, 0, 0, 0}, geo, StressScaling::scaled);
  EXPECT_NEAR(at_rest, 1e-5 * std::sqrt(8.0) / (4 * 8 * 1e4), 1e-25);
}

}  // namespace
}  // namespace mpmstab
