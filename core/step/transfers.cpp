// The velocity transfers other than FLIP (g2p of PIC, blend, APIC, XPIC and FMPM) and the
// partial p2g sums of USF, MUSL and APIC (phases.hpp). As in phases.cpp, every kernel keeps the
// arithmetic of the plain loop it replaces operation for operation: vector lanes are independent
// particles, and each grid node sums its contributions in particle order.
#include <cmath>
#include <utility>

#include "step/g2p_kernel.hpp"

namespace mpmstab {

// The partial p2g sums of USF and MUSL, and APIC's: one field summed over the stencil p2g kept,
// with p2g's arithmetic per contribution. As in p2g (p2g_kernel.hpp), a block's contributions
// are computed first, independent across particles (vectorized), then added in particle order
// through a window of the W nodes under the current particle, so that each node sums exactly
// as the plain scatter `field[base_p + k] += c_kp` does, in any particle order.
namespace {

constexpr int kFieldBlock = 32;  // a block's contributions stay in L1 until they are summed

template <int W>
struct FieldBlock {
  alignas(64) double c[W][kFieldBlock];  // what particle p0 + j adds to node base_{p0+j} + k
};

template <int W>
struct FieldWindow {
  int b = 0;  // storage index of the first node held
  double v[W] = {};
};

template <int W>
MPMSTAB_INLINE void scatter_field(const int* base, int len, const FieldBlock<W>& C,
                                  FieldWindow<W>& win, double* __restrict field) {
  int b = win.b;
  double v[W];
  for (int k = 0; k < W; ++k)
    v[k] = win.v[k];
  for (int j = 0; j < len; ++j) {
    const int bp = base[j];
    if (bp != b) {
      if (bp == b + 1) {  // node b leaves, node b + W enters
        field[b] = v[0];
        for (int k = 0; k + 1 < W; ++k)
          v[k] = v[k + 1];
        v[W - 1] = field[bp + W - 1];
      } else {
        for (int k = 0; k < W; ++k)
          field[b + k] = v[k];
        for (int k = 0; k < W; ++k)
          v[k] = field[bp + k];
      }
      b = bp;
    }
    for (int k = 0; k < W; ++k)
      v[k] += C.c[k][j];
  }
  win.b = b;
  for (int k = 0; k < W; ++k)
    win.v[k] = v[k];
}

// field[base_p + k] += contribution(p, k, out) for every particle, in particle order; `fill`
// writes out.c[k][j] for the particles p0 .. p0 + len - 1 of a block. The field is not cleared.
template <int W, class Fill>
MPMSTAB_INLINE void scatter_in_order(const AlignedVector<int>& base, Eigen::Index n, double* field,
                                     Fill fill) {
  FieldBlock<W> C;
  FieldWindow<W> win;
  win.b = base.empty() ? 0 : base[0];
  for (int k = 0; k < W; ++k)
    win.v[k] = n > 0 ? field[win.b + k] : 0.0;
  for (Eigen::Index p0 = 0; p0 < n; p0 += kFieldBlock) {
    const int len = n - p0 < kFieldBlock ? static_cast<int>(n - p0) : kFieldBlock;
    fill(p0, len, C);
    scatter_field<W>(base.data() + p0, len, C, win, field);
  }
  if (n > 0)
    for (int k = 0; k < W; ++k)
      field[win.b + k] = win.v[k];
}

// The kernels of p2g_force, p2g_momentum and p2g_affine, compiled for each instruction set (the
// fill loops vectorize across particles at the widest vector the CPU has).

template <int W>
MPMSTAB_SIMD_CLONES void force_kernel(const Stencil<W>& S, const Particles& P,
                                      const double* body_accel, Grid& G) {
  G.force.setZero();
  const double* __restrict sig = P.sigma.data();
  const double* __restrict F = P.F.data();
  const double* __restrict V0 = P.volume0.data();
  const double* __restrict m_p = P.mass.data();
  const Rows<W> w = rows<W>(S.w), g = rows<W>(S.g);
  scatter_in_order<W>(
      S.base, P.size(),
      G.force.data(), [&](Eigen::Index p0, int len, auto& C) __attribute__((always_inline)) {
        MPMSTAB_IVDEP
        for (int j = 0; j < len; ++j) {
          const auto p = p0 + j;
          const double stress_volume = -sig[p] * F[p] * V0[p];  // V_p = F_p V_p^0
          const double body = m_p[p] * body_accel[p];
          for (int k = 0; k < W; ++k)
            C.c[k][j] = g[k][p] * stress_volume + w[k][p] * body;
        }
      });
}

template <int W>
MPMSTAB_SIMD_CLONES void momentum_kernel(const Stencil<W>& S, const Particles& P, Grid& G) {
  G.momentum.setZero();
  const double* __restrict v = P.v.data();
  const double* __restrict m_p = P.mass.data();
  const Rows<W> w = rows<W>(S.w);
  scatter_in_order<W>(
      S.base, P.size(),
      G.momentum.data(), [&](Eigen::Index p0, int len, auto& C) __attribute__((always_inline)) {
        MPMSTAB_IVDEP
        for (int j = 0; j < len; ++j) {
          const auto p = p0 + j;
          const double mom = m_p[p] * v[p];
          for (int k = 0; k < W; ++k)
            C.c[k][j] = w[k][p] * mom;
        }
      });
}

template <int W>
MPMSTAB_SIMD_CLONES void affine_kernel(const Stencil<W>& S, const double* x_stencil,
                                       const Particles& P, Grid& G) {
  const bool periodic = G.bc == Boundary::periodic;
  const double h = G.h;
  const double* __restrict xs = x_stencil;
  const double* __restrict Cp = P.C.data();
  const double* __restrict m_p = P.mass.data();
  const int* __restrict base = S.base.data();
  const Rows<W> w = rows<W>(S.w);
  scatter_in_order<W>(
      S.base, P.size(),
      G.momentum.data(), [&](Eigen::Index p0, int len, auto& C) __attribute__((always_inline)) {
        for (int j = 0; j < len; ++j) {
          const auto p = p0 + j;
          const double x = periodic ? fractional_part(xs[p]) : xs[p];
          const double mC = m_p[p] * Cp[p];
          const int b = base[p];  // storage slot of the first node
          for (int k = 0; k < W; ++k) {
            const double X = (b - Grid::kOffset + k) * h;
            C.c[k][j] = w[k][p] * mC * (X - x);
          }
        }
      });
}

}  // namespace

template <int W>
void p2g_force(const Stencil<W>& S, const Particles& P, const double* body_accel, Grid& G) {
  force_kernel<W>(S, P, body_accel, G);
}

template <int W>
void p2g_momentum(const Stencil<W>& S, const Particles& P, Grid& G) {
  momentum_kernel<W>(S, P, G);
}

template <int W>
void p2g_affine(const Stencil<W>& S, const double* x_stencil, const Particles& P, Grid& G) {
  affine_kernel<W>(S, x_stencil, P, G);
}

namespace {

// PIC, blended, APIC, XPIC and FMPM transfers (phases.hpp): the arithmetic of one particle.
template <int W, Transfer kTransfer>
struct TransferInputs {
  const int* __restrict base;
  Rows<W> w, g;
  const double* __restrict a_i;
  const double* __restrict v_i;
  const double* __restrict w_i;  // XPIC's correction
  double alpha;                  // FLIP share of a blend
  bool grid_position;
};

template <int W, Transfer kTransfer>
inline void transfer_particle(std::size_t p, const TransferInputs<W, kTransfer>& in,
                              double* __restrict x, double* __restrict v, double* __restrict C,
                              double dt) {
  const int b = in.base[p];
  const double v_grid = interpolate<W>(in.w, p, in.v_i, b);  // sum_i S_ip v_i
  double v_new = v_grid;
  if constexpr (kTransfer == Transfer::blend) {
    const double v_flip = v[p] + dt * interpolate<W>(in.w, p, in.a_i, b);
    v_new = in.alpha * v_flip + (1.0 - in.alpha) * v_grid;
  }
  if constexpr (kTransfer == Transfer::apic) {
    C[p] = interpolate<W>(in.g, p, in.v_i, b);  // C_p = sum_i G_ip v_i
  }
  if constexpr (kTransfer == Transfer::xpic) {
    v_new = v_grid + interpolate<W>(in.w, p, in.w_i, b);  // + sum_i S_ip w_i
  }
  v[p] = v_new;
  x[p] += dt * (in.grid_position ? v_grid : v_new);
}

MPMSTAB_LANES_BEGIN

// transfer_particle for L::n particles at a time (g2p_kernel.hpp), lane for lane the same
// operations.
template <class L, int W, Transfer kTransfer>
MPMSTAB_LANES_BODY void transfer_lanes(std::size_t n, const TransferInputs<W, kTransfer>& in,
                                       int slots, double* __restrict x, double* __restrict v,
                                       double* __restrict C, double dt) {
  using V = typename L::V;
  const V dtv = L::set1(dt), alpha = L::set1(in.alpha), beta = L::set1(1.0 - in.alpha);
  std::size_t p0 = 0;
  for (; p0 + L::n <= n; p0 += L::n) {
    typename L::Where r;
    if (!L::template where<W>(in.base, p0, slots, r)) {
      for (std::size_t p = p0; p < p0 + L::n; ++p)
        transfer_particle<W, kTransfer>(p, in, x, v, C, dt);
      continue;
    }
    const typename L::Slots vs = L::slots(in.v_i, r);
    const V v_grid = L::template interpolate<W>(in.w, p0, vs, r);
    V v_new = v_grid;
    if constexpr (kTransfer == Transfer::blend) {
      const V a = L::template interpolate<W>(in.w, p0, L::slots(in.a_i, r), r);
      const V v_flip = L::add(L::load(v + p0), L::mul(dtv, a));
      v_new = L::add(L::mul(alpha, v_flip), L::mul(beta, v_grid));
    }
    if constexpr (kTransfer == Transfer::apic) {
      L::store(C + p0, L::template interpolate<W>(in.g, p0, vs, r));
    }
    if constexpr (kTransfer == Transfer::xpic) {
      v_new = L::add(v_grid, L::template interpolate<W>(in.w, p0, L::slots(in.w_i, r), r));
    }
    L::store(v + p0, v_new);
    const V dx = L::mul(dtv, in.grid_position ? v_grid : v_new);
    L::store(x + p0, L::add(L::load(x + p0), dx));
  }
  for (; p0 < n; ++p0)
    transfer_particle<W, kTransfer>(p0, in, x, v, C, dt);
  L::end();
}

MPMSTAB_LANES_END

// The pass's entry point for each instruction set (base/lanes.hpp).
#if MPMSTAB_AVX512
template <int W, Transfer kTransfer, class... Args>
MPMSTAB_AVX512_TARGET MPMSTAB_LANES_ENTRY void transfer_avx512(Args&&... args) {
  transfer_lanes<GridLanes8, W, kTransfer>(std::forward<Args>(args)...);
}
#endif

#if MPMSTAB_AVX2
template <int W, Transfer kTransfer, class... Args>
MPMSTAB_AVX2_TARGET MPMSTAB_LANES_ENTRY void transfer_avx2(Args&&... args) {
  transfer_lanes<GridLanes4, W, kTransfer>(std::forward<Args>(args)...);
}
#endif

#if MPMSTAB_SSE2
template <int W, Transfer kTransfer, class... Args>
MPMSTAB_LANES_ENTRY void transfer_sse2(Args&&... args) {
  transfer_lanes<GridLanes2, W, kTransfer>(std::forward<Args>(args)...);
}
#endif

template <int W, Transfer kTransfer>
void g2p_transfer(const Stencil<W>& S, const Grid& G, double dt, const ParticleUpdate& rule,
                  Particles& P) {
  const TransferInputs<W, kTransfer> in{
      S.base.data(),      rows<W>(S.w),
      rows<W>(S.g),       G.accel.data(),
      G.velocity.data(),  kTransfer == Transfer::xpic ? G.correction.data() : nullptr,
      rule.flip_fraction, rule.position == PositionUpdate::grid};
  const auto n = static_cast<std::size_t>(P.size());
  double* C = kTransfer == Transfer::apic ? P.C.data() : nullptr;
  [[maybe_unused]] const auto slots = static_cast<int>(G.velocity.size());
#if MPMSTAB_AVX512
  if (use_avx512())
    return transfer_avx512<W, kTransfer>(n, in, slots, P.x.data(), P.v.data(), C, dt);
#endif
#if MPMSTAB_AVX2
  if (use_avx2()) return transfer_avx2<W, kTransfer>(n, in, slots, P.x.data(), P.v.data(), C, dt);
#endif
#if MPMSTAB_SSE2
  transfer_sse2<W, kTransfer>(n, in, slots, P.x.data(), P.v.data(), C, dt);
#else
  for (std::size_t p = 0; p < n; ++p)
    transfer_particle<W, kTransfer>(p, in, P.x.data(), P.v.data(), C, dt);
#endif
}

}  // namespace

namespace detail {

template <int W>
void g2p_other_transfer(const Stencil<W>& S, const Grid& G, double dt, const ParticleUpdate& rule,
                        Particles& P) {
  switch (rule.transfer) {
    case Transfer::flip:  // phases.cpp
      return;
    case Transfer::pic:
      return g2p_transfer<W, Transfer::pic>(S, G, dt, rule, P);
    case Transfer::blend:
      return g2p_transfer<W, Transfer::blend>(S, G, dt, rule, P);
    case Transfer::apic:
      return g2p_transfer<W, Transfer::apic>(S, G, dt, rule, P);
    case Transfer::xpic:
      return g2p_transfer<W, Transfer::xpic>(S, G, dt, rule, P);
    case Transfer::fmpm:  // PIC with the velocity fmpm_velocity left in G
      return g2p_transfer<W, Transfer::pic>(S, G, dt, rule, P);
  }
}

}  // namespace detail

#define MPMSTAB_INSTANTIATE(W)                                                         \
  template void p2g_force(const Stencil<W>&, const Particles&, const double*, Grid&);  \
  template void p2g_momentum(const Stencil<W>&, const Particles&, Grid&);              \
  template void p2g_affine(const Stencil<W>&, const double*, const Particles&, Grid&); \
  template void detail::g2p_other_transfer(const Stencil<W>&, const Grid&, double,     \
                                           const ParticleUpdate&, Particles&);
MPMSTAB_INSTANTIATE(LinearBasis::width)
MPMSTAB_INSTANTIATE(GimpBasis::width)
MPMSTAB_INSTANTIATE(CpGimpBasis::width)
#undef MPMSTAB_INSTANTIATE

}  // namespace mpmstab
