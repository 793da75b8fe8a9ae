// Transfers: p2g conserves mass and momentum, g2p and the velocity gradient reproduce linear
// nodal fields.
#include <gtest/gtest.h>

#include <random>

#include "phases.hpp"
#include "shape.hpp"

namespace mpmstab {
namespace {

Particles random_particles(int n, double lo, double hi, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(lo, hi), val(-1.0, 1.0), pos_val(0.5, 1.5);
  Particles P;
  P.resize(n);
  for (int p = 0; p < n; ++p) {
    P.x[p] = P.X[p] = pos(rng);
    P.v[p] = val(rng);
    P.F[p] = pos_val(rng);
    P.sigma[p] = val(rng);
    P.mass[p] = pos_val(rng) * 1e-3;
    P.volume0[p] = pos_val(rng) * 1e-3;
  }
  return P;
}

template <class Basis>
void check_conservation(const Basis& basis, Boundary bc, double lo, double hi) {
  const int cells = 20;
  Grid G(cells, bc);
  Particles P = random_particles(300, lo, hi, 42);
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
void check_linear_reproduction(const Basis& basis, PositionUpdate mode) {
  const int cells = 16;
  Grid G(cells, Boundary::dirichlet);
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
  Grid scratch(cells, Boundary::dirichlet);
  p2g(basis, P, body.data(), S, scratch);  // fills the stencil at x^n

  const double dt = 1e-2, E = 5.0;
  g2p(S, G, dt, mode, P);
  stress_update(S, G, dt, E, P);
  for (Eigen::Index p = 0; p < P.size(); ++p) {
    const double x0 = before.x[p];
    const double v_new = before.v[p] + dt * (c + d * x0);
    EXPECT_NEAR(P.v[p], v_new, 1e-14) << p;
    const double moved = mode == PositionUpdate::grid ? dt * (a + b * x0) : dt * v_new;
    EXPECT_NEAR(P.x[p], x0 + moved, 1e-14) << p;
    // L_p = dv/dx = b exactly.
    EXPECT_NEAR(P.F[p], before.F[p] * (1 + dt * b), 1e-13) << p;
    EXPECT_NEAR(P.sigma[p], E * (P.F[p] - 1), 1e-13) << p;
  }
}

TEST(G2P, ReproducesLinearFieldsLinear) {
  check_linear_reproduction(LinearBasis(1.0 / 16), PositionUpdate::grid);
}
TEST(G2P, ReproducesLinearFieldsGimp) {
  check_linear_reproduction(GimpBasis(1.0 / 16, 1.0 / 64), PositionUpdate::grid);
}
TEST(G2P, ParticleVelocityPositionUpdateUsesTheNewParticleVelocity) {
  check_linear_reproduction(GimpBasis(1.0 / 16, 1.0 / 64), PositionUpdate::particle);
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

}  // namespace
}  // namespace mpmstab
