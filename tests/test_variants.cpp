// The implementation choices of params.hpp, each shown to do what it says: transfers, ghost
// nodes, update orders, body-force time and cpGIMP's deforming supports, on whole steps.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "base/failure.hpp"
#include "run/run.hpp"
#include "scenes/bar.hpp"
#include "scenes/validate.hpp"
#include "step/phases.hpp"
#include "step/simulation.hpp"
#include "support.hpp"

namespace mpmstab {
namespace {

constexpr double kPi = std::numbers::pi;

using test_support::quick_case;

Simulation advanced(const RunParams& p, int steps) {
  Simulation sim(p);
  for (int k = 1; k <= steps; ++k)
    sim.advance_to(k * p.dt);
  return sim;
}

// ---------------------------------------------------------------------------------------------
// Transfers

// Kinetic energy of a free standing wave after one period, relative to the start: the bar with
// A = 0 (no body force) and the planted velocity v = V sin(2 pi X), whose period is 1 / c.
double kinetic_energy_kept(Transfer transfer) {
  RunParams p = quick_case();
  p.A = 0;
  p.transfer = transfer;
  p.flip_fraction = 0.5;
  Simulation sim(p);
  Particles& P = sim.particles();
  P.v = 0.01 * (2 * kPi * P.X).sin();
  auto kinetic = [&] { return 0.5 * (P.mass * P.v.square()).sum(); };
  const double start = kinetic();
  const int steps = 500;  // one period, 1 / c = 0.5
  for (int k = 1; k <= steps; ++k)
    sim.advance_to(k * p.dt);
  return kinetic() / start;
}

TEST(Transfer, PicDampsAFreeVibrationMoreThanFlipAndABlendLiesBetween) {
  const double flip = kinetic_energy_kept(Transfer::flip);
  const double blend = kinetic_energy_kept(Transfer::blend);
  const double pic = kinetic_energy_kept(Transfer::pic);
  EXPECT_GT(flip, 0.95);  // FLIP keeps the energy of a resolved mode
  EXPECT_LT(pic, 0.9 * flip);
  EXPECT_LT(pic, blend);
  EXPECT_LT(blend, flip);
}

// ---------------------------------------------------------------------------------------------
// Ghost nodes

// Mass on the distinct nodes of the grid after one step from a state whose first particle was
// moved towards the wall X = 0, so that its uGIMP support [x - lp, x + lp] crosses it.
double mass_on_nodes(Walls walls, double* total) {
  RunParams p = quick_case();
  p.walls = walls;
  Simulation sim(p);
  const double h = 1.0 / p.cells;
  sim.particles().x[0] = h / 8;  // lp = h / 4: an eighth of a cell beyond the wall
  sim.advance_to(p.dt);
  const Grid& G = sim.grid();
  *total = sim.particles().mass.sum();
  return G.mass.segment(G.first_node_slot(), G.nodes()).sum();
}

TEST(Walls, GhostNodesKeepThePartitionOfUnityAtAWallAndClipDoesNot) {
  double total = 0;
  const double ghost = mass_on_nodes(Walls::ghost, &total);
  EXPECT_NEAR(ghost, total, 1e-15);
  // Clip drops the part beyond the wall: S_{-1} m_0 with S_{-1} = (h/8)^2 / (2 h) / (2 lp) = 1/64.
  const double clip = mass_on_nodes(Walls::clip, &total);
  const double m0 = 1.0 / 40;
  EXPECT_NEAR(total - clip, m0 / 64, 1e-15);
}

TEST(Walls, GhostNodesMoveFreelyAndTheWallsStayFixed) {
  RunParams p = quick_case();
  p.walls = Walls::ghost;
  Simulation sim(p);
  sim.particles().x[0] = 1.0 / 160;
  sim.advance_to(p.dt);
  const Grid& G = sim.grid();
  const int o = Grid::kOffset;
  ASSERT_GT(G.mass[o - 1], 0);
  EXPECT_NE(G.velocity[o - 1], 0.0);  // node -1: the particle's momentum over its mass share
  EXPECT_DOUBLE_EQ(G.velocity[o - 1], G.momentum[o - 1] / G.mass[o - 1] + p.dt * G.accel[o - 1]);
  EXPECT_EQ(G.velocity[o], 0.0);  // the walls
  EXPECT_EQ(G.velocity[o + p.cells], 0.0);
  EXPECT_EQ(G.nodes(), p.cells + 3);
}

// Until t = 1 / (2 c) = 0.25 the particles next to the walls move inwards; after it their
// supports cross the walls.
TEST(Walls, GhostChangesAGimpRunWhoseSupportsCrossAWall) {
  RunParams p = quick_case();
  p.T = 1;
  const RunResult clip = run(p);
  p.walls = Walls::ghost;
  const RunResult ghost = run(p);
  ASSERT_TRUE(clip.stable && ghost.stable);
  EXPECT_NE(*clip.max_error, *ghost.max_error);
}

// ---------------------------------------------------------------------------------------------
// Update orders. One step from a state some steps into the run, checked against the stress update
// written out: F^{n+1} = F^n (1 + dt sum_i G_ip v_i) with the velocity the order prescribes.

struct Step {
  Particles before, after;
  Grid grid_after;
};

Step one_step(const RunParams& p) {
  Simulation sim = advanced(p, 20);
  Step s{sim.particles(), {}, {}};
  sim.advance_to(21 * p.dt);
  s.after = sim.particles();
  s.grid_after = sim.grid();
  return s;
}

// The stencil at the positions of `P` and the nodal velocity sum_p S_ip m_p v_p / m_i.
struct Mapped {
  Stencil<GimpBasis::width> S;
  Grid G;
};

Mapped map_velocity(const RunParams& p, const Particles& P) {
  const double h = 1.0 / p.cells;
  Mapped m{{}, Grid(p.cells, p.bc)};
  m.S.resize(static_cast<std::size_t>(P.size()));
  const Eigen::ArrayXd no_body = Eigen::ArrayXd::Zero(P.size());
  p2g(GimpBasis(h, h / (2.0 * p.ppc)), P, no_body.data(), m.S, m.G);
  grid_velocity(m.G);
  return m;
}

// max_p |F_after - F_before (1 + dt sum_i G_ip v_i)| / F_before with v from `velocity`.
double stress_update_mismatch(const RunParams& p, const Step& s, const Stencil<3>& S,
                              const Eigen::ArrayXd& velocity) {
  double worst = 0;
  for (Eigen::Index q = 0; q < s.before.size(); ++q) {
    double L = 0;
    for (int k = 0; k < 3; ++k)
      L += S.g[k][q] * velocity[S.base[q] + k];
    const double expected = s.before.F[q] * (1.0 + p.dt * L);
    worst = std::max(worst, std::abs(s.after.F[q] - expected) / s.before.F[q]);
  }
  return worst;
}

TEST(UpdateOrder, UslUpdatesTheStressWithTheNewGridVelocity) {
  const RunParams p = quick_case();
  const Step s = one_step(p);
  const Mapped start = map_velocity(p, s.before);
  EXPECT_LT(stress_update_mismatch(p, s, start.S, s.grid_after.velocity), 1e-15);
  EXPECT_GT(stress_update_mismatch(p, s, start.S, start.G.velocity), 1e-9);
}

TEST(UpdateOrder, UsfUpdatesTheStressWithTheVelocityOfTheStartOfTheStep) {
  RunParams p = quick_case();
  p.update = UpdateOrder::usf;
  const Step s = one_step(p);
  const Mapped start = map_velocity(p, s.before);  // v_i^n = q_i / m_i
  EXPECT_LT(stress_update_mismatch(p, s, start.S, start.G.velocity), 1e-15);
  EXPECT_GT(stress_update_mismatch(p, s, start.S, s.grid_after.velocity), 1e-9);
}

TEST(UpdateOrder, UsfComputesTheForcesFromTheUpdatedStress) {
  RunParams p = quick_case();
  p.update = UpdateOrder::usf;
  p.A = 0;  // no body force: f_i is the internal force alone
  Simulation sim(p);
  Particles& P = sim.particles();
  P.v = 0.02 * (2 * kPi * P.X).sin();  // stretches the bar in the first step
  const Particles before = P;
  sim.advance_to(p.dt);
  // The internal force of the stress after the update, over the stencil at x^n.
  const Mapped start = map_velocity(p, before);
  Particles updated = before;
  updated.F = P.F;
  updated.sigma = P.sigma;
  Grid expected(p.cells, p.bc);
  const Eigen::ArrayXd no_body = Eigen::ArrayXd::Zero(P.size());
  p2g_force(start.S, updated, no_body.data(), expected);
  const Grid& G = sim.grid();
  const double scale = expected.force.abs().maxCoeff();
  ASSERT_GT(scale, 0);
  EXPECT_LT((G.force - expected.force).abs().maxCoeff(), 1e-14 * scale);
  // The step started from sigma = 0: a force from the old stress would vanish.
  EXPECT_TRUE((before.sigma == 0.0).all());
}

TEST(UpdateOrder, MuslRemapsTheUpdatedParticleVelocitiesBeforeTheStressUpdate) {
  RunParams p = quick_case();
  p.update = UpdateOrder::musl;
  const Step s = one_step(p);
  Particles remapped = s.before;  // positions x^n (the stencil of the step), velocities v^{n+1}
  remapped.v = s.after.v;
  const Mapped end = map_velocity(p, remapped);
  const double scale = end.G.velocity.abs().maxCoeff();
  EXPECT_LT((s.grid_after.velocity - end.G.velocity).abs().maxCoeff(), 1e-14 * scale);
  EXPECT_LT(stress_update_mismatch(p, s, end.S, end.G.velocity), 1e-15);
}

TEST(UpdateOrder, UsfAndMuslChangeTheResultOfARun) {
  RunParams p = quick_case();
  const RunResult usl = run(p);
  for (UpdateOrder order : {UpdateOrder::usf, UpdateOrder::musl}) {
    p.update = order;
    const RunResult r = run(p);
    ASSERT_TRUE(r.stable) << to_string(order);
    EXPECT_NE(*r.max_error, *usl.max_error) << to_string(order);
    EXPECT_LT(*r.max_error_over_time, 0.1 * p.A) << to_string(order);
  }
}

TEST(UpdateOrder, PeriodicImagesAreFoldedOnceInEveryOrder) {
  // The bar's solution is periodic, so with periodic boundaries every order must give about
  // the Dirichlet run's error; an image slot folded twice would add its mass and momentum again.
  for (UpdateOrder order : {UpdateOrder::usl, UpdateOrder::usf, UpdateOrder::musl}) {
    RunParams p = quick_case();
    p.update = order;
    const RunResult dirichlet = run(p);
    p.bc = Boundary::periodic;
    const RunResult periodic = run(p);
    ASSERT_TRUE(periodic.stable) << to_string(order);
    EXPECT_NEAR(*periodic.max_error, *dirichlet.max_error, 0.1 * *dirichlet.max_error)
        << to_string(order);
  }
}

// ---------------------------------------------------------------------------------------------
// Body-force time

// At t = 0 the bar is at rest in stress (F = 1) and b(X, 0) = 0: with b at the start the first
// step leaves every particle velocity as it was; with b at the end it adds dt b(X_p, dt).
TEST(BodyForceTime, EndEvaluatesTheBodyForceAtTheNewTime) {
  RunParams p = quick_case();
  Simulation start(p);
  const Particles initial = start.particles();
  start.advance_to(p.dt);
  EXPECT_TRUE((start.particles().v == initial.v).all());

  p.body_force_time = BodyForceTime::end;
  Simulation end(p);
  end.advance_to(p.dt);
  const Particles& P = end.particles();
  const BarScene scene(p.E, p.A);
  // Interior particles (full support on free nodes): dv = dt sum_i S_ip b_i, close to dt b(X_p).
  for (Eigen::Index q = 4; q < P.size() - 4; ++q) {
    const double expected = p.dt * scene.body_force(P.X[q], p.dt);
    EXPECT_NEAR(P.v[q] - initial.v[q], expected, 0.1 * std::abs(expected) + 1e-12) << q;
  }
  const RunResult a = run(quick_case());
  const RunResult b = run(p);
  EXPECT_NE(*a.max_error, *b.max_error);
}

// ---------------------------------------------------------------------------------------------
// The half-step start

// The particles start with the exact velocity at -dt/2; on the neo-Hookean scene, which starts
// at rest with its largest acceleration, that removes the start's O(dt) error: at C = 0.4 the
// error over time falls to near the spatial error of a run at a far smaller step. Refused where
// the first dt is not known before the first step, and on scenes without the exact velocity.
TEST(VelocityStart, HalfStepStartsAtMinusHalfAStepAndRemovesTheStartsError) {
  RunParams p;
  p.method = Method::gimp;
  p.scene = SceneKind::steffen;
  p.E = 64;
  p.A = 2.5e-4;
  p.T = 0.3;
  p.stepping.policy = TimeStepPolicy::cfl;
  p.stepping.cfl_factor = 0.4;
  RunParams half = p;
  half.start = VelocityStart::half_step;
  const double dt = 0.4 / (100 * 8.0);  // C h / c
  const Simulation s(half);
  const Simulation exact(p);
  // At rest at t = 0 (v = 0 exactly); at -dt/2 the exact velocity is not zero.
  EXPECT_TRUE((exact.particles().v == 0).all());
  EXPECT_GT(s.particles().v.abs().maxCoeff(), 0);
  const double w = 8.0 * std::numbers::pi;  // c pi
  for (Eigen::Index q = 0; q < s.particles().size(); ++q)
    EXPECT_NEAR(
        s.particles().v[q],
        -p.A * std::sin(2 * std::numbers::pi * s.particles().X[q]) * w * std::sin(w * -dt / 2),
        1e-15);
  RunParams fine = p;
  fine.stepping.cfl_factor = 0.0125;
  const double e_exact = *run(p).max_error_over_time, e_half = *run(half).max_error_over_time;
  const double e_fine = *run(fine).max_error_over_time;
  EXPECT_LT(e_half, e_exact / 4) << e_half << " against " << e_exact;
  EXPECT_LT(e_half, e_fine) << "the start's error at C = 0.4 exceeds the small step's";
  RunParams adaptive = half;
  adaptive.stepping.policy = TimeStepPolicy::adaptive;
  EXPECT_FALSE(validate(adaptive).empty());
  RunParams vibration = half;
  vibration.scene = SceneKind::vibration;
  EXPECT_FALSE(validate(vibration).empty());
}

// ---------------------------------------------------------------------------------------------
// cpGIMP

// The bar's particles, uniformly stretched to F: the stencil p2g keeps for a particle in the
// middle of the bar widens with F, and the grid keeps all the mass. At F = 1 the masses are
// uGIMP's to rounding.
struct Stretched {
  Stencil<CpGimpBasis::width> S;
  Grid G;
  double particle_mass = 0;
};

Stretched stretched(const RunParams& p, double F) {
  const double h = 1.0 / p.cells;
  Particles P = BarScene(p.E, 0.0).initial_particles(p.cells, p.ppc);
  P.F.setConstant(F);
  Stretched s{{}, Grid(p.cells, p.bc, p.walls, CpGimpBasis::width), P.mass.sum()};
  s.S.resize(static_cast<std::size_t>(P.size()));
  const Eigen::ArrayXd no_body = Eigen::ArrayXd::Zero(P.size());
  p2g(CpGimpBasis(h, h / (2.0 * p.ppc)), P, no_body.data(), s.S, s.G);
  return s;
}

TEST(CpGimp, SupportsFollowTheDeformationGradient) {
  const RunParams p = quick_case();
  const std::size_t mid = 21;  // X = 10.75 h: support [X - F h / 4, X + F h / 4]
  const int expected_nodes[] = {2, 2, 3, 4};
  const double Fs[] = {0.5, 1.0, 2.0, 4.0};  // 4 = 2 m: lp = h, the widest admissible
  for (int j = 0; j < 4; ++j) {
    const Stretched s = stretched(p, Fs[j]);
    int touched = 0;
    double sum_w = 0, sum_g = 0;
    for (int k = 0; k < CpGimpBasis::width; ++k) {
      touched += s.S.w[k][mid] > 1e-12;
      sum_w += s.S.w[k][mid];
      sum_g += s.S.g[k][mid];
    }
    EXPECT_EQ(touched, expected_nodes[j]) << "F = " << Fs[j];
    EXPECT_NEAR(sum_w, 1.0, 1e-14) << "F = " << Fs[j];
    EXPECT_NEAR(sum_g / p.cells, 0.0, 1e-14) << "F = " << Fs[j];
    // Dirichlet, clip: the supports stay on the grid's slots, which hold all the mass.
    EXPECT_NEAR(s.G.mass.sum(), s.particle_mass, 1e-15) << "F = " << Fs[j];
  }
  // At F = 1, uGIMP's masses to rounding.
  const Stretched cp = stretched(p, 1.0);
  const double h = 1.0 / p.cells;
  const Particles P = BarScene(p.E, 0.0).initial_particles(p.cells, p.ppc);
  Grid gimp(p.cells, p.bc);
  Stencil<GimpBasis::width> S;
  S.resize(static_cast<std::size_t>(P.size()));
  const Eigen::ArrayXd no_body = Eigen::ArrayXd::Zero(P.size());
  p2g(GimpBasis(h, h / (2.0 * p.ppc)), P, no_body.data(), S, gimp);
  EXPECT_LT((cp.G.mass.head(gimp.slots()) - gimp.mass).abs().maxCoeff(), 1e-16);
  EXPECT_EQ(cp.G.mass[gimp.slots()], 0.0);
}

TEST(CpGimp, ChangesTheResultOnceTheBarDeforms) {
  RunParams p = quick_case();
  const RunResult gimp = run(p);
  p.method = Method::cpgimp;
  const RunResult cpgimp = run(p);
  ASSERT_TRUE(cpgimp.stable);
  EXPECT_NE(*cpgimp.max_error, *gimp.max_error);
  EXPECT_LT(*cpgimp.max_error_over_time, 0.1 * p.A);
}

TEST(CpGimp, GridHasOneMorePaddingSlotAndTheOthersKeepTheirs) {
  for (Boundary bc : {Boundary::dirichlet, Boundary::periodic}) {
    EXPECT_EQ(Grid(10, bc, Walls::clip, LinearBasis::width).slots(), 13);
    EXPECT_EQ(Grid(10, bc, Walls::clip, GimpBasis::width).slots(), 13);
    EXPECT_EQ(Grid(10, bc, Walls::clip, CpGimpBasis::width).slots(), 14);
  }
}

// One particle per cell (lp = F h / 2): a large steffen amplitude stretches the supports past
// 2 h before anything else goes wrong; the run stops with that reason.
TEST(CpGimp, ASupportWiderThanTwoCellsEndsTheRun) {
  RunParams p;
  p.method = Method::cpgimp;
  p.scene = SceneKind::steffen;
  p.ppc = 1;
  p.E = 64;
  p.A = 0.14;
  p.cells = 10;
  p.dt = 1e-4;
  p.T = 0.5;
  p.observe.final_state = true;
  const RunResult r = run(p);
  ASSERT_FALSE(r.stable);
  ASSERT_TRUE(r.failure);
  EXPECT_EQ(r.failure->reason, FailureReason::support_too_wide);
  EXPECT_GE(r.failure->step, 1);
  EXPECT_EQ(to_string(r.failure->reason), "support_too_wide");
  EXPECT_GT(r.final_state->F[r.failure->particle], 2.0);
  EXPECT_GT(r.final_state->F.minCoeff(), 0.0);
  // uGIMP has no such limit: the same case does not stop for that reason.
  p.method = Method::gimp;
  const RunResult gimp = run(p);
  EXPECT_TRUE(gimp.stable || gimp.failure->reason != FailureReason::support_too_wide);
}

TEST(Run, AnInadmissibleInitialStateFailsAtStepZero) {
  RunParams p = quick_case();
  p.scene = SceneKind::steffen;
  p.A = 0.2;  // F(X, 0) = 1 + 2 pi A cos(2 pi X) reaches 1 - 1.26 < 0
  const RunResult r = run(p);
  ASSERT_TRUE(r.failure);
  EXPECT_EQ(r.failure->reason, FailureReason::nonpositive_F);
  EXPECT_EQ(r.failure->step, 0);
  EXPECT_EQ(r.steps, 0);
  EXPECT_FALSE(r.dt_stable_min);
}

}  // namespace
}  // namespace mpmstab
