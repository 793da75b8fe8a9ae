#include "crossings.hpp"

#include <cmath>

#include "shape.hpp"
#include "simd.hpp"

namespace mpmstab {

namespace {

// The boundaries passed by every particle since `cell` was taken, and the new cells, in one
// vectorized pass: cells are whole numbers held as doubles (exact below 2^51), so the count
// |c - c_old| and its sum are exact too (below 2^53).
// Eight partial sums, one per lane, so that the loop vectorizes without reassociating a sum
// (every partial sum is exact, so their total is the same in any order).
MPMSTAB_SIMD_CLONES
double count_and_store(const double* x, double* cell, Eigen::Index n, double inv_h) {
  constexpr int kLanes = 8;
  double lane[kLanes] = {};
  Eigen::Index p = 0;
  for (; p + kLanes <= n; p += kLanes) {
    for (int j = 0; j < kLanes; ++j) {
      const double c = floor_exact(x[p + j] * inv_h);
      lane[j] += std::abs(c - cell[p + j]);
      cell[p + j] = c;
    }
  }
  double passed = 0;
  for (; p < n; ++p) {
    const double c = floor_exact(x[p] * inv_h);
    passed += std::abs(c - cell[p]);
    cell[p] = c;
  }
  for (double l : lane)
    passed += l;
  return passed;
}

}  // namespace

CrossingCounter::CrossingCounter(const Particles& P, double h)
    : inv_h_(1.0 / h), cell_(static_cast<std::size_t>(P.size())) {
  for (Eigen::Index p = 0; p < P.size(); ++p)
    cell_[std::size_t(p)] = floor_exact(P.x[p] * inv_h_);
}

std::int64_t CrossingCounter::update(const Particles& P) {
  return static_cast<std::int64_t>(count_and_store(P.x.data(), cell_.data(), P.size(), inv_h_));
}

}  // namespace mpmstab
