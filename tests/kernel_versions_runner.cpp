// kernels_portable / kernels_avx2: the reproducibility test's cases run on the kernels built
// without the instruction-set versions above them (tests/kernel_versions.hpp); prints their
// records, or with the argument instruction-set the version its kernels run. Only the core sources
// that use the switch are compiled per version; the rest of the solver is the library's own objects
// (tests/CMakeLists.txt).
#include <iostream>
#include <string_view>

#include "base/instruction_set.hpp"
#include "kernel_versions.hpp"

int main(int argc, char** argv) {
  if (argc == 2 && std::string_view(argv[1]) == "instruction-set") {
    std::cout << mpmstab::kernel_instruction_set() << "\n";
    return 0;
  }
  std::cout << mpmstab::kernel_versions::all_records();
  return 0;
}
