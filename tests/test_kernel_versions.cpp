// The reproducibility guarantee across the kernels' instruction-set versions (docs/engineering.md,
// "What is reproducible"): the same cases give the same records, byte for byte, on every
// version of the kernels this machine can run. The suite runs the kernels the build's dispatch
// picks for this CPU (AVX-512 where the CPU has it, else AVX2, else the portable one);
// kernels_portable and kernels_avx2 are the same sources built without the versions above them.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "base/instruction_set.hpp"
#include "kernel_versions.hpp"
#include "support.hpp"

namespace mpmstab {
namespace {

// What `program` prints (no shell; it writes nothing on its standard error).
std::string output_of(const char* program, std::vector<std::string> args = {}) {
  args.insert(args.begin(), program);
  return test_support::run_program(program, args).output;
}

std::string dispatched_version() {
  if (__builtin_cpu_supports("x86-64-v4")) return "AVX-512";
  if (__builtin_cpu_supports("x86-64-v3")) return "AVX2";
  return "baseline";
}

// What the timings record beside every measurement (provenance.hpp's kernels): the version the
// build's dispatch picks on this CPU, and in the builds without the versions above them, theirs.
TEST(KernelVersions, TheRecordedInstructionSetIsTheVersionThatRuns) {
  EXPECT_EQ(kernel_instruction_set(), dispatched_version());
  EXPECT_EQ(output_of(MPMSTAB_KERNELS_PORTABLE_BIN, {"instruction-set"}), "baseline\n");
  const std::string avx2_bin = MPMSTAB_KERNELS_AVX2_BIN;
  if (!avx2_bin.empty()) {
    EXPECT_EQ(output_of(avx2_bin.c_str(), {"instruction-set"}),
              __builtin_cpu_supports("x86-64-v3") ? "AVX2\n" : "baseline\n");
  }
}

TEST(KernelVersions, EveryVersionThisMachineRunsGivesTheSameRecordsBitForBit) {
  const std::string here = kernel_versions::all_records();
  ASSERT_GT(here.size(), 10000u);
  const std::string portable = output_of(MPMSTAB_KERNELS_PORTABLE_BIN);
  EXPECT_TRUE(here == portable) << "the portable kernels differ from the " << dispatched_version()
                                << " ones";
  const std::string avx2_bin = MPMSTAB_KERNELS_AVX2_BIN;
  if (!avx2_bin.empty() && __builtin_cpu_supports("x86-64-v3")) {
    EXPECT_TRUE(here == output_of(avx2_bin.c_str()))
        << "the AVX2 kernels differ from the " << dispatched_version() << " ones";
  }
  std::cout << "compared: " << dispatched_version() << " (the build's dispatch) with portable"
            << (avx2_bin.empty() ? "" : " and AVX2") << "; "
            << (__builtin_cpu_supports("x86-64-v4") ? "" : "this CPU has no AVX-512\n");
}

}  // namespace
}  // namespace mpmstab
