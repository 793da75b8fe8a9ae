// XPIC(m) and FMPM(k) (xpic.hpp): order 1 is PIC to the bit; the series equals its dense-matrix
// form; XPIC's particle update is S a dt + (I - (I - P)^m) V^n with P = S S^+ (checked against
// dense matrices); the series conserves momentum; every basis runs with every update order.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "run/run.hpp"
#include "scenes/validate.hpp"
#include "step/phases.hpp"
#include "step/shape.hpp"
#include "step/simulation.hpp"
#include "step/xpic.hpp"

namespace mpmstab {
namespace {

RunParams bar(Method m, Transfer t, int order, UpdateOrder u, Boundary bc = Boundary::dirichlet) {
  RunParams p;
  p.method = m;
  p.E = 64;
  p.A = 0.01;
  p.dt = 2e-4;
  p.T = 0.2;
  p.cells = 20;
  p.bc = bc;
  p.transfer = t;
  p.xpic_order = order;
  p.fmpm_order = order;
  p.update = u;
  return p;
}

// Order 1 adds exactly zero: the final state equals PIC's bit for bit.
TEST(Xpic, OrderOneIsPicToTheBit) {
  for (const Method m : {Method::mpm, Method::gimp, Method::bspline2, Method::bspline3}) {
    for (const UpdateOrder u : {UpdateOrder::usl, UpdateOrder::usf, UpdateOrder::musl}) {
      for (const Boundary bc : {Boundary::dirichlet, Boundary::periodic}) {
        RunParams pic = bar(m, Transfer::pic, 1, u, bc);
        if (bc == Boundary::periodic) pic.scene = SceneKind::bar;
        Simulation a(pic);
        Simulation x(bar(m, Transfer::xpic, 1, u, bc));
        Simulation f(bar(m, Transfer::fmpm, 1, u, bc));
        for (int n = 1; n <= 50; ++n) {
          a.advance_to(n * 2e-4);
          x.advance_to(n * 2e-4);
          f.advance_to(n * 2e-4);
        }
        for (Eigen::Index p = 0; p < a.particles().size(); ++p) {
          ASSERT_EQ(a.particles().x[p], x.particles().x[p]) << to_string(m) << " " << to_string(u);
          ASSERT_EQ(a.particles().v[p], x.particles().v[p]);
          ASSERT_EQ(a.particles().x[p], f.particles().x[p]);
          ASSERT_EQ(a.particles().v[p], f.particles().v[p]);
          ASSERT_EQ(a.particles().F[p], f.particles().F[p]);
        }
      }
    }
  }
}

// A small state as dense matrices: S (particles x slots) and the particle masses W.
struct Dense {
  Eigen::MatrixXd S;
  Eigen::VectorXd mp;
};

template <int W>
Dense dense_of(const Particles& P, const Stencil<W>& St, int slots) {
  Dense d;
  d.S = Eigen::MatrixXd::Zero(P.size(), slots);
  for (Eigen::Index p = 0; p < P.size(); ++p)
    for (int k = 0; k < W; ++k)
      d.S(p, St.base[p] + k) += St.w[k][p];
  d.mp = P.mass.matrix();
  return d;
}

Particles scattered(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(0.0, 1.0), val(0.5, 1.5), vel(-1.0, 1.0);
  Particles P;
  P.resize(n);
  for (int p = 0; p < n; ++p) {
    P.x[p] = P.X[p] = pos(rng);
    P.v[p] = vel(rng);
    P.F[p] = 1.0;
    P.sigma[p] = vel(rng);
    P.mass[p] = val(rng) * 1e-2;
    P.volume0[p] = val(rng) * 1e-2;
  }
  return P;
}

// `n` scattered particles mapped to the grid and the grid updated: the state g2p starts from.
template <class Basis>
struct Mapped {
  Grid G;
  Particles P;
  Stencil<Basis::width> S;
};

template <class Basis>
Mapped<Basis> mapped(const Basis& basis, Boundary bc, int cells, int n, unsigned seed, double dt) {
  Mapped<Basis> s{Grid(cells, bc, Walls::clip, Basis::width), scattered(n, seed), {}};
  const Eigen::ArrayXd body = Eigen::ArrayXd::Zero(s.P.size());
  s.S.resize(s.P.size());
  p2g(basis, s.P, body.data(), s.S, s.G);
  grid_update(s.G, dt);
  return s;
}

// Periodic grid (no fixed node): the series and XPIC's particle update against dense matrices.
template <class Basis>
void check_against_dense(const Basis& basis, int m) {
  const int cells = 8;
  const double dt = 1e-3;
  auto [G, P, S] = mapped(basis, Boundary::periodic, cells, 40, 5, dt);
  // Fold the dense S onto the N distinct nodes (slot o + wrap(i)).
  const Dense d = dense_of(P, S, G.slots());
  Eigen::MatrixXd Sn = Eigen::MatrixXd::Zero(P.size(), cells);
  for (int s = 0; s < G.slots(); ++s)
    Sn.col(((s - Grid::kOffset) % cells + cells) % cells) += d.S.col(s);
  const Eigen::VectorXd mi = Sn.transpose() * d.mp;
  // Q = M_L^{-1} S^T W S;  P = S M_L^{-1} S^T W.
  const Eigen::MatrixXd Q =
      mi.cwiseInverse().asDiagonal() * Sn.transpose() * d.mp.asDiagonal() * Sn;
  const Eigen::MatrixXd Pp =
      Sn * mi.cwiseInverse().asDiagonal() * Sn.transpose() * d.mp.asDiagonal();
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(cells, cells);
  // The series of v^n.
  const Eigen::VectorXd Vn = P.v.matrix();
  const Eigen::VectorXd vn =
      mi.cwiseInverse().asDiagonal() * Sn.transpose() * d.mp.asDiagonal() * Vn;
  Eigen::VectorXd expected_w = Eigen::VectorXd::Zero(cells);
  Eigen::MatrixXd power = I;
  for (int r = 1; r < m; ++r) {
    power = power * (I - Q);
    expected_w += power * vn;
  }
  SeriesWork work;
  G.correction.setZero(G.slots());
  xpic_correction(S, P, m, G, work);
  for (int i = 0; i < cells; ++i)
    EXPECT_NEAR(G.correction[Grid::kOffset + i], expected_w[i], 1e-12) << "node " << i;
  // Momentum: sum_i m_i w_i = 0.
  double mw = 0.0;
  for (int i = 0; i < cells; ++i)
    mw += mi[i] * G.correction[Grid::kOffset + i];
  EXPECT_NEAR(mw, 0.0, 1e-15);
  // The particle update: V^{n+1} = S a dt + (I - (I - P)^m) V^n.
  Eigen::VectorXd a(cells);
  for (int i = 0; i < cells; ++i)
    a[i] = G.accel[Grid::kOffset + i];
  Eigen::MatrixXd Ppow = Eigen::MatrixXd::Identity(P.size(), P.size());
  for (int r = 0; r < m; ++r)
    Ppow = Ppow * (Eigen::MatrixXd::Identity(P.size(), P.size()) - Pp);
  const Eigen::VectorXd expected_V =
      Sn * a * dt + (Eigen::MatrixXd::Identity(P.size(), P.size()) - Ppow) * Vn;
  ParticleUpdate rule;
  rule.transfer = Transfer::xpic;
  g2p(S, G, dt, rule, P);
  for (Eigen::Index p = 0; p < P.size(); ++p)
    EXPECT_NEAR(P.v[p], expected_V[p], 1e-12) << "particle " << p << ", m = " << m;
}

TEST(Xpic, SeriesAndParticleUpdateEqualTheirDenseMatrixForms) {
  for (const int m : {1, 2, 3, 6}) {
    check_against_dense(LinearBasis(1.0 / 8), m);
    check_against_dense(GimpBasis(1.0 / 8, 1.0 / 32), m);
    check_against_dense(BSpline2Basis(1.0 / 8, 8, false), m);
    check_against_dense(BSpline3Basis(1.0 / 8, 8, false), m);
  }
}

// Dirichlet walls: every term of the series is zero on the walls, so FMPM's velocity keeps
// v = 0 there, and the series equals its dense form with the walls' rows removed.
TEST(Xpic, SeriesKeepsTheWallsFixed) {
  const int cells = 10;
  const GimpBasis basis(1.0 / cells, 1.0 / (4 * cells));
  auto [G, P, S] = mapped(basis, Boundary::dirichlet, cells, 60, 9, 1e-3);
  const Eigen::ArrayXd v = G.velocity;
  SeriesWork work;
  fmpm_velocity(S, P, 4, G, work);
  const int o = Grid::kOffset;
  EXPECT_EQ(G.velocity[o], 0.0);
  EXPECT_EQ(G.velocity[o + cells], 0.0);
  // Dense form on the free nodes 1..N-1: Q restricted, fixed rows zero.
  const Dense d = dense_of(P, S, G.slots());
  const int n = G.slots();
  Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(n, n);
  for (int s = o + 1; s < o + cells; ++s)
    if (G.mass[s] > 0) Q.row(s) = (d.S.col(s).cwiseProduct(d.mp)).transpose() * d.S / G.mass[s];
  Eigen::VectorXd term = v.matrix(), sum = v.matrix();
  for (int r = 1; r < 4; ++r) {
    term = term - Q * term;
    for (int s = 0; s < n; ++s)
      if (s <= o || s >= o + cells) term[s] = 0.0;
    sum += term;
  }
  for (int s = 0; s < n; ++s)
    EXPECT_NEAR(G.velocity[s], sum[s], 1e-12) << "slot " << s;
}

// Every basis with XPIC(3) and FMPM(3) and every update order: a stable run on the bar at
// E = 64, A = 0.01, and the error of XPIC(2) and FMPM(2) well below PIC's (PIC's dissipation).
TEST(Xpic, EveryBasisAndUpdateOrderRunsAndBeatsPic) {
  for (const Method m : {Method::mpm, Method::gimp, Method::cpgimp, Method::bspline2,
                         Method::bspline3, Method::cpdi}) {
    for (const UpdateOrder u : {UpdateOrder::usl, UpdateOrder::usf, UpdateOrder::musl}) {
      for (const Transfer t : {Transfer::xpic, Transfer::fmpm}) {
        RunParams p = bar(m, t, 3, u);
        p.T = 0.1;
        ASSERT_TRUE(validate(p).empty());
        const RunResult r = run(p);
        EXPECT_EQ(r.outcome, Outcome::stable)
            << to_string(m) << " " << to_string(u) << " " << to_string(t);
      }
    }
  }
  for (const Method m : {Method::gimp, Method::bspline2}) {
    RunParams p = bar(m, Transfer::pic, 1, UpdateOrder::usl);
    p.E = 64;
    p.A = 0.015;
    p.dt = 1e-4;
    p.T = 1.0;
    p.cells = 100;
    const double pic = *run(p).max_error;
    for (const Transfer t : {Transfer::xpic, Transfer::fmpm}) {
      p.transfer = t;
      p.xpic_order = p.fmpm_order = 2;
      const double e = *run(p).max_error;
      EXPECT_LT(e, pic / 20.0) << to_string(m) << " " << to_string(t) << ": " << e << " vs PIC "
                               << pic;
    }
  }
}

TEST(Xpic, OrderIsCheckedAndOnlyGivenWithItsTransfer) {
  RunParams p;
  p.transfer = Transfer::xpic;
  p.xpic_order = 0;
  ASSERT_EQ(validate(p).size(), 1u);
  EXPECT_EQ(validate(p)[0].key, "xpic_order");
  p.xpic_order = kMaxTransferOrder + 1;
  EXPECT_EQ(validate(p)[0].key, "xpic_order");
  p.xpic_order = 2;
  EXPECT_TRUE(validate(p).empty());
  EXPECT_FALSE(check_given(p, "xpic_order"));
  ASSERT_TRUE(check_given(p, "fmpm_order"));
  EXPECT_EQ(check_given(p, "fmpm_order")->key, "fmpm_order");
  p.transfer = Transfer::fmpm;
  p.fmpm_order = -3;
  EXPECT_EQ(validate(p)[0].key, "fmpm_order");
  p.transfer = Transfer::flip;
  EXPECT_TRUE(check_given(p, "xpic_order"));
}

}  // namespace
}  // namespace mpmstab
