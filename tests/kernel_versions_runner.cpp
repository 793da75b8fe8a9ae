// kernels_portable / kernels_avx2: the reproducibility test's cases run on the kernels built
// without the instruction-set versions above them (tests/kernel_versions.hpp); prints their
// records.
#include <iostream>

#include "kernel_versions.hpp"

int main() {
  std::cout << mpmstab::kernel_versions::all_records();
  return 0;
}
