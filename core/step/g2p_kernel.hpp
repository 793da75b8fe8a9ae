// The gather side of the kernels: sum_i S_ip field_i over a particle's stencil, one particle at
// a time and (AVX-512) eight at a time, shared by phases.cpp (FLIP's g2p, the stress update)
// and transfers.cpp (the other velocity transfers). The other transfers live in a translation
// unit of their own for the reason p2g_kernel.hpp gives: added to phases.cpp, they made GCC's
// multiversioned FLIP step about 1.4x slower (BM_Step, GIMP), with the same code. Internal to
// core/: included by those two files only.
#pragma once

#include <array>
#include <cstddef>

#include "base/simd.hpp"
#include "step/phases.hpp"

namespace mpmstab {

namespace {

template <int W>
using Rows = std::array<const double*, W>;  // S_ip (or G_ip) of slot k and particle p: [k][p]

// sum_k S_ip field_i over the stencil of particle p, summed from 0 in slot order: the arithmetic
// of one particle. The AVX-512 versions do the same operations in the same order in each lane.
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

#if MPMSTAB_AVX512
// AVX-512, 8 particles at a time. Their stencils nearly always lie within the 16 grid slots
// from the first particle's base b0, so a grid array is read with two vector loads and the value
// at base_p + k of each particle is picked by one permutation, instead of a gather. A block that
// does not fit (particles far apart or out of order) takes the scalar path.
struct Slots16 {
  __m512d lo, hi;  // field[b0 .. b0 + 15]; slots past the end of the array read as 0
};

MPMSTAB_AVX512_TARGET inline Slots16 load16(const double* field, int b0, int slots) {
  // Slots that exist from b0 on, at most the 16 read (>= W, as the stencil fits).
  const unsigned avail = slots - b0 < 16 ? static_cast<unsigned>(slots - b0) : 16u;
  const auto lo = static_cast<__mmask8>(_bzhi_u32(0xFF, avail));
  const auto hi = static_cast<__mmask8>(_bzhi_u32(0xFF, avail > 8 ? avail - 8 : 0));
  return {_mm512_maskz_loadu_pd(lo, field + b0), _mm512_maskz_loadu_pd(hi, field + b0 + 8)};
}

// base_p - b0 of particles p0 .. p0 + 7 as 64-bit lanes; false if a stencil leaves the slots.
template <int W>
MPMSTAB_AVX512_TARGET inline bool relative_bases(const int* base, std::size_t p0, __m512i& r) {
  const __m256i rel = _mm256_sub_epi32(
      _mm256_loadu_si256(reinterpret_cast<const __m256i*>(base + p0)), _mm256_set1_epi32(base[p0]));
  if (_mm256_cmple_epu32_mask(rel, _mm256_set1_epi32(16 - W)) != 0xFF) return false;
  r = _mm512_maskz_cvtepu32_epi64(0xFF, rel);
  return true;
}

// interpolate() for particles p0 .. p0 + 7.
template <int W>
MPMSTAB_AVX512_TARGET inline __m512d interpolate8(const Rows<W>& wk, std::size_t p0,
                                                  const Slots16& f, __m512i r) {
  __m512d s = _mm512_setzero_pd();
  for (int k = 0; k < W; ++k) {
    const __m512d fk =
        _mm512_permutex2var_pd(f.lo, _mm512_add_epi64(r, _mm512_set1_epi64(k)), f.hi);
    s = _mm512_add_pd(s, _mm512_mul_pd(_mm512_loadu_pd(wk[k] + p0), fk));
  }
  return s;
}

bool use_avx512() {
  static const bool yes = __builtin_cpu_supports("x86-64-v4");
  return yes;
}
#endif

#if MPMSTAB_AVX2
// AVX2, 4 particles at a time, for a CPU without AVX-512: as above with 8 grid slots from the
// first particle's base b0, read with two vector loads. AVX2 has no two-register permutation of
// doubles: the value at slot r + k of each lane is picked from each half by a permutation of its
// 32-bit pairs, and the half is chosen by a blend. A block whose stencils leave the 8 slots takes
// the scalar path.
struct Slots8 {
  __m256d lo, hi;  // field[b0 .. b0 + 7]; slots past the end of the array read as 0
};

MPMSTAB_AVX2_TARGET inline Slots8 load8(const double* field, int b0, int slots) {
  const int avail = slots - b0 < 8 ? slots - b0 : 8;  // >= W, as the stencil fits
  const __m256i lane = _mm256_setr_epi64x(0, 1, 2, 3);
  const __m256i lo = _mm256_cmpgt_epi64(_mm256_set1_epi64x(avail), lane);
  const __m256i hi = _mm256_cmpgt_epi64(_mm256_set1_epi64x(avail - 4), lane);
  return {_mm256_maskload_pd(field + b0, lo), _mm256_maskload_pd(field + b0 + 4, hi)};
}

// Where slot r + k of each lane is: the 32-bit pair to take from a half, and which half.
struct Pick {
  __m256i pair;  // (2j, 2j + 1), j = (r + k) mod 4
  __m256d high;  // all ones where r + k >= 4
};

// base_p - b0 of particles p0 .. p0 + 3 and the picks of the W slots of their stencils; false
// if a stencil leaves the 8 slots.
template <int W>
MPMSTAB_AVX2_TARGET inline bool relative_bases4(const int* base, std::size_t p0, Pick* picks) {
  const __m128i rel = _mm_sub_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(base + p0)),
                                    _mm_set1_epi32(base[p0]));
  const __m128i limit = _mm_set1_epi32(8 - W);  // unsigned: a negative offset leaves too
  if (_mm_movemask_epi8(_mm_cmpeq_epi32(_mm_max_epu32(rel, limit), limit)) != 0xFFFF) return false;
  const __m256i r = _mm256_cvtepu32_epi64(rel);
  for (int k = 0; k < W; ++k) {
    const __m256i slot = _mm256_add_epi64(r, _mm256_set1_epi64x(k));
    const __m256i j2 = _mm256_slli_epi64(_mm256_and_si256(slot, _mm256_set1_epi64x(3)), 1);
    picks[k].pair =
        _mm256_or_si256(j2, _mm256_slli_epi64(_mm256_add_epi64(j2, _mm256_set1_epi64x(1)), 32));
    picks[k].high = _mm256_castsi256_pd(_mm256_cmpgt_epi64(slot, _mm256_set1_epi64x(3)));
  }
  return true;
}

MPMSTAB_AVX2_TARGET inline __m256d permute_pairs(__m256d half, __m256i pair) {
  return _mm256_castps_pd(_mm256_permutevar8x32_ps(_mm256_castpd_ps(half), pair));
}

MPMSTAB_AVX2_TARGET inline __m256d pick(const Slots8& f, const Pick& at) {
  return _mm256_blendv_pd(permute_pairs(f.lo, at.pair), permute_pairs(f.hi, at.pair), at.high);
}

// interpolate() for particles p0 .. p0 + 3.
template <int W>
MPMSTAB_AVX2_TARGET inline __m256d interpolate4(const Rows<W>& wk, std::size_t p0, const Slots8& f,
                                                const Pick* picks) {
  __m256d s = _mm256_setzero_pd();
  for (int k = 0; k < W; ++k)
    s = _mm256_add_pd(s, _mm256_mul_pd(_mm256_loadu_pd(wk[k] + p0), pick(f, picks[k])));
  return s;
}

[[maybe_unused]] bool use_avx2() {  // phases.cpp; transfers.cpp does without
  static const bool yes = __builtin_cpu_supports("x86-64-v3");
  return yes;
}
#endif

}  // namespace

namespace detail {

// g2p of every transfer but FLIP (phases.hpp), in transfers.cpp.
template <int W>
void g2p_other_transfer(const Stencil<W>& S, const Grid& G, double dt, const ParticleUpdate& rule,
                        Particles& P);

}  // namespace detail

}  // namespace mpmstab
