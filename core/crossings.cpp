#include "crossings.hpp"

#include <cstdlib>

#include "shape.hpp"

namespace mpmstab {

CrossingCounter::CrossingCounter(const Particles& P, double h)
    : inv_h_(1.0 / h), cell_(static_cast<std::size_t>(P.size())) {
  for (Eigen::Index p = 0; p < P.size(); ++p)
    cell_[p] = floor_to_int(P.x[p] * inv_h_);
}

std::int64_t CrossingCounter::update(const Particles& P) {
  std::int64_t passed = 0;
  for (Eigen::Index p = 0; p < P.size(); ++p) {
    const int c = floor_to_int(P.x[p] * inv_h_);
    passed += std::abs(c - cell_[p]);
    cell_[p] = c;
  }
  return passed;
}

}  // namespace mpmstab
