// The gather side of the kernels: sum_i S_ip field_i over a particle's stencil, one particle at
// a time and several at a time (AVX-512: 8, AVX2: 4, SSE2: 2), shared by phases.cpp (FLIP's g2p,
// the stress update) and transfers.cpp (the other velocity transfers). The other transfers live in
// a translation unit of their own for the reason p2g_kernel.hpp gives: added to phases.cpp, they
// made GCC's multiversioned FLIP step about 1.4x slower (BM_Step, GIMP), with the same code.
// Internal to core/: included by those two files only.
#pragma once

#include <array>
#include <cstddef>

#include "base/lanes.hpp"
#include "base/simd.hpp"
#include "step/phases.hpp"

namespace mpmstab {

namespace {

template <int W>
using Rows = std::array<const double*, W>;  // S_ip (or G_ip) of slot k and particle p: [k][p]

// sum_k S_ip field_i over the stencil of particle p, summed from 0 in slot order: the arithmetic
// of one particle. The vector versions do the same operations in the same order in each lane.
template <int W>
inline double interpolate(const Rows<W>& wk, std::size_t p, const double* __restrict field, int b) {
  double s = 0;
  for (int k = 0; k < W; ++k)
    s += wk[k][p] * field[b + k];
  return s;
}

template <int W>
Rows<W> rows(const std::array<AlignedVector<double>, W>& a) {
  Rows<W> r;
  for (int k = 0; k < W; ++k)
    r[k] = a[k].data();
  return r;
}

// The lanes of the hand-written passes (base/lanes.hpp) with what they read from the grid: where
// the stencils of L::n particles lie (Where, from where(); false if the lanes cannot read them,
// and the block then takes the scalar path), a field's values there (Slots, from slots()), and
// interpolate() for the L::n particles from them.

#if MPMSTAB_AVX512
// AVX-512, 8 particles at a time. Their stencils nearly always lie within the 16 grid slots
// from the first particle's base b0, so a grid array is read with two vector loads and the value
// at base_p + k of each particle is picked by one permutation, instead of a gather. A block that
// does not fit (particles far apart or out of order) takes the scalar path.
struct GridLanes8 : Lanes8 {
  struct Where {
    __m512i rel;    // base_p - b0 of each lane, as 64-bit lanes
    int b0, count;  // the first particle's base, and the length of the grid arrays
  };
  struct Slots {
    __m512d lo, hi;  // field[b0 .. b0 + 15]; slots past the end of the array read as 0
  };

  template <int W>
  MPMSTAB_AVX512_TARGET static bool where(const int* base, std::size_t p0, int count, Where& at) {
    const __m256i rel =
        _mm256_sub_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(base + p0)),
                         _mm256_set1_epi32(base[p0]));
    if (_mm256_cmple_epu32_mask(rel, _mm256_set1_epi32(16 - W)) != 0xFF) return false;
    at = {_mm512_maskz_cvtepu32_epi64(0xFF, rel), base[p0], count};
    return true;
  }

  MPMSTAB_AVX512_TARGET static Slots slots(const double* field, const Where& at) {
    // Slots that exist from b0 on, at most the 16 read (>= W, as the stencil fits).
    const unsigned avail = at.count - at.b0 < 16 ? static_cast<unsigned>(at.count - at.b0) : 16u;
    const auto lo = static_cast<__mmask8>(_bzhi_u32(0xFF, avail));
    const auto hi = static_cast<__mmask8>(_bzhi_u32(0xFF, avail > 8 ? avail - 8 : 0));
    return {_mm512_maskz_loadu_pd(lo, field + at.b0), _mm512_maskz_loadu_pd(hi, field + at.b0 + 8)};
  }

  // interpolate() for particles p0 .. p0 + 7.
  template <int W>
  MPMSTAB_AVX512_TARGET static __m512d interpolate(const Rows<W>& wk, std::size_t p0,
                                                   const Slots& f, const Where& at) {
    __m512d s = _mm512_setzero_pd();
    for (int k = 0; k < W; ++k) {
      const __m512d fk =
          _mm512_permutex2var_pd(f.lo, _mm512_add_epi64(at.rel, _mm512_set1_epi64(k)), f.hi);
      s = _mm512_add_pd(s, _mm512_mul_pd(_mm512_loadu_pd(wk[k] + p0), fk));
    }
    return s;
  }
};

bool use_avx512() {
  static const bool yes = __builtin_cpu_supports("x86-64-v4");
  return yes;
}
#endif

#if MPMSTAB_SSE2
// What GridLanes4 and GridLanes2 share: a stencil has at most 4 nodes, so each particle's values
// of a field are read by loads from its own base and transposed into the values of slot k for
// the L::n particles (Slots, from each's slots()), which its interpolate() weighs. A block with a
// stencil whose 4 slots pass the end of the grid arrays takes the scalar path. (interpolate()
// returns a vector: written here, without a target, it would draw GCC's -Wpsabi note where the
// template is instantiated, so each lanes writes its own.)
template <class L>
struct TransposedLanes : L {
  using V = typename L::V;
  struct Where {
    const int* base;  // of the block's first particle
  };
  struct Slots {
    V at[4];  // [k]: field[base_p + k] of each lane
  };

  template <int W>
  MPMSTAB_LANES_BODY static bool where(const int* base, std::size_t p0, int count, Where& at) {
    const auto last = static_cast<unsigned>(count - 4);  // a negative base fails too
    for (int j = 0; j < L::n; ++j)
      if (static_cast<unsigned>(base[p0 + j]) > last) return false;
    at.base = base + p0;
    return true;
  }
};
#endif

#if MPMSTAB_AVX2
// AVX2, 4 particles at a time, for a CPU without AVX-512 (TransposedLanes): each particle's 4
// values of a field are one vector load from its base, and a 4 x 4 transposition makes of them
// the values of slot k for the 4 particles (6 shuffles with 4 loads; AVX2 has no two-register
// permutation of doubles, and its gathers are slow on the CPUs that lack AVX-512).
struct GridLanes4 : TransposedLanes<Lanes4> {
  MPMSTAB_AVX2_TARGET static Slots slots(const double* field, const Where& at) {
    const __m256d r0 = _mm256_loadu_pd(field + at.base[0]);
    const __m256d r1 = _mm256_loadu_pd(field + at.base[1]);
    const __m256d r2 = _mm256_loadu_pd(field + at.base[2]);
    const __m256d r3 = _mm256_loadu_pd(field + at.base[3]);
    const __m256d t0 = _mm256_unpacklo_pd(r0, r1), t1 = _mm256_unpackhi_pd(r0, r1);
    const __m256d t2 = _mm256_unpacklo_pd(r2, r3), t3 = _mm256_unpackhi_pd(r2, r3);
    return {{_mm256_permute2f128_pd(t0, t2, 0x20), _mm256_permute2f128_pd(t1, t3, 0x20),
             _mm256_permute2f128_pd(t0, t2, 0x31), _mm256_permute2f128_pd(t1, t3, 0x31)}};
  }

  // interpolate() for particles p0 .. p0 + 3.
  template <int W>
  MPMSTAB_AVX2_TARGET static __m256d interpolate(const Rows<W>& wk, std::size_t p0, const Slots& f,
                                                 const Where&) {
    static_assert(W <= 4, "a stencil of at most 4 nodes");
    __m256d s = _mm256_setzero_pd();
    for (int k = 0; k < W; ++k)
      s = _mm256_add_pd(s, _mm256_mul_pd(_mm256_loadu_pd(wk[k] + p0), f.at[k]));
    return s;
  }
};

bool use_avx2() {
  static const bool yes = __builtin_cpu_supports("x86-64-v3");
  return yes;
}
#endif

#if MPMSTAB_SSE2
// SSE2, 2 particles at a time, for an x86-64 CPU without AVX2 (TransposedLanes): each particle's
// 4 values of a field read with two loads from its base, and slot k of the 2 particles made by
// one unpack of the loads that hold it.
struct GridLanes2 : TransposedLanes<Lanes2> {
  static Slots slots(const double* field, const Where& at) {
    const double* f0 = field + at.base[0];
    const double* f1 = field + at.base[1];
    const __m128d lo0 = _mm_loadu_pd(f0), hi0 = _mm_loadu_pd(f0 + 2);
    const __m128d lo1 = _mm_loadu_pd(f1), hi1 = _mm_loadu_pd(f1 + 2);
    return {{_mm_unpacklo_pd(lo0, lo1), _mm_unpackhi_pd(lo0, lo1), _mm_unpacklo_pd(hi0, hi1),
             _mm_unpackhi_pd(hi0, hi1)}};
  }

  // interpolate() for particles p0 and p0 + 1.
  template <int W>
  static __m128d interpolate(const Rows<W>& wk, std::size_t p0, const Slots& f, const Where&) {
    static_assert(W <= 4, "a stencil of at most 4 nodes");
    __m128d s = _mm_setzero_pd();
    for (int k = 0; k < W; ++k)
      s = _mm_add_pd(s, _mm_mul_pd(_mm_loadu_pd(wk[k] + p0), f.at[k]));
    return s;
  }
};
#endif

}  // namespace

namespace detail {

// g2p of every transfer but FLIP (phases.hpp), in transfers.cpp.
template <int W>
void g2p_other_transfer(const Stencil<W>& S, const Grid& G, double dt, const ParticleUpdate& rule,
                        Particles& P);

}  // namespace detail

}  // namespace mpmstab
