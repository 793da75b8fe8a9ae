// One column of `make bench-versions` (tests/bench_versions.sh): ns per particle-step of each
// method given, on the paper's bar (E = 64, A = 0.015, dt = 1e-6, 100 cells x 2 particles, the
// run `mpmstab run --E 64 --A 0.015 --dt 1e-6` makes, shortened to --particle-steps).
//
// Built once per kernel version (tests/CMakeLists.txt): bench_version_default runs the
// library's run() with its kernels as the build dispatches them on this CPU, bench_version_avx2
// and bench_version_portable the same run() with the kernels compiled without the versions above
// them (as kernels_avx2 and kernels_portable are); bench_lean_<isa> runs the lean loop
// (lean_step.cpp) compiled for the instruction set of the version it stands beside.
//
// Usage: bench_<name> --particle-steps N method...  Prints, per method, a line
// "<method> <ns per particle-step> <instruction set>", and nothing else.
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <string>
#include <string_view>

#include "base/params.hpp"
#ifdef MPMSTAB_BENCH_LEAN
#include "lean_step.hpp"
#else
#include "base/instruction_set.hpp"
#include "run/run.hpp"
#endif

namespace {

constexpr double kParticles = 200;  // 100 cells x 2 particles per cell

int usage(const std::string& message) {
  std::cerr << "bench_versions: " << message
            << "\nusage: bench_<name> --particle-steps N method...\n";
  return 2;
}

// Wall ns per particle-step of one run of p.
double ns_per_particle_step(const mpmstab::RunParams& p) {
#ifdef MPMSTAB_BENCH_LEAN
  const mpmstab::lean::Timing t = mpmstab::lean::run(p, mpmstab::lean::bar_state(p));
  if (!(t.checksum > 0)) std::cerr << "bench_versions: unexpected lean state\n";
  return t.seconds * 1e9 / static_cast<double>(t.particle_steps);
#else
  const auto start = std::chrono::steady_clock::now();
  const mpmstab::RunResult r = mpmstab::run(p);
  const std::chrono::duration<double> wall = std::chrono::steady_clock::now() - start;
  if (r.failure) std::cerr << "bench_versions: the run failed\n";
  return wall.count() * 1e9 / static_cast<double>(r.particles * r.steps);
#endif
}

const char* instruction_set() {
#ifdef MPMSTAB_BENCH_LEAN
  return MPMSTAB_BENCH_LEAN;  // the -march it was compiled with
#else
  return mpmstab::kernel_instruction_set();
#endif
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4 || std::string_view(argv[1]) != "--particle-steps") return usage("bad arguments");
  char* end = nullptr;
  const double particle_steps = std::strtod(argv[2], &end);
  if (*end != '\0' || !(particle_steps >= kParticles) || particle_steps > 1e11) {
    return usage("--particle-steps: not a number in [200, 1e11]");
  }
  mpmstab::RunParams p;
  p.E = 64;
  p.A = 0.015;
  p.dt = 1e-6;
  p.T = p.dt * static_cast<double>(static_cast<long long>(particle_steps / kParticles));
  for (int i = 3; i < argc; ++i) {
    const auto method = mpmstab::parse_method(argv[i]);
    if (!method) return usage(std::string("unknown method '") + argv[i] + "'");
#ifdef MPMSTAB_BENCH_LEAN
    if (!mpmstab::lean::supports(*method)) {
      return usage(std::string("the lean loop has no method '") + argv[i] + "'");
    }
#endif
    p.method = *method;
    std::cout << argv[i] << " " << ns_per_particle_step(p) << " " << instruction_set() << "\n";
  }
  return 0;
}
