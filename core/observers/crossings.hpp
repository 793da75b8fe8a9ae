// Grid crossings (Table 2): each time a particle's cell index changes, add the number of cell
// boundaries it passed, |cell_new - cell_old|, with cell = floor(x / h) of the unwrapped position.
#pragma once

#include <cstdint>
#include <vector>

#include "base/params.hpp"
#include "base/particles.hpp"

namespace mpmstab {

class CrossingCounter {
 public:
  CrossingCounter(const Particles& P, double h);
  // Count the boundaries passed since the last call (or construction) and remember the cells.
  std::int64_t update(const Particles& P);

 private:
  double inv_h_;
  std::vector<double> cell_;  // floor(x / h) of each particle, a whole number
};

// The crossings of the exact motion, x_p(t) = X_p + u(X_p, t) with the scene's exact
// displacement, for the particles of the run's initial layout, sampled at t_k = k T / samples
// (k = 0..samples), under the counting rules a reader of Table 2 could have used. No run: the
// count a perfect solver would report under each rule.
struct ExactCrossings {
  std::int64_t every = 0;            // every boundary passed, |cell change| summed (our counter)
  std::int64_t rightward = 0;        // the boundaries passed moving right only
  std::int64_t per_boundary = 0;     // per sample, each boundary counted once however many cross it
  std::int64_t changes = 0;          // per sample, each particle that changed cell counted once
  std::int64_t particles_moved = 0;  // particles that ever left their first cell
};
ExactCrossings exact_crossings(const RunParams& p, std::int64_t samples);

}  // namespace mpmstab
