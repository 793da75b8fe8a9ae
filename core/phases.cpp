// The phases (phases.hpp). Every kernel keeps the arithmetic of the plain loop it replaces
// operation for operation, so that the results are the same bits: vector lanes are independent
// particles or nodes, and each grid node still sums its contributions in particle order.
#include "phases.hpp"
#include "extremes_kernel.hpp"
#include "g2p_kernel.hpp"
#include "grid_nodes.hpp"
#include "p2g_kernel.hpp"

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

void grid_update(Grid& G, double dt) {
  double* m = G.mass.data();
  double* q = G.momentum.data();
  double* f = G.force.data();
  double* v = G.velocity.data();
  double* a = G.accel.data();
  if (G.bc == Boundary::periodic) fold_images(G, {m, q, f});
  on_free_nodes(G, [&](int lo, int hi) { nodal_update(m, q, f, v, a, lo, hi, dt); });
  if (G.bc == Boundary::periodic) copy_to_images(G, {v, a});
}

void grid_velocity(Grid& G) {
  if (G.bc == Boundary::periodic) fold_images(G, {G.mass.data(), G.momentum.data()});
  detail::divide_by_mass(G, G.momentum.data(), G.velocity.data());
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

template <int W, bool kGridPosition>
MPMSTAB_SIMD_CLONES void g2p_loop(std::size_t n, const int* __restrict base, const Rows<W> w,
                                  const double* __restrict a_i, const double* __restrict v_i,
                                  double* __restrict x, double* __restrict v, double dt) {
  MPMSTAB_IVDEP
  for (std::size_t p = 0; p < n; ++p)
    g2p_particle<W, kGridPosition>(p, base, w, a_i, v_i, x, v, dt);
}

template <int W>
MPMSTAB_SIMD_CLONES void stress_loop(std::size_t n, const int* __restrict base, const Rows<W> g,
                                     const double* __restrict v_i, double* __restrict F,
                                     double* __restrict sig, double dt, double E) {
  MPMSTAB_IVDEP
  for (std::size_t p = 0; p < n; ++p)
    stress_particle<W>(p, base, g, v_i, F, sig, dt, E);
}

#if MPMSTAB_AVX512
// FLIP's g2p and the stress update, 8 particles at a time (g2p_kernel.hpp).
template <int W, bool kGridPosition>
MPMSTAB_AVX512_TARGET void g2p_avx512(std::size_t n, const int* __restrict base, const Rows<W> w,
                                      const double* __restrict a_i, const double* __restrict v_i,
                                      int slots, double* __restrict x, double* __restrict v,
                                      double dt) {
  const __m512d dt8 = _mm512_set1_pd(dt);
  std::size_t p0 = 0;
  for (; p0 + 8 <= n; p0 += 8) {
    __m512i r;
    if (!relative_bases<W>(base, p0, r)) {
      for (std::size_t p = p0; p < p0 + 8; ++p)
        g2p_particle<W, kGridPosition>(p, base, w, a_i, v_i, x, v, dt);
      continue;
    }
    const int b0 = base[p0];
    const __m512d a = interpolate8<W>(w, p0, load16(a_i, b0, slots), r);
    const __m512d vp = _mm512_add_pd(_mm512_loadu_pd(v + p0), _mm512_mul_pd(dt8, a));
    _mm512_storeu_pd(v + p0, vp);
    __m512d dx;
    if constexpr (kGridPosition) {
      dx = _mm512_mul_pd(dt8, interpolate8<W>(w, p0, load16(v_i, b0, slots), r));
    } else {
      dx = _mm512_mul_pd(dt8, vp);
    }
    _mm512_storeu_pd(x + p0, _mm512_add_pd(_mm512_loadu_pd(x + p0), dx));
  }
  for (; p0 < n; ++p0)
    g2p_particle<W, kGridPosition>(p0, base, w, a_i, v_i, x, v, dt);
}

template <int W>
MPMSTAB_AVX512_TARGET void stress_avx512(std::size_t n, const int* __restrict base, const Rows<W> g,
                                         const double* __restrict v_i, int slots,
                                         double* __restrict F, double* __restrict sig, double dt,
                                         double E) {
  const __m512d dt8 = _mm512_set1_pd(dt), E8 = _mm512_set1_pd(E), one = _mm512_set1_pd(1.0);
  std::size_t p0 = 0;
  for (; p0 + 8 <= n; p0 += 8) {
    __m512i r;
    if (!relative_bases<W>(base, p0, r)) {
      for (std::size_t p = p0; p < p0 + 8; ++p)
        stress_particle<W>(p, base, g, v_i, F, sig, dt, E);
      continue;
    }
    const __m512d L = interpolate8<W>(g, p0, load16(v_i, base[p0], slots), r);
    const __m512d Fp =
        _mm512_mul_pd(_mm512_loadu_pd(F + p0), _mm512_add_pd(one, _mm512_mul_pd(dt8, L)));
    _mm512_storeu_pd(F + p0, Fp);
    _mm512_storeu_pd(sig + p0, _mm512_mul_pd(E8, _mm512_sub_pd(Fp, one)));
  }
  for (; p0 < n; ++p0)
    stress_particle<W>(p0, base, g, v_i, F, sig, dt, E);
}

// USL with FLIP: g2p_avx512 and stress_avx512 in one pass, and with kCheck the extremes of what
// they write (extremes_kernel.hpp).
template <int W, bool kGridPosition, bool kCheck, bool kError>
MPMSTAB_AVX512_TARGET void g2p_stress_avx512(std::size_t n, const int* __restrict base,
                                             const Rows<W> w, const Rows<W> g,
                                             const double* __restrict a_i,
                                             const double* __restrict v_i, int slots, Particles& P,
                                             double dt, double E, const StateCheck* check) {
  double* __restrict x = P.x.data();
  double* __restrict v = P.v.data();
  double* __restrict F = P.F.data();
  double* __restrict sig = P.sigma.data();
  const __m512d dt8 = _mm512_set1_pd(dt), E8 = _mm512_set1_pd(E), one = _mm512_set1_pd(1.0);
  Extremes8<kError> e(kError ? check->error : nullptr);
  std::size_t p0 = 0;
  for (; p0 + 8 <= n; p0 += 8) {
    __m512i r;
    if (!relative_bases<W>(base, p0, r)) {
      for (std::size_t p = p0; p < p0 + 8; ++p) {
        g2p_particle<W, kGridPosition>(p, base, w, a_i, v_i, x, v, dt);
        stress_particle<W>(p, base, g, v_i, F, sig, dt, E);
      }
      if constexpr (kCheck) {
        e.add(p0, _mm512_loadu_pd(x + p0), _mm512_loadu_pd(v + p0), _mm512_loadu_pd(F + p0),
              _mm512_loadu_pd(sig + p0));
      }
      continue;
    }
    const int b0 = base[p0];
    const Slots16 vel = load16(v_i, b0, slots);
    // g2p (g2p_avx512).
    const __m512d a = interpolate8<W>(w, p0, load16(a_i, b0, slots), r);
    const __m512d vp = _mm512_add_pd(_mm512_loadu_pd(v + p0), _mm512_mul_pd(dt8, a));
    _mm512_storeu_pd(v + p0, vp);
    __m512d dx;
    if constexpr (kGridPosition) {
      dx = _mm512_mul_pd(dt8, interpolate8<W>(w, p0, vel, r));
    } else {
      dx = _mm512_mul_pd(dt8, vp);
    }
    const __m512d xp = _mm512_add_pd(_mm512_loadu_pd(x + p0), dx);
    _mm512_storeu_pd(x + p0, xp);
    // The stress update (stress_avx512).
    const __m512d L = interpolate8<W>(g, p0, vel, r);
    const __m512d Fp =
        _mm512_mul_pd(_mm512_loadu_pd(F + p0), _mm512_add_pd(one, _mm512_mul_pd(dt8, L)));
    _mm512_storeu_pd(F + p0, Fp);
    const __m512d sp = _mm512_mul_pd(E8, _mm512_sub_pd(Fp, one));
    _mm512_storeu_pd(sig + p0, sp);
    if constexpr (kCheck) e.add(p0, xp, vp, Fp, sp);
  }
  for (; p0 < n; ++p0) {
    g2p_particle<W, kGridPosition>(p0, base, w, a_i, v_i, x, v, dt);
    stress_particle<W>(p0, base, g, v_i, F, sig, dt, E);
    if constexpr (kCheck) e.add_one(p0, x[p0], v[p0], F[p0], sig[p0]);
  }
  if constexpr (kCheck) *check->extremes = e.result();
  // Leave no upper vector state dirty for the SSE code that runs next (GCC 12 omits this
  // vzeroupper here; without it the next step's body force took 4x its time on this CPU).
  _mm256_zeroupper();
}
#endif

template <int W, bool kGridPosition>
void g2p_any(const Stencil<W>& S, const Grid& G, double dt, Particles& P) {
  const auto n = static_cast<std::size_t>(P.size());
#if MPMSTAB_AVX512
  if (use_avx512()) {
    return g2p_avx512<W, kGridPosition>(n, S.base.data(), rows<W>(S.w), G.accel.data(),
                                        G.velocity.data(), static_cast<int>(G.velocity.size()),
                                        P.x.data(), P.v.data(), dt);
  }
#endif
  g2p_loop<W, kGridPosition>(n, S.base.data(), rows<W>(S.w), G.accel.data(), G.velocity.data(),
                             P.x.data(), P.v.data(), dt);
}

// Stress update with a material law other than the linear one, one particle after the other.
template <int W>
void stress_update_law(const Stencil<W>& S, const Grid& G, double dt, const MaterialLaw& law,
                       Particles& P) {
  const Rows<W> g = rows<W>(S.g);
  const double* v_i = G.velocity.data();
  for (std::size_t p = 0; p < static_cast<std::size_t>(P.size()); ++p) {
    const double L = interpolate<W>(g, p, v_i, S.base[p]);
    P.F[p] *= 1.0 + dt * L;
    P.sigma[p] = law.stress(P.F[p]);
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
  const auto n = static_cast<std::size_t>(P.size());
  const double E = law.E;
#if MPMSTAB_AVX512
  if (use_avx512()) {
    return stress_avx512<W>(n, S.base.data(), rows<W>(S.g), G.velocity.data(),
                            static_cast<int>(G.velocity.size()), P.F.data(), P.sigma.data(), dt, E);
  }
#endif
  stress_loop<W>(n, S.base.data(), rows<W>(S.g), G.velocity.data(), P.F.data(), P.sigma.data(), dt,
                 E);
}

template <int W>
bool g2p_and_stress(const Stencil<W>& S, const Grid& G, double dt, const ParticleUpdate& rule,
                    const MaterialLaw& law, Particles& P, const StateCheck* check) {
#if MPMSTAB_AVX512
  if (!use_avx512() || rule.transfer != Transfer::flip || law.kind != Material::linear) {
    return false;
  }
  const auto n = static_cast<std::size_t>(P.size());
  const int slots = static_cast<int>(G.velocity.size());
  auto pass = [&]<bool kGridPosition, bool kCheck, bool kError>() {
    g2p_stress_avx512<W, kGridPosition, kCheck, kError>(
        n, S.base.data(), rows<W>(S.w), rows<W>(S.g), G.accel.data(), G.velocity.data(), slots, P,
        dt, law.E, check);
  };
  auto with_check = [&]<bool kGridPosition>() {
    if (!check) {
      pass.template operator()<kGridPosition, false, false>();
    } else if (check->error) {
      pass.template operator()<kGridPosition, true, true>();
    } else {
      pass.template operator()<kGridPosition, true, false>();
    }
  };
  if (rule.position == PositionUpdate::grid) {
    with_check.template operator()<true>();
  } else {
    with_check.template operator()<false>();
  }
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
                               const MaterialLaw&, Particles&, const StateCheck*);
MPMSTAB_INSTANTIATE(LinearBasis::width)
MPMSTAB_INSTANTIATE(GimpBasis::width)
MPMSTAB_INSTANTIATE(CpGimpBasis::width)
#undef MPMSTAB_INSTANTIATE

}  // namespace mpmstab
