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

}  // namespace

namespace detail {

// g2p of every transfer but FLIP (phases.hpp), in transfers.cpp.
template <int W>
void g2p_other_transfer(const Stencil<W>& S, const Grid& G, double dt, const ParticleUpdate& rule,
                        Particles& P);

}  // namespace detail

}  // namespace mpmstab
