#include "base/instruction_set.hpp"

#include "base/simd.hpp"

namespace mpmstab {

// The same tests as the dispatch: the loader's choice among MPMSTAB_SIMD_CLONES' versions, and
// use_avx512 (step/g2p_kernel.hpp) and state_extremes (base/failure.cpp) for the hand-written ones.
const char* kernel_instruction_set() {
#if MPMSTAB_AVX512
  if (__builtin_cpu_supports("x86-64-v4")) return "AVX-512";
#endif
#if MPMSTAB_AVX2
  if (__builtin_cpu_supports("x86-64-v3")) return "AVX2";
#endif
  return "baseline";
}

}  // namespace mpmstab
