// Grid crossings (Table 2): each time a particle's cell index changes, add the number of cell
// boundaries it passed, |cell_new - cell_old|, with cell = floor(x / h) of the unwrapped position.
#pragma once

#include <cstdint>
#include <vector>

#include "particles.hpp"

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

}  // namespace mpmstab
