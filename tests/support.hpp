// Helpers shared by the tests: running the command-line program, and a small quick case.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

#include "params.hpp"

namespace mpmstab::test_support {

struct CliOutcome {
  int status;          // exit status; -1 if the program did not exit normally
  std::string output;  // stdout and stderr together
};

// Runs build/mpmstab with `args` (a shell command line) and collects all it prints.
inline CliOutcome run_mpmstab(const std::string& args) {
  const std::string command = std::string(MPMSTAB_BIN) + " " + args + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return {-1, "popen failed"};
  std::string output;
  std::array<char, 4096> buffer;
  while (const std::size_t n = fread(buffer.data(), 1, buffer.size(), pipe))
    output.append(buffer.data(), n);
  const int raw = pclose(pipe);
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, output};
}

// A GIMP case of the bar that runs in milliseconds: E = 4, A = 0.015, dt = 1e-3, T = 0.2 on
// 20 cells.
inline RunParams quick_case() {
  RunParams p;
  p.method = Method::gimp;
  p.E = 4;
  p.A = 0.015;
  p.dt = 1e-3;
  p.T = 0.2;
  p.cells = 20;
  return p;
}

}  // namespace mpmstab::test_support
