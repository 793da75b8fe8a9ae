// kernels_portable / kernels_avx2: the reproducibility test's cases run on the kernels built
// without the instruction-set versions above them (tests/kernel_versions.hpp); prints their
// records. Only the core sources that use the switch are compiled per version; the rest of the
// solver is the library's own objects (tests/CMakeLists.txt).
#include <iostream>

#include "kernel_versions.hpp"

int main() {
  std::cout << mpmstab::kernel_versions::all_records();
  return 0;
}
