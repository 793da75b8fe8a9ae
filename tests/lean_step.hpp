// The lean loop of `make bench-versions`: the solver's default algorithm on the paper's bar,
// written plainly in one file (lean_step.cpp), compiled for one instruction set per binary.
#pragma once

#include <cstdint>
#include <vector>

#include "base/params.hpp"

namespace mpmstab::lean {

struct Timing {
  double seconds = 0;               // wall time of the steps alone
  std::int64_t particle_steps = 0;  // steps x particles
  double checksum = 0;              // sum of the final positions, so that no step is skipped
};

// The particles at t = 0, and the body force's profile b(X_p) / sin(c pi t) (the bar's).
struct State {
  std::vector<double> x, v, F, sigma, mass, volume0, body;
};

// The bar's particles for p (E, A, cells, ppc) at t = 0 (lean_state.cpp).
State bar_state(const RunParams& p);

// The bases the lean loop has: mpm, gimp, bspline2, bspline3.
bool supports(Method m);

// Runs p (method, E, dt, T, cells, ppc; USL, FLIP, Dirichlet walls) from `initial` for T / dt
// steps; the state at T goes to *final_state when given.
Timing run(const RunParams& p, State initial, State* final_state = nullptr);

}  // namespace mpmstab::lean
