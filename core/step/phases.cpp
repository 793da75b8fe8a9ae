// The phases (phases.hpp). Every kernel keeps the arithmetic of the plain loop it replaces
// operation for operation, so that the results are the same bits: vector lanes are independent
// particles or nodes, and each grid node still sums its contributions in particle order.
#include "step/phases.hpp"
#include "base/extremes_kernel.hpp"
#include "step/g2p_kernel.hpp"
#include "step/grid_nodes.hpp"
#include "step/p2g_kernel.hpp"

#include <array>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <type_traits>
#include <utility>

namespace mpmstab {

using detail::copy_to_images;
using detail::fold_images;
using detail::on_free_nodes;

void p2g(const LinearBasis& basis, const Particles& P, const double* body_accel,
         Stencil<LinearBasis::width>& S, Grid& G) {
  p2g_any(basis, P, body_accel, S, G);
}

void p2g(const GimpBasis& basis, const Particles& P, const double* body_accel,
         Stencil<GimpBasis::width>& S, Grid& G) {
  p2g_any(basis, P, body_accel, S, G);
}

void p2g(const CpGimpBasis& basis, const Particles& P, const double* body_accel,
         Stencil<CpGimpBasis::width>& S, Grid& G) {
  p2g_any(basis, P, body_accel, S, G);
}

// ---------------------------------------------------------------------------------------------
// Grid update, eqs. (7), (8).
namespace {

// a_i = f_i / m_i and v_i = q_i / m_i + dt a_i on slots [lo, hi), 0 where m_i = 0 (the
// quotients computed there are discarded). Vectorized across nodes.
MPMSTAB_SIMD_CLONES void nodal_update(const double* __restrict m, const double* __restrict q,
                                      const double* __restrict f, double* __restrict v,
                                      double* __restrict a, int lo, int hi, double dt) {
  for (int s = lo; s < hi; ++s) {
    const double inv_m = 1.0 / m[s];
    const double as = f[s] * inv_m;
    const double vs = q[s] * inv_m + dt * as;
    const bool has_mass = m[s] > 0.0;
    a[s] = has_mass ? as : 0.0;
    v[s] = has_mass ? vs : 0.0;
  }
}

}  // namespace

namespace detail {

MPMSTAB_SIMD_CLONES void divide_where_mass(const double* m, const double* num, double* out, int lo,
                                           int hi) {
  for (int s = lo; s < hi; ++s) {
    const double quotient = num[s] / m[s];
    out[s] = m[s] > 0.0 ? quotient : 0.0;
  }
}

}  // namespace detail

void grid_update(Grid& G, double dt) {
  double* m = G.mass.data();
  double* q = G.momentum.data();
  double* f = G.force.data();
  double* v = G.velocity.data();
  double* a = G.accel.data();
  if (G.bc == Boundary::periodic) fold_images(G, {m, q, f});
  on_free_nodes(G, [&](int lo, int hi) { nodal_update(m, q, f, v, a, lo, hi, dt); });
  if (G.small_mass == SmallMass::cutoff || G.small_mass == SmallMass::drop) {
    detail::on_node_ranges(
        G,
        [&](int lo, int hi) {
          for (int s = lo; s < hi; ++s) {
            if (!G.small(m[s])) continue;
            a[s] = 0.0;  // cutoff: no acceleration; drop: no node
            v[s] = G.small_mass == SmallMass::cutoff ? q[s] / m[s] : 0.0;
          }
        },
        [](int, int) {});
  }
  if (G.extend_to_empty) detail::extend_to_empty_nodes(G, {v, a});
  if (G.bc == Boundary::periodic) copy_to_images(G, {v, a});
}

void grid_velocity(Grid& G) {
  if (G.bc == Boundary::periodic) fold_images(G, {G.mass.data(), G.momentum.data()});
  detail::divide_by_mass(G, G.momentum.data(), G.velocity.data());
  if (G.extend_to_empty) {
    detail::extend_to_empty_nodes(G, {G.velocity.data()});
    if (G.bc == Boundary::periodic) copy_to_images(G, {G.velocity.data()});
  }
}

// ---------------------------------------------------------------------------------------------
// g2p, eqs. (9), (10), and the stress update, eqs. (11), (13), (14).
namespace {

template <int W, bool kGridPosition>
inline void g2p_particle(std::size_t p, const int* __restrict base, const Rows<W>& w,
                         const double* __restrict a_i, const double* __restrict v_i,
                         double* __restrict x, double* __restrict v, double dt) {
  const int b = base[p];
  v[p] += dt * interpolate<W>(w, p, a_i, b);
  if constexpr (kGridPosition) {
    x[p] += dt * interpolate<W>(w, p, v_i, b);
  } else {
    x[p] += dt * v[p];
  }
}

template <int W>
inline void stress_particle(std::size_t p, const int* __restrict base, const Rows<W>& g,
                            const double* __restrict v_i, double* __restrict F,
                            double* __restrict sig, double dt, double E) {
  const double L = interpolate<W>(g, p, v_i, base[p]);
  F[p] *= 1.0 + dt * L;
  sig[p] = E * (F[p] - 1.0);
}

#if !MPMSTAB_SSE2
// The plain loops, for a build without the hand-written passes (not GCC on x86-64).
template <int W, bool kGridPosition>
void g2p_loop(std::size_t n, const int* __restrict base, const Rows<W> w,
              const double* __restrict a_i, const double* __restrict v_i, double* __restrict x,
              double* __restrict v, double dt) {
  MPMSTAB_IVDEP
  for (std::size_t p = 0; p < n; ++p)
    g2p_particle<W, kGridPosition>(p, base, w, a_i, v_i, x, v, dt);
}

template <int W>
void stress_loop(std::size_t n, const int* __restrict base, const Rows<W> g,
                 const double* __restrict v_i, double* __restrict F, double* __restrict sig,
                 double dt, double E) {
  MPMSTAB_IVDEP
  for (std::size_t p = 0; p < n; ++p)
    stress_particle<W>(p, base, g, v_i, F, sig, dt, E);
}
#endif

MPMSTAB_LANES_BEGIN

// The passes over the particles from the grid, L::n particles at a time (g2p_kernel.hpp's
// GridLanes8 and GridLanes4): FLIP's g2p (kG2p), the stress update with the linear law (kStress),
// or both in one pass (USL), each lane doing the operations of g2p_particle and stress_particle;
// with kCheck, the state's extremes (and with kError the error over time) taken from the values
// as the pass writes them, the others read (extremes_kernel.hpp).
template <class L, int W, bool kG2p, bool kStress, bool kGridPosition, bool kCheck, bool kError>
MPMSTAB_LANES_BODY void particle_pass_lanes(std::size_t n, const int* __restrict base,
                                            const Rows<W> w, const Rows<W> g,
                                            const double* __restrict a_i,
                                            const double* __restrict v_i, int slots, Particles& P,
                                            double dt, double E, const StateCheck* check) {
  using V = typename L::V;
  double* __restrict x = P.x.data();
  double* __restrict v = P.v.data();
  double* __restrict F = P.F.data();
  double* __restrict sig = P.sigma.data();
  const V dtv = L::set1(dt), Ev = L::set1(E), one = L::set1(1.0);
  Extremes<L, kError> e(kError ? check->error : nullptr);
  std::size_t p0 = 0;
  for (; p0 + L::n <= n; p0 += L::n) {
    typename L::Where r;
    if (!L::template where<W>(base, p0, slots, r)) {
      for (std::size_t p = p0; p < p0 + L::n; ++p) {
        if constexpr (kG2p) g2p_particle<W, kGridPosition>(p, base, w, a_i, v_i, x, v, dt);
        if constexpr (kStress) stress_particle<W>(p, base, g, v_i, F, sig, dt, E);
      }
      if constexpr (kCheck) {
        e.add(p0, L::load(x + p0), L::load(v + p0), L::load(F + p0), L::load(sig + p0));
      }
      continue;
    }
    typename L::Slots vel;
    if constexpr (kStress || kGridPosition) vel = L::slots(v_i, r);
    V xp, vp, Fp, sp;
    if constexpr (kG2p) {  // g2p_particle
      const V a = L::template interpolate<W>(w, p0, L::slots(a_i, r), r);
      vp = L::add(L::load(v + p0), L::mul(dtv, a));
      L::store(v + p0, vp);
      V dx;
      if constexpr (kGridPosition) {
        dx = L::mul(dtv, L::template interpolate<W>(w, p0, vel, r));
      } else {
        dx = L::mul(dtv, vp);
      }
      xp = L::add(L::load(x + p0), dx);
      L::store(x + p0, xp);
    } else if constexpr (kCheck) {
      xp = L::load(x + p0);
      vp = L::load(v + p0);
    }
    if constexpr (kStress) {  // stress_particle
      const V Lv = L::template interpolate<W>(g, p0, vel, r);
      Fp = L::mul(L::load(F + p0), L::add(one, L::mul(dtv, Lv)));
      L::store(F + p0, Fp);
      sp = L::mul(Ev, L::sub(Fp, one));
      L::store(sig + p0, sp);
    } else if constexpr (kCheck) {
      Fp = L::load(F + p0);
      sp = L::load(sig + p0);
    }
    if constexpr (kCheck) e.add(p0, xp, vp, Fp, sp);
  }
  for (; p0 < n; ++p0) {
    if constexpr (kG2p) g2p_particle<W, kGridPosition>(p0, base, w, a_i, v_i, x, v, dt);
    if constexpr (kStress) stress_particle<W>(p0, base, g, v_i, F, sig, dt, E);
    if constexpr (kCheck) e.add_one(p0, x[p0], v[p0], F[p0], sig[p0]);
  }
  if constexpr (kCheck) *check->extremes = e.result();
  L::end();
}

MPMSTAB_LANES_END

// The pass's entry point for each instruction set (base/lanes.hpp).
#if MPMSTAB_AVX512
template <int W, bool... kFlags, class... Args>
MPMSTAB_AVX512_TARGET MPMSTAB_LANES_ENTRY void particle_pass_avx512(Args&&... args) {
  particle_pass_lanes<GridLanes8, W, kFlags...>(std::forward<Args>(args)...);
}
#endif

#if MPMSTAB_AVX2
template <int W, bool... kFlags, class... Args>
MPMSTAB_AVX2_TARGET MPMSTAB_LANES_ENTRY void particle_pass_avx2(Args&&... args) {
  particle_pass_lanes<GridLanes4, W, kFlags...>(std::forward<Args>(args)...);
}
#endif

#if MPMSTAB_SSE2
template <int W, bool... kFlags, class... Args>
MPMSTAB_LANES_ENTRY void particle_pass_sse2(Args&&... args) {
  particle_pass_lanes<GridLanes2, W, kFlags...>(std::forward<Args>(args)...);
}

// One pass of particle_pass_lanes, on the widest lanes of this CPU (AVX-512, AVX2, else SSE2),
// over the run's arrays, the check's flags chosen at run time.
template <int W, bool kG2p, bool kStress, bool kGridPosition>
void particle_pass(const Stencil<W>& S, const Grid& G, double dt, double E, Particles& P,
                   const StateCheck* check) {
  const auto pass = [&]<bool kCheck, bool kError>() {
    const auto n = static_cast<std::size_t>(P.size());
    const auto slots = static_cast<int>(G.velocity.size());
#if MPMSTAB_AVX512
    if (use_avx512()) {
      return particle_pass_avx512<W, kG2p, kStress, kGridPosition, kCheck, kError>(
          n, S.base.data(), rows<W>(S.w), rows<W>(S.g), G.accel.data(), G.velocity.data(), slots, P,
          dt, E, check);
    }
#endif
    // With the 16 vector registers of AVX2 and SSE2, the extremes' accumulators and the pass's
    // values do not fit together: the extremes are taken by their own pass over the values just
    // written (the same lanes, the same values).
    const auto unchecked = [&]() {
#if MPMSTAB_AVX2
      if (use_avx2()) {
        return particle_pass_avx2<W, kG2p, kStress, kGridPosition, false, false>(
            n, S.base.data(), rows<W>(S.w), rows<W>(S.g), G.accel.data(), G.velocity.data(), slots,
            P, dt, E, check);
      }
#endif
      particle_pass_sse2<W, kG2p, kStress, kGridPosition, false, false>(
          n, S.base.data(), rows<W>(S.w), rows<W>(S.g), G.accel.data(), G.velocity.data(), slots, P,
          dt, E, check);
    };
    unchecked();
    if constexpr (kCheck) *check->extremes = state_extremes(P, kError ? check->error : nullptr);
  };
  if (!check) {
    pass.template operator()<false, false>();
  } else if (check->error) {
    pass.template operator()<true, true>();
  } else {
    pass.template operator()<true, false>();
  }
}

template <int W, bool kG2p, bool kStress>
void particle_pass(const Stencil<W>& S, const Grid& G, double dt, double E, PositionUpdate position,
                   Particles& P, const StateCheck* check) {
  if (position == PositionUpdate::grid) {
    particle_pass<W, kG2p, kStress, true>(S, G, dt, E, P, check);
  } else {
    particle_pass<W, kG2p, kStress, false>(S, G, dt, E, P, check);
  }
}
#endif

template <int W, bool kGridPosition>
void g2p_any(const Stencil<W>& S, const Grid& G, double dt, Particles& P) {
#if MPMSTAB_SSE2
  particle_pass<W, true, false, kGridPosition>(S, G, dt, 0.0, P, nullptr);
#else
  g2p_loop<W, kGridPosition>(static_cast<std::size_t>(P.size()), S.base.data(), rows<W>(S.w),
                             G.accel.data(), G.velocity.data(), P.x.data(), P.v.data(), dt);
#endif
}

// Stress update with a material law other than the linear one: stress_particle's steps with the
// law's stress, independent across particles, so vectorized for each instruction set (a gather
// of the W grid velocities per lane).
template <int W>
MPMSTAB_SIMD_CLONES void stress_update_law(const Stencil<W>& S, const Grid& G, double dt,
                                           const MaterialLaw law, Particles& P) {
  const Rows<W> g = rows<W>(S.g);
  const double* __restrict v_i = G.velocity.data();
  const int* __restrict base = S.base.data();
  double* __restrict F = P.F.data();
  double* __restrict sig = P.sigma.data();
  const auto n = static_cast<std::size_t>(P.size());
  MPMSTAB_IVDEP
  for (std::size_t p = 0; p < n; ++p) {
    const double L = interpolate<W>(g, p, v_i, base[p]);
    F[p] *= 1.0 + dt * L;
    sig[p] = law.stress(F[p]);
  }
}

}  // namespace

template <int W>
void g2p(const Stencil<W>& S, const Grid& G, double dt, const ParticleUpdate& rule, Particles& P) {
  switch (rule.transfer) {
    case Transfer::flip:
      if (rule.position == PositionUpdate::grid) {
        g2p_any<W, true>(S, G, dt, P);
      } else {
        g2p_any<W, false>(S, G, dt, P);
      }
      return;
    case Transfer::pic:
    case Transfer::blend:
    case Transfer::apic:
    case Transfer::xpic:
    case Transfer::fmpm:
      return detail::g2p_other_transfer(S, G, dt, rule, P);  // transfers.cpp
  }
}

template <int W>
void stress_update(const Stencil<W>& S, const Grid& G, double dt, const MaterialLaw& law,
                   Particles& P) {
  if (law.kind != Material::linear) return stress_update_law(S, G, dt, law, P);
#if MPMSTAB_SSE2
  particle_pass<W, false, true, false>(S, G, dt, law.E, P, nullptr);
#else
  stress_loop<W>(static_cast<std::size_t>(P.size()), S.base.data(), rows<W>(S.g), G.velocity.data(),
                 P.F.data(), P.sigma.data(), dt, law.E);
#endif
}

template <int W>
bool g2p(const Stencil<W>& S, const Grid& G, double dt, const ParticleUpdate& rule, Particles& P,
         [[maybe_unused]] const StateCheck* check) {
#if MPMSTAB_SSE2
  if (check && rule.transfer == Transfer::flip) {
    particle_pass<W, true, false>(S, G, dt, 0.0, rule.position, P, check);
    return true;
  }
#endif
  g2p(S, G, dt, rule, P);
  return false;
}

template <int W>
bool stress_update(const Stencil<W>& S, const Grid& G, double dt, const MaterialLaw& law,
                   Particles& P, [[maybe_unused]] const StateCheck* check) {
#if MPMSTAB_SSE2
  if (check && law.kind == Material::linear) {
    particle_pass<W, false, true, false>(S, G, dt, law.E, P, check);
    return true;
  }
#endif
  stress_update(S, G, dt, law, P);
  return false;
}

template <int W>
bool g2p_and_stress(const Stencil<W>& S, const Grid& G, double dt, const ParticleUpdate& rule,
                    const MaterialLaw& law, Particles& P, const StateCheck* check) {
#if MPMSTAB_SSE2
  if (rule.transfer != Transfer::flip || law.kind != Material::linear) {
    return false;
  }
  particle_pass<W, true, true>(S, G, dt, law.E, rule.position, P, check);
  return true;
#else
  (void)S, (void)G, (void)dt, (void)rule, (void)law, (void)P, (void)check;
  return false;
#endif
}

#define MPMSTAB_INSTANTIATE(W)                                                                  \
  template void g2p(const Stencil<W>&, const Grid&, double, const ParticleUpdate&, Particles&); \
  template void stress_update(const Stencil<W>&, const Grid&, double, const MaterialLaw&,       \
                              Particles&);                                                      \
  template bool g2p_and_stress(const Stencil<W>&, const Grid&, double, const ParticleUpdate&,   \
                               const MaterialLaw&, Particles&, const StateCheck*);              \
  template bool g2p(const Stencil<W>&, const Grid&, double, const ParticleUpdate&, Particles&,  \
                    const StateCheck*);                                                         \
  template bool stress_update(const Stencil<W>&, const Grid&, double, const MaterialLaw&,       \
                              Particles&, const StateCheck*);
MPMSTAB_INSTANTIATE(LinearBasis::width)
MPMSTAB_INSTANTIATE(GimpBasis::width)
MPMSTAB_INSTANTIATE(CpGimpBasis::width)
#undef MPMSTAB_INSTANTIATE

}  // namespace mpmstab
