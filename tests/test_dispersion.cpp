// The dispersion of the schemes (core/analysis/dispersion.hpp) and the mode scene
// (core/scenes/scene.hpp): the phase speed of the physical branch against closed forms, the cells
// per wavelength for a phase error, the period measured by runs of the mode scene against the
// predicted one, and the scene's exact solution.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "analysis/dispersion.hpp"
#include "base/params.hpp"
#include "scenes/bar.hpp"
#include "scenes/mode.hpp"
#include "scenes/scene_registry.hpp"
#include "scenes/steffen.hpp"
#include "scenes/validate.hpp"
#include "step/simulation.hpp"

namespace mpmstab {
namespace {

constexpr double kPi = std::numbers::pi;

RunParams scheme(Method m, int ppc = 2, Transfer t = Transfer::flip) {
  RunParams p;
  p.method = m;
  p.ppc = ppc;
  p.transfer = t;
  return p;
}

// (a) Consistency: c_num / c -> 1 as kh -> 0, at second order (the error falls by about 4 when
// kh halves).
TEST(Dispersion, PhaseSpeedTendsToOneAsKhTendsToZero) {
  for (const Method m : {Method::mpm, Method::gimp, Method::bspline3}) {
    for (const double C : {0.1, 0.4}) {
      SCOPED_TRACE(std::string(to_string(m)) + " C = " + std::to_string(C));
      const auto branch = dispersion_branch(scheme(m), C, {kPi / kDispersionSamples, 0.05, 0.1});
      EXPECT_LT(std::abs(branch[0].phase_speed - 1), 1e-5);
      const double e1 = std::abs(branch[1].phase_speed - 1),
                   e2 = std::abs(branch[2].phase_speed - 1);
      EXPECT_GT(e2, 3 * e1);
      EXPECT_LT(e2, 5 * e1);
      for (const auto& d : branch)
        EXPECT_LE(d.damping, 1 + 1e-8);  // FLIP below the limit: no amplification
    }
  }
}

// (b) The semi-discrete limit C -> 0 of linear MPM (USL), in closed form. With the particles'
// quadrature, the grid's consistent mass M = S diag(m) S^T and the lumped one M_L = diag(M 1)
// have the symbol ratio Q(kh) = M / M_L: cos^2(kh / 2) for one particle per cell at the cell's
// centre, (5 + 3 cos kh) / 8 for two at its quarters. The stiffness is that of linear finite
// elements (the particles' volumes sum to h in each cell), the lumped-mass result being
// c_num / c = sin(kh / 2) / (kh / 2). FLIP maps the particle velocities to the grid every step:
// the grid velocity w obeys dw/dt = M_L^-1 M M_L^-1 f, so c_num / c = sqrt(Q) sin(kh/2) / (kh/2)
// (for one particle per cell, sin(kh) / kh). FMPM(k) replaces the lumped velocity by the
// series for M^-1: for large k the consistent-mass result sin(kh/2) / (kh/2) / sqrt(Q). The
// lumped-mass result is the geometric mean of the two. Checked at C = 1e-3, where the time
// step's own error is of order C^2 (kh)^2 < 1e-5, to a relative 2e-5.
TEST(Dispersion, LinearMpmAtATinyCourantNumberIsTheSemiDiscreteResult) {
  const double C = 1e-3;
  const std::vector<double> khs = {0.1, 0.3, 0.5, 0.7};
  const auto lumped = [](double kh) { return std::sin(kh / 2) / (kh / 2); };
  const auto q1 = [](double kh) { return std::pow(std::cos(kh / 2), 2); };
  const auto q2 = [](double kh) { return (5 + 3 * std::cos(kh)) / 8; };
  const auto flip1 = dispersion_branch(scheme(Method::mpm, 1), C, khs);
  const auto flip2 = dispersion_branch(scheme(Method::mpm, 2), C, khs);
  RunParams full = scheme(Method::mpm, 2, Transfer::fmpm);
  full.fmpm_order = 8;  // (1 - Q)^8 < 1e-7 at kh <= 0.7
  const auto fmpm2 = dispersion_branch(full, C, khs);
  for (std::size_t i = 0; i < khs.size(); ++i) {
    const double kh = khs[i];
    SCOPED_TRACE("kh = " + std::to_string(kh));
    EXPECT_NEAR(flip1[i].phase_speed, std::sin(kh) / kh, 2e-5);
    EXPECT_NEAR(flip1[i].phase_speed, std::sqrt(q1(kh)) * lumped(kh), 2e-5);
    EXPECT_NEAR(flip2[i].phase_speed, std::sqrt(q2(kh)) * lumped(kh), 2e-5);
    EXPECT_NEAR(fmpm2[i].phase_speed, lumped(kh) / std::sqrt(q2(kh)), 2e-5);
    EXPECT_NEAR(std::sqrt(flip2[i].phase_speed * fmpm2[i].phase_speed), lumped(kh), 2e-5);
  }
}

// The cells per wavelength are where the phase error reaches the tolerance: within it on every
// longer wave of a fine scan, at it (to the bisection's accuracy) at the wavelength returned.
TEST(Dispersion, CellsPerWavelengthIsWhereThePhaseErrorReachesTheTolerance) {
  for (const Method m : {Method::mpm, Method::bspline3}) {
    const double C = 0.25;
    const auto cells = cells_per_wavelength(scheme(m), C);
    ASSERT_TRUE(cells.has_value()) << to_string(m);
    const double kh_max = 2 * kPi / *cells;
    std::vector<double> khs;
    for (int j = 1; j <= 50; ++j)
      khs.push_back(kh_max * j / 50);
    const auto branch = dispersion_branch(scheme(m), C, khs);
    for (const auto& d : branch)
      EXPECT_LE(std::abs(d.phase_speed - 1), kPhaseTolerance * (1 + 1e-4)) << d.kh;
    EXPECT_NEAR(std::abs(branch.back().phase_speed - 1), kPhaseTolerance, 1e-4 * kPhaseTolerance)
        << to_string(m);
  }
}

// The wave error after n steps, |lambda^n - e^{i C kh n}|, in the cases with a closed form: an
// exact eigenvalue gives 0, a pure phase lag delta per step 2 |sin(n delta / 2)|, a pure damping
// 1 - |lambda|^n; a branch that stops propagating has no phase to carry the wave (infinite).
TEST(Dispersion, AmplitudeErrorIsDampingAndPhaseErrorTogether) {
  const double C = 0.5, kh = 0.2, periods = 3;
  const double steps = periods * 2 * kPi / (C * kh);
  DispersionPoint d;
  d.kh = kh;
  d.damping = 1;
  d.phase = C * kh;
  EXPECT_NEAR(amplitude_error(d, C, periods), 0, 1e-12);
  const double lag = 1e-3;  // per step
  d.phase = C * kh - lag;
  EXPECT_NEAR(amplitude_error(d, C, periods), 2 * std::abs(std::sin(steps * lag / 2)), 1e-12);
  d.phase = C * kh;
  d.damping = 0.999;
  EXPECT_NEAR(amplitude_error(d, C, periods), 1 - std::pow(0.999, steps), 1e-12);
  // Twice the periods: a phase error grows with them.
  d.damping = 1;
  d.phase = C * kh - lag;
  EXPECT_GT(amplitude_error(d, C, 2 * periods), 1.9 * amplitude_error(d, C, periods));
  d.propagates = false;
  EXPECT_TRUE(std::isinf(amplitude_error(d, C, periods)));
  EXPECT_THROW(amplitude_error(d, 0, periods), std::invalid_argument);
}

// The cells per wavelength for a wave error are where the error reaches the tolerance: within it
// on every longer wave of a fine scan, at it (to the bisection's accuracy) at the wavelength
// returned. FLIP barely damps a long wave below its limit, so its wave error after N periods is
// its phase drift, 2 pi N |c_num / c - 1| to first order: the cells it needs are those for a
// phase error of tolerance / (2 pi N), within 1%. PIC damps every wave: it needs more cells
// per wavelength than the scan's first kh holds (2 kDispersionSamples), found by halving below
// it, and none up to kMaxCellsPerWavelength for a tolerance a thousand times smaller.
TEST(Dispersion, CellsPerWavelengthForAWaveErrorIsWhereItReachesTheTolerance) {
  const double C = 0.5, periods = 10, tolerance = 0.01;
  for (const Transfer t : {Transfer::flip, Transfer::pic}) {
    const RunParams p = scheme(Method::gimp, 2, t);
    SCOPED_TRACE(std::string(to_string(t)));
    const auto cells = cells_per_wavelength_amplitude(p, C, periods, tolerance);
    ASSERT_TRUE(cells.has_value());
    const double kh_max = 2 * kPi / *cells;
    for (int j = 1; j <= 20; ++j) {
      const double kh = kh_max * j / 20;
      EXPECT_LE(amplitude_error(dispersion_at(p, C, kh), C, periods), tolerance * (1 + 1e-4)) << kh;
    }
    EXPECT_NEAR(amplitude_error(dispersion_at(p, C, kh_max), C, periods), tolerance,
                1e-4 * tolerance);
    if (t == Transfer::flip) {
      const auto phase_only = cells_per_wavelength(p, C, tolerance / (2 * kPi * periods));
      ASSERT_TRUE(phase_only.has_value());
      EXPECT_NEAR(*cells / *phase_only, 1, 1e-2);
      EXPECT_LT(*cells, 2 * kDispersionSamples);
    } else {
      EXPECT_GT(*cells, 2 * kDispersionSamples);
      EXPECT_GT(*cells, 10 * *cells_per_wavelength(p, C));  // the phase error alone: far fewer
      EXPECT_FALSE(cells_per_wavelength_amplitude(p, C, periods, tolerance / 1000).has_value());
    }
  }
  // A tolerance no wave error reaches (at most 1 + |lambda|^n <= 2 below the limit, where the
  // branch propagates up to kh = pi): the shortest wave of the grid, 2 cells.
  EXPECT_EQ(cells_per_wavelength_amplitude(scheme(Method::gimp), C, periods, 2.5), 2.0);
}

// (c) A run of the mode scene measures the period the branch predicts: within a relative 1e-5
// (measured: about 1e-8; the prediction's own error is that of the symbol's central
// differences, the measurement's that of the quartic through the samples at each turning
// point), while the exact period 1/c lies far further away: on 8 cells per wavelength at
// C = 0.25 the schemes' periods exceed it by 8% (MPM, GIMP) and 23% (the cubic B-spline).
TEST(Dispersion, MeasuredPeriodOfTheModeSceneIsThePredictedOne) {
  for (const Method m : {Method::mpm, Method::gimp, Method::bspline3}) {
    RunParams p = scheme(m);
    p.scene = SceneKind::mode;
    p.bc = Boundary::periodic;
    p.E = 1;
    p.A = 1e-6;
    p.cells = 8;
    p.dt = 0.25 / p.cells;  // C = 0.25
    p.T = 6;
    const double predicted = predicted_mode_period(p);
    const ModePeriod measured = measure_mode_period(p);
    SCOPED_TRACE(std::string(to_string(m)) + " predicted " + std::to_string(predicted) +
                 " measured " + std::to_string(measured.period));
    EXPECT_GE(measured.periods, 4);
    EXPECT_NEAR(measured.period / predicted, 1, 1e-5);
    EXPECT_LT(std::abs(measured.period - predicted), std::abs(measured.period - 1.0));
  }
}

// (d) The mode scene is posed with periodic boundaries only: validate names `bc`.
TEST(SceneMode, RefusesDirichletWalls) {
  RunParams p;
  p.scene = SceneKind::mode;
  p.bc = Boundary::dirichlet;
  const auto issues = validate(p);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].key, "bc");
  EXPECT_NE(issues[0].message.find("mode"), std::string::npos) << issues[0].message;
  p.bc = Boundary::periodic;
  EXPECT_TRUE(validate(p).empty());
  EXPECT_FALSE(scene_supports(SceneKind::mode, Boundary::dirichlet));
  EXPECT_TRUE(scene_supports(SceneKind::mode, Boundary::periodic));
  EXPECT_EQ(parse_scene("mode"), SceneKind::mode);
  EXPECT_EQ(to_string(SceneKind::mode), "mode");
}

// (e) The initial particle state is the exact solution at t = 0: displaced, at rest, with the
// exact F and stress.
TEST(SceneMode, InitialStateIsTheExactSolutionAtRest) {
  const ModeScene scene(9.0, 0.01);
  const int cells = 10, ppc = 3;
  const Particles P = scene.initial_particles(cells, ppc);
  ASSERT_EQ(P.size(), cells * ppc);
  for (Eigen::Index p = 0; p < P.size(); ++p) {
    const double X = P.X[p];
    EXPECT_NEAR(P.x[p] - X, scene.displacement(X, 0.0), 1e-15);
    EXPECT_NEAR(P.x[p] - X, 0.01 * std::sin(2 * kPi * X), 1e-15);
    EXPECT_EQ(P.v[p], scene.velocity(X, 0.0));
    EXPECT_EQ(P.v[p], 0.0);
    EXPECT_NEAR(P.F[p], 1 + 2 * kPi * 0.01 * std::cos(2 * kPi * X), 1e-15);
    EXPECT_NEAR(P.sigma[p], scene.stress(X, 0.0), 1e-13);
    EXPECT_NEAR(P.sigma[p], 9.0 * (P.F[p] - 1), 1e-15);
  }
  EXPECT_EQ(scene.material(), Material::linear);
  EXPECT_DOUBLE_EQ(scene.period(), 1.0 / 3.0);  // 1 / c, c = 3
}

// The exact solution is a free wave: rho0 u_tt = E u_XX with no body force, v = u_t and
// sigma = E u_X (central differences, a relative 1e-6), and its energy K + U is constant.
TEST(SceneMode, ExactSolutionIsAFreeWaveOfConstantEnergy) {
  const ModeScene scene(4.0, 0.02);
  const double d = 1e-4;
  for (double X : {0.1, 0.37, 0.62}) {
    for (double t : {0.013, 0.2, 0.77}) {
      const auto u = [&](double Y, double s) { return scene.displacement(Y, s); };
      const double u_tt = (u(X, t + d) - 2 * u(X, t) + u(X, t - d)) / (d * d);
      const double u_XX = (u(X + d, t) - 2 * u(X, t) + u(X - d, t)) / (d * d);
      EXPECT_NEAR(scene.rho0 * u_tt, scene.E * u_XX, 1e-5 * (1 + std::abs(u_tt)));
      EXPECT_EQ(scene.body_force(X, t), 0.0);
      EXPECT_NEAR(scene.velocity(X, t), (u(X, t + d) - u(X, t - d)) / (2 * d), 1e-7);
      EXPECT_NEAR(scene.stress(X, t), scene.E * (u(X + d, t) - u(X - d, t)) / (2 * d), 1e-6);
    }
  }
  const double total = kPi * kPi * scene.E * scene.A * scene.A;
  for (double t : {0.0, 0.1, 0.33}) {
    const ExactEnergy e = scene.exact_energy(t);
    EXPECT_NEAR(e.kinetic + e.strain, total, 1e-15);
    EXPECT_EQ(e.work, 0.0);
  }
}

// The mode scene declares no body force (the solver then never evaluates one); its body force
// at the particles is zero all the same.
TEST(SceneMode, HasNoBodyForce) {
  RunParams p;
  p.scene = SceneKind::mode;
  p.bc = Boundary::periodic;
  p.A = 1e-3;
  p.cells = 8;
  const auto scene = make_scene(p);
  ASSERT_NE(dynamic_cast<const ModeScene*>(scene.get()), nullptr);
  EXPECT_FALSE(scene->has_body_force());
  const Particles P = scene->initial_particles(p.cells, p.ppc);
  Eigen::ArrayXd b = Eigen::ArrayXd::Constant(P.size(), 1.0);
  scene->body_force_at(P.X)->evaluate(0.3, b);
  ASSERT_EQ(b.size(), P.size());
  EXPECT_TRUE((b == 0.0).all());
  for (const SceneKind kind : {SceneKind::bar, SceneKind::steffen}) {
    p.scene = kind;
    EXPECT_TRUE(make_scene(p)->has_body_force());
  }
}

}  // namespace
}  // namespace mpmstab
