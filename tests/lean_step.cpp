// The lean loop of `make bench-versions` (bench_versions.cpp): the paper's bar under USL with
// FLIP and the position from the grid velocity, the solver's default algorithm, written as a
// careful programmer writes it in one file without the solver's kernels. Particles and grid are
// plain arrays (struct of arrays); S_ip and G_ip come from their piecewise definitions, once per
// step, and are kept for g2p and the stress update; nodes beyond a wall are clipped (GIMP, MPM)
// or eliminated by linear extrapolation (the B-splines), as the solver's default walls do. No
// intrinsics and no hand-made vector code: what the compiler makes of it for the instruction set
// it is compiled for (tests/CMakeLists.txt compiles it once per version). The initial state and
// the body force's profile are the bar scene's (bench_versions.cpp, compiled with the library's
// flags: no type of the library crosses into this file but plain vectors and RunParams).
#include "lean_step.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>
#include <vector>

namespace mpmstab::lean {

namespace {

constexpr int kMaxWidth = 4;
constexpr int kPad = 2;  // nodes beyond each wall in the grid arrays

// N(r) and dN/dr of node i for a particle at distance r = x_p - X_i, in units of h, and the
// first node a particle at x touches (in cells) with the number of nodes.
struct Shape {
  Method method;
  double lp = 0;  // GIMP's half-width in cells

  int width() const {
    switch (method) {
      case Method::mpm:
        return 2;
      case Method::bspline3:
        return 4;
      default:
        return 3;
    }
  }
  int first(double s) const {  // s = x / h
    switch (method) {
      case Method::gimp:
        return static_cast<int>(std::floor(s - lp));
      case Method::bspline2:
        return static_cast<int>(std::floor(s - 0.5));
      case Method::bspline3:
        return static_cast<int>(std::floor(s)) - 1;
      default:
        return static_cast<int>(std::floor(s));
    }
  }
  void eval(double r, double& n, double& d) const {
    const double a = std::abs(r), sign = r < 0 ? -1.0 : 1.0;
    n = d = 0.0;
    switch (method) {
      case Method::mpm:
        if (a < 1) n = 1 - a, d = -sign;
        return;
      case Method::gimp:  // Bardenhagen & Kober's five branches
        if (a < lp) {
          n = 1 - (r * r + lp * lp) / (2 * lp), d = -r / lp;
        } else if (a <= 1 - lp) {
          n = 1 - a, d = -sign;
        } else if (a < 1 + lp) {
          n = (1 + lp - a) * (1 + lp - a) / (4 * lp), d = -sign * (1 + lp - a) / (2 * lp);
        }
        return;
      case Method::bspline2:
        if (a < 0.5) {
          n = 0.75 - a * a, d = -2 * r;
        } else if (a < 1.5) {
          n = 0.5 * (1.5 - a) * (1.5 - a), d = -sign * (1.5 - a);
        }
        return;
      case Method::bspline3:
        if (a < 1) {
          n = 2.0 / 3.0 - a * a + 0.5 * a * a * a, d = sign * (-2 * a + 1.5 * a * a);
        } else if (a < 2) {
          n = (2 - a) * (2 - a) * (2 - a) / 6, d = -sign * 0.5 * (2 - a) * (2 - a);
        }
        return;
      default:
        return;
    }
  }
};

struct Bar {
  RunParams p;
  Shape shape;
  double h, c_pi;                                           // c pi, c = sqrt(E / rho0)
  std::vector<double> x, v, F, sigma, mass, volume0, body;  // particles
  std::vector<int> first;                                   // first node of each particle
  std::vector<double> S, G;                                 // [p * kMaxWidth + k]
  std::vector<double> m, q, f, vel, acc;                    // nodes -kPad .. N + kPad
  double t = 0;

  Bar(const RunParams& params, State state)
      : p(params),
        shape{p.method, p.method == Method::gimp ? 0.5 / p.ppc : 0.0},
        h(1.0 / p.cells),
        c_pi(std::sqrt(p.E) * 3.14159265358979323846),
        x(std::move(state.x)),
        v(std::move(state.v)),
        F(std::move(state.F)),
        sigma(std::move(state.sigma)),
        mass(std::move(state.mass)),
        volume0(std::move(state.volume0)),
        body(std::move(state.body)) {
    const std::size_t n = x.size(), nodes = static_cast<std::size_t>(p.cells) + 1 + 2 * kPad;
    first.resize(n);
    S.resize(n * kMaxWidth);
    G.resize(n * kMaxWidth);
    for (auto* a : {&m, &q, &f, &vel, &acc})
      a->resize(nodes);
  }

  // S_ip, G_ip of particle j's nodes first .. first + W - 1; walls as the solver's defaults. The
  // grid arrays hold kPad nodes beyond each wall, so that every stencil fits; they keep 0.
  void weights(std::size_t j) {
    const int W = shape.width(), N = p.cells;
    const double s = x[j] / h;
    const int b = shape.first(s);
    double* Sj = &S[j * kMaxWidth];
    double* Gj = &G[j * kMaxWidth];
    for (int k = 0; k < W; ++k) {
      shape.eval(s - (b + k), Sj[k], Gj[k]);
      Gj[k] /= h;
    }
    const bool spline = p.method == Method::bspline2 || p.method == Method::bspline3;
    for (int k = 0; k < W; ++k) {
      const int i = b + k;
      if (i >= 0 && i <= N) continue;
      if (spline && (i == -1 || i == N + 1)) {  // c_{-1} = 2 c_0 - c_1, c_{N+1} = 2 c_N - c_{N-1}
        const int in = i == -1 ? k + 1 : k - 1, next = i == -1 ? k + 2 : k - 2;
        Sj[in] += 2 * Sj[k], Sj[next] -= Sj[k];
        Gj[in] += 2 * Gj[k], Gj[next] -= Gj[k];
      }
      Sj[k] = Gj[k] = 0.0;  // no such node
    }
    first[j] = b + kPad;
  }

  void step(double dt) {
    const int W = shape.width(), N = p.cells;
    const std::size_t n = x.size();
    const double factor = std::sin(c_pi * t);  // b = profile(X) sin(c pi t)
    std::fill(m.begin(), m.end(), 0.0);
    std::fill(q.begin(), q.end(), 0.0);
    std::fill(f.begin(), f.end(), 0.0);
    for (std::size_t j = 0; j < n; ++j) {  // p2g, eqs. (5)-(7)
      weights(j);
      const double* Sj = &S[j * kMaxWidth];
      const double* Gj = &G[j * kMaxWidth];
      const double stress_volume = -sigma[j] * F[j] * volume0[j];
      const double force = mass[j] * body[j] * factor;
      for (int k = 0; k < W; ++k) {
        const int i = first[j] + k;
        m[i] += Sj[k] * mass[j];
        q[i] += Sj[k] * mass[j] * v[j];
        f[i] += Gj[k] * stress_volume + Sj[k] * force;
      }
    }
    for (int i = kPad; i <= N + kPad; ++i) {  // grid update, eqs. (7), (8); nodes 0, N fixed
      const bool free = i > kPad && i < N + kPad && m[i] > 0.0;
      acc[i] = free ? f[i] / m[i] : 0.0;
      vel[i] = free ? q[i] / m[i] + dt * acc[i] : 0.0;
    }
    for (std::size_t j = 0; j < n; ++j) {  // g2p, eqs. (9), (10); stress, eqs. (11)-(14)
      const double* Sj = &S[j * kMaxWidth];
      const double* Gj = &G[j * kMaxWidth];
      double a = 0, u = 0, L = 0;
      for (int k = 0; k < W; ++k) {
        const int i = first[j] + k;
        a += Sj[k] * acc[i];
        u += Sj[k] * vel[i];
        L += Gj[k] * vel[i];
      }
      v[j] += dt * a;
      x[j] += dt * u;
      F[j] *= 1.0 + dt * L;
      sigma[j] = p.E * (F[j] - 1.0);
    }
    t += dt;
  }
};

}  // namespace

bool supports(Method m) {
  return m == Method::mpm || m == Method::gimp || m == Method::bspline2 || m == Method::bspline3;
}

Timing run(const RunParams& p, State initial, State* final_state) {
  Bar bar(p, std::move(initial));
  const auto steps = static_cast<std::int64_t>(std::llround(p.T / p.dt));
  const auto start = std::chrono::steady_clock::now();
  for (std::int64_t s = 0; s < steps; ++s)
    bar.step(p.dt);
  const std::chrono::duration<double> wall = std::chrono::steady_clock::now() - start;
  double checksum = 0;
  for (const double xp : bar.x)
    checksum += xp;
  const auto particles = static_cast<std::int64_t>(bar.x.size());
  if (final_state) *final_state = {bar.x, bar.v, bar.F, bar.sigma, bar.mass, bar.volume0, bar.body};
  return {wall.count(), steps * particles, checksum};
}

}  // namespace mpmstab::lean
