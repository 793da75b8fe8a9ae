// APIC: the affine part of p2g conserves momentum, an affine velocity field goes to the grid and
// back unchanged for every basis, and on the bar it removes PIC's dissipation.
#include <gtest/gtest.h>

#include <random>

#include "run/run.hpp"
#include "scenes/validate.hpp"
#include "step/phases.hpp"
#include "step/shape.hpp"
#include "step/simulation.hpp"

namespace mpmstab {
namespace {

constexpr double kA = 0.3, kB = -1.7;  // v(x) = a + b x

Particles affine_particles(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(0.3, 0.7), val(0.5, 1.5);
  Particles P;
  P.resize(n);
  P.C.resize(n);
  for (int p = 0; p < n; ++p) {
    P.x[p] = P.X[p] = pos(rng);
    P.v[p] = kA + kB * P.x[p];
    P.C[p] = kB;
    P.F[p] = 1.0;
    P.sigma[p] = 0.0;
    P.mass[p] = val(rng) * 1e-3;
    P.volume0[p] = val(rng) * 1e-3;
  }
  return P;
}

template <class Basis>
void check_affine_round_trip(const Basis& basis) {
  const int cells = 20;
  Grid G(cells, Boundary::dirichlet, Walls::clip, Basis::width);
  Particles P = affine_particles(400, 11);
  const Eigen::ArrayXd body = Eigen::ArrayXd::Zero(P.size());
  Stencil<Basis::width> S;
  S.resize(P.size());
  p2g(basis, P, body.data(), S, G);
  const double momentum = G.momentum.sum();
  p2g_affine(S, P.x.data(), P, G);
  // The affine part adds no momentum: sum_i S_ip (X_i - x_p) = 0 for every particle.
  EXPECT_NEAR(G.momentum.sum(), momentum, 1e-15 * P.size());
  // The nodes hold the field: q_i / m_i = a + b X_i wherever there is mass.
  int nodes = 0;
  for (Eigen::Index s = 0; s < G.velocity.size(); ++s) {
    G.velocity[s] = G.mass[s] > 0 ? G.momentum[s] / G.mass[s] : 0.0;
    G.accel[s] = 0.0;
    if (G.mass[s] > 1e-12) {
      const double X = (s - Grid::kOffset) * G.h;
      EXPECT_NEAR(G.velocity[s], kA + kB * X, 1e-12) << "slot " << s;
      ++nodes;
    }
  }
  EXPECT_GT(nodes, 5);
  // And g2p gives it back: v_p = a + b x_p, C_p = b.
  const Particles before = P;
  g2p(S, G, 0.0, ParticleUpdate{Transfer::apic, 1.0, PositionUpdate::grid}, P);
  for (Eigen::Index p = 0; p < P.size(); ++p) {
    EXPECT_NEAR(P.v[p], kA + kB * before.x[p], 1e-12) << p;
    EXPECT_NEAR(P.C[p], kB, 1e-10) << p;
  }
}

TEST(Apic, PreservesAffineVelocityFieldsExactlyForEveryBasis) {
  check_affine_round_trip(LinearBasis(1.0 / 20));
  check_affine_round_trip(GimpBasis(1.0 / 20, 1.0 / 80));
  check_affine_round_trip(CpGimpBasis(1.0 / 20, 1.0 / 80));
  check_affine_round_trip(CpdiBasis(1.0 / 20, 1.0 / 80));
  check_affine_round_trip(BSpline2Basis(1.0 / 20, 20, true));
  check_affine_round_trip(BSpline3Basis(1.0 / 20, 20, true));
}

// A whole step's transfers keep an affine velocity field, dt > 0, under every update order and
// every basis: the block at rest in stress (sigma = 0, F = 1, no load) with v_p = a + b x_p and
// C_p = b, advanced one step. Its force is zero until the stress is updated, so
//  - USL and MUSL: the grid velocity is a + b X_i; g2p gives v_p = a + b x_p^n and C_p = b; the
//    stress update reads L_p = b (MUSL from its re-mapped velocity: the re-map's affine term must
//    be taken about x_p^n, where its S_ip were evaluated, not about the moved x_p^{n+1});
//  - USF: the stress update reads L_p = b from v^n, before its force moves the field.
// F_p = 1 + dt b then holds to round-off. Taken about x_p^{n+1}, MUSL's re-map is off by
// -b dt v_p and F_p by about dt^2 b^2 (here 3e-6, against round-off 1e-15).
void check_affine_step(Method m, Boundary bc, UpdateOrder update) {
  RunParams p;
  p.scene = SceneKind::block;
  p.method = m;
  p.bc = bc;
  p.E = 100;
  p.cells = 32;
  p.A = 1.0 / 64;
  p.dt = 1e-3;  // c dt / h = 0.32
  p.T = 1;
  p.transfer = Transfer::apic;
  p.update = update;
  const std::string what = std::string(to_string(m)) + ", " + std::string(to_string(bc)) + ", " +
                           std::string(to_string(update));
  ASSERT_TRUE(validate(p).empty()) << what;
  Simulation sim(p);
  Particles& P = sim.particles();
  for (Eigen::Index q = 0; q < P.size(); ++q) {
    P.v[q] = kA + kB * P.x[q];
    P.C[q] = kB;
  }
  const Eigen::ArrayXd x0 = P.x;
  sim.advance_to(p.dt);
  const Particles& after = sim.particles();
  for (Eigen::Index q = 0; q < after.size(); ++q) {
    EXPECT_NEAR(after.F[q], 1.0 + p.dt * kB, 1e-14) << what << ", particle " << q;
    if (update == UpdateOrder::usf) continue;  // its force, from the new stress, moves the field
    EXPECT_NEAR(after.v[q], kA + kB * x0[q], 1e-13) << what << ", particle " << q;
    EXPECT_NEAR(after.C[q], kB, 1e-11) << what << ", particle " << q;
  }
}

TEST(Apic, AWholeStepKeepsAnAffineFieldUnderEveryUpdateOrderAndBasis) {
  for (const Method m : {Method::mpm, Method::gimp, Method::cpgimp, Method::cpdi, Method::bspline2,
                         Method::bspline3})
    for (const Boundary bc : {Boundary::dirichlet, Boundary::periodic})
      for (const UpdateOrder u : {UpdateOrder::usl, UpdateOrder::usf, UpdateOrder::musl})
        check_affine_step(m, bc, u);
}

// PIC damps the bar's wave; APIC keeps what PIC loses (measured at E = 64, A = 0.015,
// dt = 1e-4, 100 cells, T = 1: GIMP 1.5e-3 with PIC, 1.2e-5 with APIC, 2.2e-5 with FLIP).
// It runs with each update order.
TEST(Apic, RemovesPicsDissipationOnTheBarWithEveryUpdateOrder) {
  RunParams p;
  p.method = Method::gimp;
  p.E = 64;
  p.A = 0.015;
  p.dt = 1e-4;
  p.T = 1;
  p.transfer = Transfer::pic;
  const RunResult pic = run(p);
  p.transfer = Transfer::apic;
  for (const auto update : {UpdateOrder::usl, UpdateOrder::usf, UpdateOrder::musl}) {
    p.update = update;
    ASSERT_TRUE(validate(p).empty());
    const RunResult apic = run(p);
    ASSERT_EQ(apic.outcome, Outcome::stable) << to_string(update);
    EXPECT_LT(*apic.max_error, 0.05 * *pic.max_error) << to_string(update);
  }
}

}  // namespace
}  // namespace mpmstab
