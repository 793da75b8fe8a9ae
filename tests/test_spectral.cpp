// The spectral limit (core/analysis/spectral.hpp): the linearised map of a case derived by hand,
// the limit of that case in closed form, the limit independent of E, and runs just below and just
// above the limit of a small bar.
#include <gtest/gtest.h>

#include <cmath>

#include <complex>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/bloch.hpp"
#include "analysis/spectral.hpp"
#include "run/edge.hpp"
#include "run/run.hpp"
#include "step/simulation.hpp"

namespace mpmstab {
namespace {

// The bar at a tiny amplitude, where the linearised map governs: E = 1 (c = 1), A = 1e-6, its
// error over time observed.
RunParams tiny_bar(Method m, int cells, double T) {
  RunParams p;
  p.method = m;
  p.cells = cells;
  p.E = 1;
  p.A = 1e-6;
  p.T = T;
  p.observe.error_over_time = true;
  return p;
}

// MPM and GIMP with USL and USF, FLIP and PIC: the schemes whose limits the tests check against
// measured edges and the dense map, each a tiny_bar of `cells` cells to T.
std::vector<RunParams> linear_schemes(int cells, double T) {
  std::vector<RunParams> out;
  for (const Method m : {Method::mpm, Method::gimp}) {
    for (const UpdateOrder u : {UpdateOrder::usl, UpdateOrder::usf}) {
      for (const Transfer t : {Transfer::flip, Transfer::pic}) {
        RunParams p = tiny_bar(m, cells, T);
        p.update = u;
        p.transfer = t;
        out.push_back(p);
      }
    }
  }
  return out;
}

std::string name_of(const RunParams& p) {
  std::ostringstream s;
  s << to_string(p.method) << ' ' << to_string(p.update) << ' ' << to_string(p.transfer);
  return s.str();
}

RunParams two_cell_bar(double E) {
  RunParams p;
  p.method = Method::mpm;
  p.E = E;
  p.A = 0.01;
  p.dt = 1e-3;
  p.cells = 2;
  p.ppc = 1;
  return p;
}

// Two cells, one particle each (x = 1/4, 3/4), linear hat, Dirichlet walls, USL with FLIP: the
// one free node (x = 1/2) has S = 1/2 and G = +2, -2 for the two particles, m_1 = 1/2,
// V_p = 1/2. In the scaled state (v_0 / c, v_1 / c, e_0, e_1), e = F - 1, with C = c dt / h:
//   v_1^{n+1} / c = (v_0 + v_1) / 2c - C (e_0 - e_1)                 (grid update)
//   v_p' / c      = v_p / c - (C / 2) (e_0 - e_1)                     (FLIP)
//   e_0' = e_0 + C v_1^{n+1} / c,  e_1' = e_1 - C v_1^{n+1} / c       (stress update)
TEST(Spectral, MapOfTwoCellsOneParticleEachIsTheHandDerivedMatrix) {
  for (const double C : {0.3, 0.9, 1.4}) {
    const RunParams p = two_cell_bar(64);
    const Eigen::ArrayXd x = Simulation(p).particles().x;
    const Eigen::MatrixXd M = linear_step_map(p, x, C);
    Eigen::MatrixXd hand(4, 4);
    hand << 1, 0, -C / 2, C / 2,  //
        0, 1, -C / 2, C / 2,      //
        C / 2, C / 2, 1 - C * C, C * C, -C / 2, -C / 2, C * C, 1 - C * C;
    EXPECT_LT((M - hand).cwiseAbs().maxCoeff(), 1e-9) << "C = " << C << "\n" << M;
  }
}

// The same case in closed form: on (v_0 + v_1, e_0 - e_1) the map is [[1, -C], [C, 1 - 2C^2]],
// determinant 1 - C^2; for C > 1 its eigenvalues are real, and the smaller,
// a - sqrt(a^2 - a) with a = 1 - C^2, passes -1 at C^2 = 4/3. The other two modes are 1.
TEST(Spectral, LimitOfTheHandDerivedCaseIsTwoOverSqrtThree) {
  const SpectralLimit s = spectral_limit(two_cell_bar(64));
  ASSERT_TRUE(s.courant.has_value());
  EXPECT_NEAR(*s.courant, 2 / std::sqrt(3.0), 2e-4 * 2 / std::sqrt(3.0));
  EXPECT_GT(s.radius_above, 1.0);
  // The mode is the strain difference with the summed velocity: both particles move.
  EXPECT_NEAR(s.mode_strain[0], s.mode_strain[1], 1e-6);
  EXPECT_NEAR(s.mode_v[0], s.mode_v[1], 1e-6);
}

// In the scaled state the map depends on dt only through c dt / h: the limit is one Courant
// number for every E.
TEST(Spectral, LimitIsOneCourantNumberForEveryE) {
  RunParams p;
  p.method = Method::gimp;
  p.cells = 8;
  p.dt = 1e-3;
  p.E = 4;
  const auto a = spectral_limit(p).courant;
  p.E = 1e4;
  const auto b = spectral_limit(p).courant;
  ASSERT_TRUE(a && b);
  EXPECT_NEAR(*a, *b, 1e-4 * *a);
}

// A run of the bar at A = 1e-6 for T = 20 stays bounded at 0.9 of the limit and grows at 1.1.
TEST(Spectral, RunsBelowTheLimitStayBoundedAndAboveItGrow) {
  for (const Method m : {Method::mpm, Method::gimp}) {
    RunParams p = tiny_bar(m, 10, 20);
    const SpectralLimit s = spectral_limit(p);
    ASSERT_TRUE(s.courant.has_value());
    const double h = 1.0 / p.cells;
    p.dt = 0.9 * *s.courant * h;  // c = 1
    const RunResult below = run(p);
    EXPECT_TRUE(below.stable) << to_string(m);
    ASSERT_TRUE(below.max_error_over_time.has_value());
    EXPECT_LT(*below.max_error_over_time, 10 * p.A) << to_string(m);
    p.dt = 1.1 * *s.courant * h;
    const RunResult above = run(p);
    const bool grew = !above.stable || *above.max_error_over_time > 100 * p.A;
    EXPECT_TRUE(grew) << to_string(m) << " limit " << *s.courant;
  }
}

// The measured tiny-amplitude edge: the largest Courant number whose run of the bar at A = 1e-6
// for T = 200 (c = 1: 100 periods of the solution) stays bounded: it ends stable with an error
// over time of at most 3 A (a bounded run's error, phase error included, is at most 2 A; a
// growing mode passes 3 A). Found by bisection between 0.1 and 3, without reading the spectral
// limit.
// It agrees with the spectral limit within 5% for MPM and GIMP, USL and USF, FLIP and PIC.
TEST(Spectral, LimitAgreesWithTheMeasuredTinyAmplitudeEdgeWithinFivePercent) {
  for (RunParams p : linear_schemes(10, 200)) {
    const double h = 1.0 / p.cells;
    auto bounded = [&](double C) {
      p.dt = C * h;
      const RunResult r = run(p);
      return r.stable && *r.max_error_over_time <= 3 * p.A;
    };
    double lo = 0.1, hi = 3.0;
    ASSERT_TRUE(bounded(lo));
    ASSERT_FALSE(bounded(hi));
    while (hi - lo > 1e-3) {
      const double mid = 0.5 * (lo + hi);
      (bounded(mid) ? lo : hi) = mid;
    }
    const auto spectral = spectral_limit(p).courant;
    ASSERT_TRUE(spectral.has_value());
    EXPECT_NEAR(lo / *spectral, 1.0, 0.05)
        << name_of(p) << ": measured " << lo << ", spectral " << *spectral;
  }
}

// The spectral policy steps at s times the limit: at s = 0.5 the first step is half the limit and
// the run stays bounded; at s = 1.2 a run at A = 1e-6 grows.
TEST(Spectral, PolicyStepsAtAFractionOfTheLimit) {
  RunParams p = tiny_bar(Method::gimp, 10, 50);
  p.stepping.policy = TimeStepPolicy::spectral;
  p.stepping.safety = 0.5;
  const auto limit = bloch_limit(p).courant;  // what the record carries, a uniform layout
  ASSERT_TRUE(limit.has_value());
  const RunResult half = run(p);
  EXPECT_TRUE(half.stable);
  EXPECT_NEAR(half.dt_max, 0.5 * *limit / p.cells, 1e-12);  // c = 1, h = 1/10
  EXPECT_LE(*half.max_error_over_time, 3 * p.A);
  p.stepping.safety = 1.2;
  const RunResult above = run(p);
  EXPECT_TRUE(!above.stable || *above.max_error_over_time > 3 * p.A);
}

// The spectral policy's limit at a new layout skips the limiting mode, not the search: the same
// Courant number as spectral_limit's, bit for bit, on a jittered layout and with a starting guess.
TEST(Spectral, LimitWithoutTheModeIsTheSameCourantNumber) {
  for (const Method m : {Method::mpm, Method::gimp}) {
    RunParams p = tiny_bar(m, 10, 20);
    p.layout.jitter = 0.3;
    const Eigen::ArrayXd x = Simulation(p).particles().x;
    const SpectralLimit full = spectral_limit(p, x);
    ASSERT_TRUE(full.courant.has_value());
    EXPECT_EQ(spectral_courant_at(p, x), full.courant);
    const SpectralLimit near = spectral_limit(p, x, 1.05 * *full.courant);
    EXPECT_EQ(spectral_courant_at(p, x, 1.05 * *full.courant), near.courant);
  }
}

// Each record's Bloch limit skips the mode, not the search: bloch_limit's Courant number, bit for
// bit, for schemes whose symbols differ in size.
TEST(Bloch, LimitWithoutTheModeIsTheSameCourantNumber) {
  for (const Method m : {Method::mpm, Method::gimp}) {
    for (const Transfer t : {Transfer::flip, Transfer::apic}) {
      RunParams p = tiny_bar(m, 10, 20);
      p.transfer = t;
      const SpectralLimit full = bloch_limit(p);
      ASSERT_TRUE(full.courant.has_value());
      EXPECT_EQ(bloch_courant(p), full.courant);
    }
  }
}

// The Bloch symbol of linear MPM, one particle at each cell's centre, USL with FLIP, derived by
// hand. Node i lies between particles i - 1 and i; each particle gives 1/2 of its mass and
// momentum to its two nodes, so v_i = (v_{i-1} + v_i) / 2 and a_i = (c^2 / h)(e_i - e_{i-1}). For
// the mode (u, e) e^{i j theta}, u = v / c, C = c dt / h:
//   u' = u + C ((1 + e^{i theta}) / 2)(1 - e^{-i theta}) e = u + i C sin(theta) e
//   e' = e + C (e^{i theta} - 1)[(1 + e^{-i theta}) / 2 u + C (1 - e^{-i theta}) e]
//      = e + i C sin(theta) u - 4 C^2 sin^2(theta / 2) e.
// At theta = pi, S = diag(1, 1 - 4 C^2): the limit is C = 1 / sqrt(2).
TEST(Bloch, SymbolOfOneParticlePerCellIsTheHandDerivedMatrix) {
  RunParams p = two_cell_bar(64);
  p.ppc = 1;
  const std::complex<double> i(0, 1);
  for (const double C : {0.3, 0.7, 1.2}) {
    for (const double theta : {0.0, 0.4, 1.9, 3.14159265358979}) {
      const Eigen::MatrixXcd S = bloch_symbol(p, C, theta);
      ASSERT_EQ(S.rows(), 2);
      Eigen::MatrixXcd hand(2, 2);
      const double s = std::sin(theta / 2);
      hand << 1.0, i * C * std::sin(theta), i * C * std::sin(theta), 1.0 - 4 * C * C * s * s;
      EXPECT_LT((S - hand).cwiseAbs().maxCoeff(), 1e-9)
          << "C = " << C << ", theta = " << theta << "\n"
          << S;
    }
  }
  const SpectralLimit b = bloch_limit(p);
  ASSERT_TRUE(b.courant.has_value());
  EXPECT_NEAR(*b.courant, 1 / std::sqrt(2.0), 2e-4);
  ASSERT_TRUE(b.wavenumber.has_value());
  EXPECT_DOUBLE_EQ(*b.wavenumber, 1.0);  // the mode alternating from cell to cell
}

// The Bloch limit of the interior is the dense limit of a bar of 30 cells within 0.5% for MPM and
// GIMP with USL and USF, FLIP and PIC (the walls' own modes do not limit these schemes; on 50
// cells the two agree within 0.11%), and the same for every number of cells.
TEST(Bloch, AgreesWithTheDenseLimitOfABar) {
  for (RunParams p : linear_schemes(30, 1)) {
    const auto bloch = bloch_limit(p).courant;
    const auto dense = spectral_limit(p).courant;
    ASSERT_TRUE(bloch && dense);
    EXPECT_NEAR(*bloch / *dense, 1.0, 5e-3) << name_of(p);
    p.cells = 1000;
    EXPECT_EQ(bloch_limit(p).courant, bloch);
  }
}

// At the uniform layout cpGIMP's and CPDI's weights are GIMP's (each particle's domain lies in one
// cell at F = 1), so their limits must be GIMP's, by the dense map and by the Bloch symbol; the
// kink of their weights at F = 1 once gave a limit far below it.
TEST(Bloch, CpGimpAndCpdiHaveGimpsLimitAtTheUniformLayout) {
  RunParams p;
  p.cells = 20;
  p.method = Method::gimp;
  const auto gimp_dense = spectral_limit(p).courant, gimp_bloch = bloch_limit(p).courant;
  ASSERT_TRUE(gimp_dense && gimp_bloch);
  for (const Method m : {Method::cpgimp, Method::cpdi}) {
    p.method = m;
    const auto dense = spectral_limit(p).courant, bloch = bloch_limit(p).courant;
    ASSERT_TRUE(dense && bloch) << to_string(m);
    EXPECT_NEAR(*dense / *gimp_dense, 1.0, 1e-6) << to_string(m);
    EXPECT_NEAR(*bloch / *gimp_bloch, 1.0, 1e-6) << to_string(m);
  }
}

// A run records the Bloch limit of a uniform layout, the dense limit of a jittered one only
// when asked, and the spectral policy's first step is s times the recorded limit.
TEST(Bloch, EveryRunRecordsTheLimitOfItsInitialLayout) {
  RunParams p;
  p.method = Method::gimp;
  p.cells = 20;
  p.E = 4;
  p.A = 1e-3;
  p.dt = 1e-3;
  p.T = 1e-2;
  const RunResult uniform = run(p);
  ASSERT_TRUE(uniform.courant_spectral.has_value());
  EXPECT_EQ(uniform.spectral_analysis, SpectralAnalysis::bloch);
  EXPECT_NEAR(*uniform.dt_spectral, *uniform.courant_spectral * (1.0 / 20) / 2, 1e-15);
  p.layout.jitter = 0.5;
  EXPECT_FALSE(run(p).courant_spectral.has_value());  // not uniform, not asked
  p.observe.spectral = true;
  const RunResult jittered = run(p);
  ASSERT_TRUE(jittered.courant_spectral.has_value());
  EXPECT_EQ(jittered.spectral_analysis, SpectralAnalysis::dense);
  EXPECT_NE(*jittered.courant_spectral, *uniform.courant_spectral);
}

// The edge search with a bound finds the tiny-amplitude edge: the largest dt that stays within
// 3 A to T = 200 (2600 steps), within 2% of the spectral limit for MPM (USL, FLIP), where
// survival alone does not see the growth before T.
TEST(Bloch, TheBoundedEdgeSearchFindsTheLimit) {
  RunParams p = tiny_bar(Method::mpm, 10, 200);
  EdgeOptions o;
  o.tolerance = 0.005;
  o.bound = 3;
  const EdgeResult bounded = find_edge(p, o);
  const auto limit = spectral_limit(p).courant;  // of this bar, walls included
  ASSERT_TRUE(bounded.dt_edge && limit);
  EXPECT_NEAR(*bounded.dt_edge / (*limit * 0.1), 1.0, 0.02);
  EdgeOptions survive_only;
  survive_only.tolerance = 0.005;
  const EdgeResult survival = find_edge(p, survive_only);
  ASSERT_TRUE(survival.dt_edge.has_value());
  EXPECT_GT(*survival.dt_edge, 1.05 * *bounded.dt_edge);
}

// The layout: shift moves every particle by the same fraction of the spacing, jitter each by
// its own fixed amount; both keep every particle in its cell and in order, and the same
// parameters give the same layout.
TEST(Layout, ShiftAndJitterMoveParticlesWithinTheirCells) {
  RunParams p;
  p.cells = 10;
  p.ppc = 3;
  p.layout.shift = 0.4;
  const Eigen::ArrayXd shifted = Simulation(p).particles().X;
  const double spacing = 0.1 / 3;
  EXPECT_NEAR(shifted[0], 0.9 * spacing, 1e-15);
  EXPECT_NEAR(shifted[4] - shifted[3], spacing, 1e-15);
  p.layout.shift = 0;
  p.layout.jitter = 0.9;
  const Eigen::ArrayXd a = Simulation(p).particles().X, b = Simulation(p).particles().X;
  EXPECT_TRUE((a == b).all());
  double largest = 0;
  for (Eigen::Index k = 0; k < a.size(); ++k) {
    const double centre = (double(k) + 0.5) * spacing;
    largest = std::max(largest, std::abs(a[k] - centre));
    EXPECT_LE(std::abs(a[k] - centre), 0.45 * spacing + 1e-15);
    EXPECT_EQ(int(a[k] / 0.1), int(k / 3));
  }
  EXPECT_GT(largest, 0.3 * spacing);  // it does move them
}

}  // namespace
}  // namespace mpmstab
