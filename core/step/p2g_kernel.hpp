// p2g's kernel (phases.hpp), shared by the translation units that instantiate it: phases.cpp
// for the paper's bases (mpm, gimp, cpgimp) and p2g_bases.cpp for the others. The others are
// instantiated apart: with the B-spline instantiations in phases.cpp, GCC's function
// multiversioning of this template (MPMSTAB_SIMD_CLONES) ran the paper's bases' p2g much slower
// (BM_Step, one core: GIMP 3.72 -> 7.07 ns per particle-step, MPM 2.64 -> 3.39, cpGIMP about
// 8.3), and apart they run as before (GIMP 3.72, MPM 2.58). The cause inside GCC was not
// pinned down. Internal to core/: included by those two files only.
#pragma once

#include <array>
#include <cmath>
#include <type_traits>
#include <utility>

#include "step/phases.hpp"

#include "base/simd.hpp"

namespace mpmstab {

// ---------------------------------------------------------------------------------------------
// p2g, eqs. (5)-(7). Particles go in blocks of kBlock. For a block, first S_ip, G_ip and each
// particle's force on each of its W nodes (independent iterations, vectorized across particles);
// then the sums into the grid, particle after particle, so that every node adds its
// contributions in particle order as the plain scatter does (the order fixes the rounding). The
// mass and momentum contributions (S_ip m_p, S_ip m_p v_p) are formed there, one 2-lane multiply
// per node, from the stored S_ip: storing them from the vectorized loop instead took two vector
// stores and a permutation per node and 8 particles, and ran GIMP 3%, cpGIMP 3-7% slower in
// every version (whole runs, best of 3 interleaved, on an AMD EPYC with AVX-512).
// Particles stay nearly sorted, so consecutive ones share nodes: the W nodes under the current
// particle are held in registers (Window), loaded from the grid when they enter and written
// back when they leave. This removes the chain of store and reload of the same node from one
// particle to the next, which bounds the plain scatter, and gives the same sums as it in any
// particle order (a jump of the stencil writes back and reloads all W nodes).
namespace {

constexpr int kBlock = 32;  // the contributions of a block stay in L1 until they are summed

// (m_i, q_i) of one node: one 2-lane add does the mass and the momentum sums together.
using Pair = double __attribute__((vector_size(16)));

template <int W>
struct alignas(64) Contributions {
  double f[W][kBlock];  // -G_ip sigma_p V_p + S_ip m_p b_p
};

template <int W>
struct Window {
  int b = 0;    // storage index of the first node
  Pair mq[W];   // nodes b .. b + W - 1
  double f[W];  //
};

// The boundary-modified B-splines' values for the particles of a block next to a wall, one at a
// time (shape.hpp). Out of line, so that evaluate_block stays small enough to be inlined, and so
// vectorized, in each instruction set's p2g_kernel.
template <class Basis, int W = Basis::width>
__attribute__((noinline)) void modify_block(const Basis& basis, const double* x, int len,
                                            const int* base, double* const* w, double* const* g) {
  for (int j = 0; j < len; ++j) {
    double wp[W], gp[W];
    for (int k = 0; k < W; ++k) {
      wp[k] = w[k][j];
      gp[k] = g[k][j];
    }
    basis.modify(x[j], base[j] - Grid::kOffset, wp, gp);
    for (int k = 0; k < W; ++k) {
      w[k][j] = wp[k];
      g[k][j] = gp[k];
    }
  }
}

// Always inlined into p2g_kernel: each of its instruction-set clones then vectorizes the loops
// for its own vector width (not inlined, it would be compiled once, for the baseline).
template <bool kPeriodic, bool kForce, class Basis>
__attribute__((always_inline)) inline void evaluate_block(const Basis& basis, const Particles& P,
                                                          const double* body_accel, Eigen::Index p0,
                                                          int len, Stencil<Basis::width>& S,
                                                          Contributions<Basis::width>& C) {
  constexpr int W = Basis::width;
  const double* __restrict x = P.x.data() + p0;
  const double* __restrict F = P.F.data() + p0;
  const double* __restrict sig = P.sigma.data() + p0;
  const double* __restrict m_p = P.mass.data() + p0;
  const double* __restrict V0 = P.volume0.data() + p0;
  const double* __restrict b_p = kForce ? body_accel + p0 : nullptr;
  int* __restrict base = S.base.data() + p0;
  double *w[W], *g[W];
  for (int k = 0; k < W; ++k) {
    w[k] = S.w[k].data() + p0;
    g[k] = S.g[k].data() + p0;
  }
  // What particle j adds to its nodes, from its S_ip and G_ip.
  auto contribute = [&](int j, const double* wp, const double* gp) __attribute__((always_inline)) {
    if constexpr (kForce) {
      const double stress_volume = -sig[j] * F[j] * V0[j];  // V_p = F_p V_p^0 (eq. 6)
      const double body = m_p[j] * b_p[j];
      for (int k = 0; k < W; ++k)
        C.f[k][j] = gp[k] * stress_volume + wp[k] * body;
    }
  };
  // S_ip, G_ip, the base node and the contributions of every particle of the block; for the
  // B-splines, with or without the elimination of the ghost nodes (a choice made once per block,
  // so that the loop is free of control flow and vectorizes).
  const auto evaluate = [&]<bool kEliminate>() __attribute__((always_inline)) {
    MPMSTAB_IVDEP
    for (int j = 0; j < len; ++j) {
      double xp = x[j];
      if constexpr (kPeriodic) xp = fractional_part(xp);
      int bp;
      double wp[W], gp[W];
      if constexpr (requires { basis.eval(xp, F[j], bp, wp, gp); }) {
        basis.eval(xp, F[j], bp, wp, gp);  // a domain that follows F_p (cpGIMP, CPDI)
      } else if constexpr (requires { basis.eliminate; }) {
        basis.template eval_vector<kEliminate>(xp, bp, wp, gp);  // B-splines: walls below
      } else {
        basis.eval(xp, bp, wp, gp);
      }
      base[j] = bp + Grid::kOffset;
      for (int k = 0; k < W; ++k) {
        w[k][j] = wp[k];
        g[k][j] = gp[k];
      }
      contribute(j, wp, gp);
    }
  };
  if constexpr (requires { basis.eliminate; }) {
    if (basis.eliminate) {
      evaluate.template operator()<true>();
    } else {
      evaluate.template operator()<false>();
    }
  } else {
    evaluate.template operator()<false>();
  }
  // B-splines with modified walls (shape.hpp): the particles next to a wall get the modified
  // values, and the block's contributions are made again from them.
  if constexpr (requires { basis.modifies(); }) {
    if (!basis.modifies()) return;
    modify_block(basis, x, len, base, w, g);
    for (int j = 0; j < len; ++j) {
      double wp[W], gp[W];
      for (int k = 0; k < W; ++k) {
        wp[k] = w[k][j];
        gp[k] = g[k][j];
      }
      contribute(j, wp, gp);
    }
  }
}

// Always inlined into p2g_kernel, as evaluate_block is (out of line it is compiled once, for the
// baseline: BM_Step, GIMP, 3.5 -> 6.3 ns per particle-step when GCC chose not to inline it).
template <int W, bool kForce>
__attribute__((always_inline)) inline void scatter_block(const int* base, int len,
                                                         const double* const* w, const double* m_p,
                                                         const double* v, const Contributions<W>& C,
                                                         Window<W>& win, double* __restrict m_i,
                                                         double* __restrict q_i,
                                                         double* __restrict f_i) {
  int b = win.b;
  Pair mq[W];
  double f[W];
  for (int k = 0; k < W; ++k) {
    mq[k] = win.mq[k];
    f[k] = win.f[k];
  }
  for (int j = 0; j < len; ++j) {
    const int bp = base[j];
    if (bp != b) {
      if (bp == b + 1) {  // the usual move: node b leaves, node b + W enters
        m_i[b] = mq[0][0];
        q_i[b] = mq[0][1];
        if constexpr (kForce) f_i[b] = f[0];
        for (int k = 0; k + 1 < W; ++k) {
          mq[k] = mq[k + 1];
          f[k] = f[k + 1];
        }
        mq[W - 1] = Pair{m_i[bp + W - 1], q_i[bp + W - 1]};
        if constexpr (kForce) f[W - 1] = f_i[bp + W - 1];
      } else {
        for (int k = 0; k < W; ++k) {
          m_i[b + k] = mq[k][0];
          q_i[b + k] = mq[k][1];
          if constexpr (kForce) f_i[b + k] = f[k];
        }
        for (int k = 0; k < W; ++k) {
          mq[k] = Pair{m_i[bp + k], q_i[bp + k]};
          if constexpr (kForce) f[k] = f_i[bp + k];
        }
      }
      b = bp;
    }
    // (S_ip m_p, S_ip m_p v_p) to node base_p + k, the two products of one 2-lane multiply.
    const double mass = m_p[j];
    const Pair mm = {mass, mass * v[j]};
    for (int k = 0; k < W; ++k) {
      const double s = w[k][j];
      mq[k] += Pair{s, s} * mm;
      if constexpr (kForce) f[k] += C.f[k][j];
    }
  }
  win.b = b;
  for (int k = 0; k < W; ++k) {
    win.mq[k] = mq[k];
    win.f[k] = f[k];
  }
}

template <bool kPeriodic, bool kForce, class Basis>
MPMSTAB_SIMD_CLONES void p2g_kernel(const Basis& basis, const Particles& P,
                                    const double* body_accel, Stencil<Basis::width>& S, Grid& G) {
  constexpr int W = Basis::width;
  G.mass.setZero();
  G.momentum.setZero();
  if constexpr (kForce) G.force.setZero();
  Window<W> win;  // at slot 0, which holds the cleared values
  for (int k = 0; k < W; ++k) {
    win.mq[k] = Pair{0.0, 0.0};
    win.f[k] = 0.0;
  }
  Contributions<W> C;
  const Eigen::Index n = P.size();
  for (Eigen::Index p0 = 0; p0 < n; p0 += kBlock) {
    const int len = n - p0 < kBlock ? static_cast<int>(n - p0) : kBlock;
    if (len == kBlock) {  // a constant trip count vectorizes best
      evaluate_block<kPeriodic, kForce>(basis, P, body_accel, p0, kBlock, S, C);
    } else {
      evaluate_block<kPeriodic, kForce>(basis, P, body_accel, p0, len, S, C);
    }
    const double* w[W];
    for (int k = 0; k < W; ++k)
      w[k] = S.w[k].data() + p0;
    scatter_block<W, kForce>(S.base.data() + p0, len, w, P.mass.data() + p0, P.v.data() + p0, C,
                             win, G.mass.data(), G.momentum.data(), G.force.data());
  }
  for (int k = 0; k < W; ++k) {
    G.mass[win.b + k] = win.mq[k][0];
    G.momentum[win.b + k] = win.mq[k][1];
    if constexpr (kForce) G.force[win.b + k] = win.f[k];
  }
}

template <class Basis>
void p2g_any(const Basis& basis, const Particles& P, const double* body_accel,
             Stencil<Basis::width>& S, Grid& G) {
  const bool periodic = G.bc == Boundary::periodic;
  if (body_accel) {
    (periodic ? p2g_kernel<true, true, Basis> : p2g_kernel<false, true, Basis>)(basis, P,
                                                                                body_accel, S, G);
  } else {  // m_i and q_i only (USF, whose f_i comes after its stress update)
    (periodic ? p2g_kernel<true, false, Basis> : p2g_kernel<false, false, Basis>)(basis, P,
                                                                                  body_accel, S, G);
  }
}

}  // namespace

}  // namespace mpmstab
