// Transfers: p2g conserves mass and momentum, g2p and the velocity gradient reproduce linear
// nodal fields, for every basis and transfer; the partial phases of USF and MUSL; the grid update
// with ghost nodes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "step/phases.hpp"
#include "step/shape.hpp"

namespace mpmstab {
namespace {

// F_p is drawn from [0.5, F_hi): with cpGIMP (lp0 = h / 4 below) the supports reach 2 h.
Particles random_particles(int n, double lo, double hi, unsigned seed, double F_hi = 1.5) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(lo, hi), val(-1.0, 1.0), pos_val(0.5, 1.5),
      stretch(0.5, F_hi);
  Particles P;
  P.resize(n);
  for (int p = 0; p < n; ++p) {
    P.x[p] = P.X[p] = pos(rng);
    P.v[p] = val(rng);
    P.F[p] = stretch(rng);
    P.sigma[p] = val(rng);
    P.mass[p] = pos_val(rng) * 1e-3;
    P.volume0[p] = pos_val(rng) * 1e-3;
  }
  return P;
}

template <class Basis>
void check_conservation(const Basis& basis, Boundary bc, double lo, double hi) {
  const int cells = 20;
  Grid G(cells, bc, Walls::clip, Basis::width);
  Particles P = random_particles(300, lo, hi, 42, 3.99);
  Eigen::ArrayXd body = Eigen::ArrayXd::Random(P.size());
  Stencil<Basis::width> S;
  S.resize(P.size());
  p2g(basis, P, body.data(), S, G);
  const double mass = P.mass.sum();
  const double momentum = (P.mass * P.v).sum();
  const double body_force = (P.mass * body).sum();
  // Every slot (real nodes and padding) together holds exactly what the particles carried.
  EXPECT_NEAR(G.mass.sum(), mass, 1e-15 * P.size());
  EXPECT_NEAR(G.momentum.sum(), momentum, 1e-15 * P.size());
  // Internal forces cancel (sum_i G_ip = 0); only the body force remains.
  EXPECT_NEAR(G.force.sum(), body_force, 1e-12);

  if (bc == Boundary::periodic) {
    // After folding the images into the real nodes, the real nodes hold everything.
    grid_update(G, 1e-3);
    const auto real = [&](const Eigen::ArrayXd& a) {
      return a.segment(Grid::kOffset, G.nodes()).sum();
    };
    EXPECT_NEAR(real(G.mass), mass, 1e-15 * P.size());
    EXPECT_NEAR(real(G.momentum), momentum, 1e-15 * P.size());
    EXPECT_NEAR(real(G.force), body_force, 1e-12);
  }
}

TEST(P2G, ConservesMassMomentumAndForceLinear) {
  check_conservation(LinearBasis(1.0 / 20), Boundary::dirichlet, 0.0, 1.0);
}

TEST(P2G, ConservesMassMomentumAndForceGimp) {
  check_conservation(GimpBasis(1.0 / 20, 1.0 / 80), Boundary::dirichlet, 0.0, 1.0);
}

TEST(P2G, ConservesAcrossPeriodicWrapLinear) {
  // Unwrapped positions on both sides of [0, 1]: the stencil uses their images.
  check_conservation(LinearBasis(1.0 / 20), Boundary::periodic, -0.7, 1.7);
}

TEST(P2G, ConservesAcrossPeriodicWrapGimp) {
  check_conservation(GimpBasis(1.0 / 20, 1.0 / 80), Boundary::periodic, -0.7, 1.7);
}

TEST(P2G, ConservesMassMomentumAndForceCpGimp) {
  check_conservation(CpGimpBasis(1.0 / 20, 1.0 / 80), Boundary::dirichlet, 0.0, 1.0);
}

// Supports up to 2 h wide reach the image slots N + 2 and -1: the folding covers every slot.
TEST(P2G, ConservesAcrossPeriodicWrapCpGimp) {
  check_conservation(CpGimpBasis(1.0 / 20, 1.0 / 80), Boundary::periodic, -0.7, 1.7);
}

// B-splines: with the ghost nodes eliminated at Dirichlet walls (their weight moved onto the two
// first nodes inside) and across the periodic wrap.
TEST(P2G, ConservesMassMomentumAndForceBSplines) {
  check_conservation(BSpline2Basis(1.0 / 20, 20, true), Boundary::dirichlet, 0.0, 1.0);
  check_conservation(BSpline3Basis(1.0 / 20, 20, true), Boundary::dirichlet, 0.0, 1.0);
  check_conservation(BSpline2Basis(1.0 / 20, 20, false), Boundary::periodic, -0.7, 1.7);
  check_conservation(BSpline3Basis(1.0 / 20, 20, false), Boundary::periodic, -0.7, 1.7);
}

// The partial sums of USF and MUSL give p2g's sums bit for bit (same terms, same order).
TEST(P2G, ForceAndMomentumSumsAloneAreP2gsSums) {
  const int cells = 20;
  const GimpBasis basis(1.0 / cells, 1.0 / 80);
  for (Boundary bc : {Boundary::dirichlet, Boundary::periodic}) {
    Particles P = random_particles(300, bc == Boundary::periodic ? -0.7 : 0.0,
                                   bc == Boundary::periodic ? 1.7 : 1.0, 5);
    const Eigen::ArrayXd body = Eigen::ArrayXd::Random(P.size());
    Stencil<GimpBasis::width> S;
    S.resize(P.size());
    Grid G(cells, bc);
    p2g(basis, P, body.data(), S, G);
    Grid alone(cells, bc);
    alone.force.setConstant(7.0);  // cleared by the partial sums
    alone.momentum.setConstant(7.0);
    p2g_force(S, P, body.data(), alone);
    p2g_momentum(S, P, alone);
    EXPECT_TRUE((alone.force == G.force).all());
    EXPECT_TRUE((alone.momentum == G.momentum).all());
  }
}

// p2g's sums are those of the plain scatter, bit for bit: a cleared grid, then for each particle
// in order and each node of its stencil m_i += S_ip m_p, q_i += S_ip (m_p v_p),
// f_i += G_ip (-sigma_p F_p V_p^0) + S_ip (m_p b_p). The grid starts full of NaN (p2g clears
// it), and the particles come sorted, reversed, shuffled and in runs with jumps both ways, on a
// grid with cells no particle reaches at either end.
template <class Basis>
void check_plain_scatter(const Basis& basis, Boundary bc) {
  constexpr int W = Basis::width;
  const int cells = 40;
  const bool periodic = bc == Boundary::periodic;
  Particles sorted = random_particles(257, periodic ? -0.3 : 0.2, periodic ? 1.3 : 0.8, 11);
  std::vector<int> order(std::size_t(sorted.size()));
  for (std::size_t i = 0; i < order.size(); ++i)
    order[i] = int(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return sorted.x[a] < sorted.x[b]; });
  std::mt19937 rng(3);
  for (int arrangement = 0; arrangement < 4; ++arrangement) {
    std::vector<int> o = order;
    if (arrangement == 1) std::reverse(o.begin(), o.end());
    if (arrangement == 2) std::shuffle(o.begin(), o.end(), rng);
    if (arrangement == 3)  // sorted runs of 40 particles, the runs in shuffled order
      for (std::size_t r = 0; r + 80 <= o.size(); r += 80)
        std::rotate(o.begin() + long(r), o.begin() + long(r + 40), o.begin() + long(r + 80));
    Particles P;
    P.resize(sorted.size());
    for (std::size_t i = 0; i < o.size(); ++i) {
      const int q = o[i];
      P.x[long(i)] = sorted.x[q];
      P.v[long(i)] = sorted.v[q];
      P.F[long(i)] = sorted.F[q];
      P.sigma[long(i)] = sorted.sigma[q];
      P.mass[long(i)] = sorted.mass[q];
      P.volume0[long(i)] = sorted.volume0[q];
    }
    const Eigen::ArrayXd body = Eigen::ArrayXd::Random(P.size());
    Grid G(cells, bc, Walls::clip, W);
    for (Eigen::ArrayXd* a : {&G.mass, &G.momentum, &G.force})
      a->setConstant(std::numeric_limits<double>::quiet_NaN());
    Stencil<W> S;
    S.resize(std::size_t(P.size()));
    p2g(basis, P, body.data(), S, G);
    Eigen::ArrayXd m = Eigen::ArrayXd::Zero(G.mass.size()), q = m, f = m;
    for (Eigen::Index p = 0; p < P.size(); ++p) {
      const double mom = P.mass[p] * P.v[p];
      const double stress_volume = -P.sigma[p] * P.F[p] * P.volume0[p];
      const double b = P.mass[p] * body[p];
      for (int k = 0; k < W; ++k) {
        const int s = S.base[std::size_t(p)] + k;
        const double w = S.w[k][std::size_t(p)], g = S.g[k][std::size_t(p)];
        m[s] += w * P.mass[p];
        q[s] += w * mom;
        f[s] += g * stress_volume + w * b;
      }
    }
    const auto same_bits = [](const Eigen::ArrayXd& a, const Eigen::ArrayXd& e) {
      return a.size() == e.size() &&
             std::memcmp(a.data(), e.data(), sizeof(double) * std::size_t(a.size())) == 0;
    };
    EXPECT_TRUE(same_bits(G.mass, m)) << "arrangement " << arrangement;
    EXPECT_TRUE(same_bits(G.momentum, q)) << "arrangement " << arrangement;
    EXPECT_TRUE(same_bits(G.force, f)) << "arrangement " << arrangement;
  }
}

TEST(P2G, SumsAreThePlainScatterBitForBitInAnyParticleOrder) {
  const double h = 1.0 / 40;
  for (Boundary bc : {Boundary::dirichlet, Boundary::periodic}) {
    check_plain_scatter(LinearBasis(h), bc);
    check_plain_scatter(GimpBasis(h, h / 4), bc);
    check_plain_scatter(CpGimpBasis(h, h / 4), bc);
    check_plain_scatter(BSpline2Basis(h, 40, bc == Boundary::dirichlet), bc);
    check_plain_scatter(BSpline3Basis(h, 40, bc == Boundary::dirichlet), bc);
  }
}

// USF's p2g (no body force given) sums m_i and q_i alone, bit for bit those of the full p2g, and
// leaves f_i as it was (its p2g_force comes after the stress update).
TEST(P2G, WithoutABodyForceSumsMassAndMomentumAlone) {
  const int cells = 20;
  const GimpBasis basis(1.0 / cells, 1.0 / 80);
  for (Boundary bc : {Boundary::dirichlet, Boundary::periodic}) {
    const Particles P = random_particles(300, bc == Boundary::periodic ? -0.7 : 0.0,
                                         bc == Boundary::periodic ? 1.7 : 1.0, 9);
    const Eigen::ArrayXd body = Eigen::ArrayXd::Random(P.size());
    Stencil<GimpBasis::width> S, S_alone;
    S.resize(std::size_t(P.size()));
    S_alone.resize(std::size_t(P.size()));
    Grid G(cells, bc), alone(cells, bc);
    p2g(basis, P, body.data(), S, G);
    alone.force.setConstant(7.0);
    p2g(basis, P, nullptr, S_alone, alone);
    EXPECT_TRUE((alone.mass == G.mass).all());
    EXPECT_TRUE((alone.momentum == G.momentum).all());
    EXPECT_TRUE((alone.force == 7.0).all());
    EXPECT_EQ(S_alone.base, S.base);
    for (int k = 0; k < GimpBasis::width; ++k) {
      EXPECT_EQ(S_alone.w[k], S.w[k]);
      EXPECT_EQ(S_alone.g[k], S.g[k]);
    }
  }
}

TEST(P2G, MassOfTheBarIsOneOnTheNodes) {
  // rho0 = 1 on [0, 1]: the interior nodes of a uniform particle layout carry mass h each.
  const int cells = 10, ppc = 2;
  Particles P;
  P.resize(cells * ppc);
  for (int p = 0; p < cells * ppc; ++p) {
    P.x[p] = P.X[p] = (p + 0.5) / (cells * ppc);
    P.v[p] = 0;
    P.F[p] = 1;
    P.sigma[p] = 0;
    P.mass[p] = 1.0 / (cells * ppc);
    P.volume0[p] = 1.0 / (cells * ppc);
  }
  Eigen::ArrayXd body = Eigen::ArrayXd::Zero(P.size());
  for (int method = 0; method < 2; ++method) {
    Grid G(cells, Boundary::dirichlet);
    if (method == 0) {
      Stencil<2> S;
      S.resize(P.size());
      p2g(LinearBasis(0.1), P, body.data(), S, G);
    } else {
      Stencil<3> S;
      S.resize(P.size());
      p2g(GimpBasis(0.1, 0.025), P, body.data(), S, G);
    }
    for (int i = 1; i < cells; ++i)
      EXPECT_NEAR(G.mass[Grid::kOffset + i], 0.1, 1e-15) << i;
    EXPECT_NEAR(G.mass[Grid::kOffset + 0], 0.05, 1e-15);
  }
}

// Set every slot of the grid to linear fields v(X) = a + b X, acc(X) = c + d X, then g2p and
// the stress update must see exactly those fields at each particle.
template <class Basis>
void check_linear_reproduction(const Basis& basis, const ParticleUpdate& rule) {
  const int cells = 16;
  Grid G(cells, Boundary::dirichlet, Walls::clip, Basis::width);
  const double a = 0.3, b = -1.7, c = 2.0, d = 0.9;
  for (Eigen::Index s = 0; s < G.velocity.size(); ++s) {
    const double X = (s - Grid::kOffset) * G.h;
    G.velocity[s] = a + b * X;
    G.accel[s] = c + d * X;
  }
  Particles P = random_particles(200, 0.0, 1.0, 7);
  const Particles before = P;
  Eigen::ArrayXd body = Eigen::ArrayXd::Zero(P.size());
  Stencil<Basis::width> S;
  S.resize(P.size());
  Grid scratch(cells, Boundary::dirichlet, Walls::clip, Basis::width);
  p2g(basis, P, body.data(), S, scratch);  // fills the stencil at x^n

  const double dt = 1e-2, E = 5.0;
  g2p(S, G, dt, rule, P);
  stress_update(S, G, dt, MaterialLaw{Material::linear, E}, P);
  const double alpha = rule.flip_fraction;
  for (Eigen::Index p = 0; p < P.size(); ++p) {
    const double x0 = before.x[p];
    const double v_flip = before.v[p] + dt * (c + d * x0);
    const double v_pic = a + b * x0;
    const double v_new = rule.transfer == Transfer::flip  ? v_flip
                         : rule.transfer == Transfer::pic ? v_pic
                                                          : alpha * v_flip + (1 - alpha) * v_pic;
    EXPECT_NEAR(P.v[p], v_new, 1e-14) << p;
    const double moved = rule.position == PositionUpdate::grid ? dt * v_pic : dt * v_new;
    EXPECT_NEAR(P.x[p], x0 + moved, 1e-14) << p;
    // L_p = dv/dx = b exactly.
    EXPECT_NEAR(P.F[p], before.F[p] * (1 + dt * b), 1e-13) << p;
    EXPECT_NEAR(P.sigma[p], E * (P.F[p] - 1), 1e-13) << p;
  }
}

constexpr ParticleUpdate kFlip{Transfer::flip, 1.0, PositionUpdate::grid};

TEST(G2P, ReproducesLinearFieldsLinear) {
  check_linear_reproduction(LinearBasis(1.0 / 16), kFlip);
}
TEST(G2P, ReproducesLinearFieldsGimp) {
  check_linear_reproduction(GimpBasis(1.0 / 16, 1.0 / 64), kFlip);
}
TEST(G2P, ReproducesLinearFieldsCpGimp) {
  check_linear_reproduction(CpGimpBasis(1.0 / 16, 1.0 / 64), kFlip);
}
TEST(P2G, ConservesMassMomentumAndForceCpdi) {
  check_conservation(CpdiBasis(1.0 / 20, 1.0 / 80), Boundary::dirichlet, 0.0, 1.0);
  check_conservation(CpdiBasis(1.0 / 20, 1.0 / 80), Boundary::periodic, -0.7, 1.7);
}
TEST(G2P, ReproducesLinearFieldsCpdi) {
  check_linear_reproduction(CpdiBasis(1.0 / 16, 1.0 / 64), kFlip);
}
TEST(G2P, ReproducesLinearFieldsBSplines) {
  check_linear_reproduction(BSpline2Basis(1.0 / 16, 16, true), kFlip);
  check_linear_reproduction(BSpline3Basis(1.0 / 16, 16, true), kFlip);
}
TEST(G2P, ParticleVelocityPositionUpdateUsesTheNewParticleVelocity) {
  check_linear_reproduction(GimpBasis(1.0 / 16, 1.0 / 64),
                            {Transfer::flip, 1.0, PositionUpdate::particle});
}
TEST(G2P, PicTakesTheGridVelocity) {
  for (auto position : {PositionUpdate::grid, PositionUpdate::particle}) {
    check_linear_reproduction(GimpBasis(1.0 / 16, 1.0 / 64), {Transfer::pic, 0.95, position});
  }
}
TEST(G2P, BlendMixesFlipAndPic) {
  for (auto position : {PositionUpdate::grid, PositionUpdate::particle}) {
    check_linear_reproduction(LinearBasis(1.0 / 16), {Transfer::blend, 0.3, position});
    check_linear_reproduction(CpGimpBasis(1.0 / 16, 1.0 / 64), {Transfer::blend, 0.9, position});
  }
}

TEST(StressUpdate, NeoHookeanLaw) {
  const int cells = 16;
  Grid G(cells, Boundary::dirichlet);
  const double b = -1.7;
  for (Eigen::Index s = 0; s < G.velocity.size(); ++s)
    G.velocity[s] = 0.3 + b * (s - Grid::kOffset) * G.h;
  Particles P = random_particles(100, 0.0, 1.0, 9);
  const Particles before = P;
  const Eigen::ArrayXd body = Eigen::ArrayXd::Zero(P.size());
  Stencil<GimpBasis::width> S;
  S.resize(P.size());
  Grid scratch(cells, Boundary::dirichlet);
  p2g(GimpBasis(1.0 / cells, 1.0 / 64), P, body.data(), S, scratch);
  const double dt = 1e-2, E = 5.0;
  stress_update(S, G, dt, MaterialLaw{Material::neo_hookean, E}, P);
  for (Eigen::Index p = 0; p < P.size(); ++p) {
    const double F = before.F[p] * (1 + dt * b);
    EXPECT_NEAR(P.F[p], F, 1e-13) << p;
    EXPECT_NEAR(P.sigma[p], 0.5 * E * (F - 1 / F), 1e-12) << p;
  }
}

// The last phase of a step taking the state check in its own pass: USL's g2p and stress update
// as one pass (FLIP), g2p alone (USF), the stress update alone (MUSL, USL with another transfer).
// Each gives the state of the phases' definitions, evaluated here one particle at a time (sums
// from 0 in slot order), and the extremes of their definitions, bit for bit: for particles in
// order (8 at a time), out of order (one at a time) and a tail of 3.
enum class Last { g2p_and_stress, g2p, stress };

template <class Basis>
void check_last_phase(const Basis& basis, bool sorted, PositionUpdate position, Last last) {
  constexpr int W = Basis::width;
  const int cells = 25;
  Particles P = random_particles(203, 0.0, 1.0, 11);
  if (sorted) {
    for (Eigen::Index p = 0; p < P.size(); ++p)
      P.x[p] = P.X[p] = (p + 0.5 + 0.3 * std::sin(3.0 * p)) / P.size();
  }
  Grid G(cells, Boundary::dirichlet, Walls::clip, W);
  const Eigen::ArrayXd body = Eigen::ArrayXd::Random(P.size());
  Stencil<W> S;
  S.resize(P.size());
  p2g(basis, P, body.data(), S, G);
  const double dt = 2e-3;
  grid_update(G, dt);
  const ParticleUpdate rule{Transfer::flip, 0.95, position};
  const MaterialLaw law{Material::linear, 30.0};
  const Eigen::ArrayXd u = Eigen::ArrayXd::Random(P.size());
  const ErrorTerms terms{P.X.data(), u.data(), 0.37};
  const bool moves = last != Last::stress, stresses = last != Last::g2p;
  for (const bool plant_nan : {false, true}) {
    SCOPED_TRACE(plant_nan);
    Particles want = P, one = P;
    if (plant_nan) want.v[57] = one.v[57] = std::numeric_limits<double>::quiet_NaN();
    for (Eigen::Index p = 0; p < P.size(); ++p) {
      auto sum = [&](const auto& rows, const Eigen::ArrayXd& field) {
        double s = 0;
        for (int k = 0; k < W; ++k)
          s += rows[k][p] * field[S.base[p] + k];
        return s;
      };
      if (moves) {
        want.v[p] += dt * sum(S.w, G.accel);
        want.x[p] += dt * (position == PositionUpdate::grid ? sum(S.w, G.velocity) : want.v[p]);
      }
      if (stresses) {
        want.F[p] *= 1.0 + dt * sum(S.g, G.velocity);
        want.sigma[p] = law.E * (want.F[p] - 1.0);
      }
    }
    StateExtremes taken;
    const StateCheck check{&terms, &taken};
    bool took = false;
    switch (last) {
      case Last::g2p_and_stress:
        took = g2p_and_stress(S, G, dt, rule, law, one, &check);
        break;
      case Last::g2p:
        took = g2p(S, G, dt, rule, one, &check);
        break;
      case Last::stress:
        took = stress_update(S, G, dt, law, one, &check);
        break;
    }
    if (!took) GTEST_SKIP() << "no AVX-512 here";
    for (Eigen::Index p = 0; p < P.size(); ++p) {
      if (plant_nan && p == 57) continue;  // NaN != NaN
      ASSERT_EQ(one.x[p], want.x[p]) << p;
      ASSERT_EQ(one.v[p], want.v[p]) << p;
      ASSERT_EQ(one.F[p], want.F[p]) << p;
      ASSERT_EQ(one.sigma[p], want.sigma[p]) << p;
    }
    // The definitions of the extremes.
    StateExtremes e;
    e.finite = want.x.isFinite().all() && want.v.isFinite().all() && want.F.isFinite().all() &&
               want.sigma.isFinite().all();
    e.F_min = want.F.minCoeff();
    e.F_max = want.F.maxCoeff();
    e.F_abs_max = want.F.abs().maxCoeff();
    e.sigma_abs_max = want.sigma.abs().maxCoeff();
    e.sigmaF_abs_max = (want.sigma * want.F).abs().maxCoeff();
    e.x_min = want.x.minCoeff();
    e.x_max = want.x.maxCoeff();
    for (Eigen::Index p = 0; p < P.size(); ++p)
      e.error_max = std::max(e.error_max, std::abs((want.x[p] - P.X[p]) - u[p] * terms.factor));
    for (const StateExtremes& got : {taken, state_extremes(want, &terms)}) {
      EXPECT_EQ(got.finite, e.finite);
      if (plant_nan) continue;  // the values are read only for a finite state
      EXPECT_EQ(got.F_min, e.F_min);
      EXPECT_EQ(got.F_max, e.F_max);
      EXPECT_EQ(got.F_abs_max, e.F_abs_max);
      EXPECT_EQ(got.sigma_abs_max, e.sigma_abs_max);
      EXPECT_EQ(got.sigmaF_abs_max, e.sigmaF_abs_max);
      EXPECT_EQ(got.x_min, e.x_min);
      EXPECT_EQ(got.x_max, e.x_max);
      EXPECT_EQ(got.error_max, e.error_max);
    }
    EXPECT_EQ(taken.finite, !plant_nan);
    if (!plant_nan) {
      EXPECT_GT(taken.error_max, 0);
    }
  }
}

TEST(LastPhase, TakesTheCheckInItsPassBitForBit) {
  for (const Last last : {Last::g2p_and_stress, Last::g2p, Last::stress}) {
    for (const bool sorted : {true, false}) {
      for (const auto position : {PositionUpdate::grid, PositionUpdate::particle}) {
        SCOPED_TRACE(testing::Message() << int(last) << " " << sorted << " " << int(position));
        check_last_phase(LinearBasis(1.0 / 25), sorted, position, last);
        check_last_phase(GimpBasis(1.0 / 25, 1.0 / 100), sorted, position, last);
        check_last_phase(CpGimpBasis(1.0 / 25, 1.0 / 100), sorted, position, last);
      }
    }
  }
}

// Where the one pass does not apply (PIC, another material law), it does nothing; g2p with
// another transfer than FLIP, and the stress update with another law, do their phase and leave
// the check to be taken.
TEST(LastPhase, LeavesTheCheckWhereItCannotTakeIt) {
  Particles P = random_particles(40, 0.0, 1.0, 5);
  const Particles before = P;
  Grid G(10, Boundary::dirichlet);
  Stencil<GimpBasis::width> S;
  S.resize(P.size());
  const Eigen::ArrayXd body = Eigen::ArrayXd::Zero(P.size());
  p2g(GimpBasis(0.1, 0.025), P, body.data(), S, G);
  grid_update(G, 1e-3);
  EXPECT_FALSE(g2p_and_stress(S, G, 1e-3, ParticleUpdate{Transfer::pic, 0.95, PositionUpdate::grid},
                              MaterialLaw{Material::linear, 4.0}, P, nullptr));
  EXPECT_FALSE(g2p_and_stress(S, G, 1e-3, ParticleUpdate{}, MaterialLaw{Material::neo_hookean, 4.0},
                              P, nullptr));
  EXPECT_TRUE((P.x == before.x).all() && (P.F == before.F).all());
  StateExtremes untouched;
  untouched.F_min = -7;
  const StateCheck check{nullptr, &untouched};
  EXPECT_FALSE(
      g2p(S, G, 1e-3, ParticleUpdate{Transfer::pic, 0.95, PositionUpdate::grid}, P, &check));
  EXPECT_FALSE((P.x == before.x).all());  // the phase was done
  EXPECT_FALSE(stress_update(S, G, 1e-3, MaterialLaw{Material::neo_hookean, 4.0}, P, &check));
  EXPECT_FALSE((P.F == before.F).all());
  EXPECT_EQ(untouched.F_min, -7);
}

TEST(GridUpdate, DirichletNodesAndEmptyNodesStayAtRest) {
  Grid G(4, Boundary::dirichlet);
  G.mass << 1, 1, 1, 0, 1, 1, 1;  // slots -1..5; node 2 empty
  G.momentum.setConstant(2.0);
  G.force.setConstant(4.0);
  grid_update(G, 0.5);
  const int o = Grid::kOffset;
  EXPECT_EQ(G.velocity[o + 0], 0.0);
  EXPECT_EQ(G.velocity[o + 4], 0.0);
  EXPECT_EQ(G.velocity[o + 2], 0.0);
  EXPECT_EQ(G.velocity[o - 1], 0.0);
  EXPECT_EQ(G.velocity[o + 5], 0.0);
  // v = q / m + dt f / m = 2 + 0.5 * 4 = 4; a = f / m = 4.
  EXPECT_DOUBLE_EQ(G.velocity[o + 1], 4.0);
  EXPECT_DOUBLE_EQ(G.accel[o + 3], 4.0);
}

TEST(GridUpdate, GhostNodesAreFreeAndTheWallsFixed) {
  Grid G(4, Boundary::dirichlet, Walls::ghost);
  G.mass << 1, 1, 1, 0, 1, 1, 1;  // slots -1..5; node 2 empty
  G.momentum.setConstant(2.0);
  G.force.setConstant(4.0);
  grid_update(G, 0.5);
  const int o = Grid::kOffset;
  EXPECT_EQ(G.velocity[o + 0], 0.0);  // walls
  EXPECT_EQ(G.velocity[o + 4], 0.0);
  EXPECT_EQ(G.velocity[o + 2], 0.0);         // no mass
  EXPECT_DOUBLE_EQ(G.velocity[o - 1], 4.0);  // ghost nodes: as interior nodes
  EXPECT_DOUBLE_EQ(G.velocity[o + 5], 4.0);
  EXPECT_DOUBLE_EQ(G.accel[o - 1], 4.0);
  EXPECT_EQ(G.first_node_slot(), 0);
  EXPECT_EQ(G.nodes(), 7);
}

TEST(GridVelocity, IsMomentumOverMassWithTheBoundaryConditions) {
  for (Walls walls : {Walls::clip, Walls::ghost}) {
    Grid G(4, Boundary::dirichlet, walls);
    G.mass << 2, 1, 2, 0, 4, 1, 2;
    G.momentum.setConstant(2.0);
    G.force.setConstant(100.0);  // not used
    grid_velocity(G);
    const int o = Grid::kOffset;
    EXPECT_EQ(G.velocity[o], 0.0);
    EXPECT_EQ(G.velocity[o + 4], 0.0);
    EXPECT_EQ(G.velocity[o + 2], 0.0);
    EXPECT_DOUBLE_EQ(G.velocity[o + 1], 1.0);
    EXPECT_DOUBLE_EQ(G.velocity[o + 3], 0.5);
    EXPECT_EQ(G.velocity[o - 1], walls == Walls::ghost ? 1.0 : 0.0);
  }
}

// USF folds the images for its v_i^n and again in the grid update: the second fold adds nothing.
TEST(GridVelocity, PeriodicImagesFoldOnce) {
  const int cells = 20;
  Particles P = random_particles(300, -0.7, 1.7, 3);
  const Eigen::ArrayXd body = Eigen::ArrayXd::Random(P.size());
  Stencil<GimpBasis::width> S;
  S.resize(P.size());
  Grid once(cells, Boundary::periodic), twice(cells, Boundary::periodic);
  p2g(GimpBasis(1.0 / cells, 1.0 / 80), P, body.data(), S, once);
  p2g(GimpBasis(1.0 / cells, 1.0 / 80), P, body.data(), S, twice);
  grid_velocity(twice);
  grid_update(once, 1e-3);
  grid_update(twice, 1e-3);
  EXPECT_TRUE((once.mass == twice.mass).all());
  EXPECT_TRUE((once.velocity == twice.velocity).all());
  EXPECT_NEAR(once.mass.segment(Grid::kOffset, cells).sum(), P.mass.sum(), 1e-15 * P.size());
}

}  // namespace
}  // namespace mpmstab
