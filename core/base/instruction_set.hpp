// Which instruction-set version of the kernels (base/simd.hpp) this build runs on this CPU. The
// results are the same bytes under every version (tests/test_kernel_versions.cpp); the speed is
// not, so the harness records the version beside every timing.
#pragma once

namespace mpmstab {

// "AVX-512" (x86-64-v4), "AVX2" (x86-64-v3) or "baseline" (the build's own target, x86-64-v2
// unless MPMSTAB_ARCH says otherwise): the version the kernels' dispatch picks.
const char* kernel_instruction_set();

}  // namespace mpmstab
