#include "observers/crossings.hpp"

#include <algorithm>
#include <cmath>

#include "base/simd.hpp"
#include "scenes/scene_registry.hpp"
#include "step/shape.hpp"

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

ExactCrossings exact_crossings(const RunParams& p, std::int64_t samples) {
  const auto scene = make_scene(p);
  const Particles P = scene->initial_particles(p.cells, p.ppc, p.layout);
  const double h = 1.0 / p.cells;
  const ExactDisplacement exact(*scene, P.X);
  const Eigen::Index n = P.X.size();
  std::vector<double> cell(static_cast<std::size_t>(n));
  std::vector<char> moved(static_cast<std::size_t>(n), 0);
  // The boundaries, by floor(x / h) + 1 of the cell to their right, offset so that a particle a
  // few cells outside the bar still indexes the vector: the step each was last counted at.
  const int offset = p.cells + 2;
  std::vector<std::int64_t> counted_at(static_cast<std::size_t>(3 * p.cells + 6), -1);
  auto cell_at = [&](Eigen::Index i, const ExactDisplacement::Terms& u) {
    return std::floor((P.X[i] + u.u[i] * u.factor) / h);
  };
  const ExactDisplacement::Terms u0 = exact.at(P.X, 0);
  for (Eigen::Index i = 0; i < n; ++i)
    cell[std::size_t(i)] = cell_at(i, u0);
  ExactCrossings out;
  for (std::int64_t k = 1; k <= samples; ++k) {
    const ExactDisplacement::Terms u = exact.at(P.X, p.T * double(k) / double(samples));
    for (Eigen::Index i = 0; i < n; ++i) {
      const double c = cell_at(i, u), old = cell[std::size_t(i)];
      if (c == old) continue;
      const auto passed = static_cast<std::int64_t>(std::abs(c - old));
      out.every += passed;
      if (c > old) out.rightward += passed;
      ++out.changes;
      moved[std::size_t(i)] = 1;
      // The boundaries between the two cells: those right of min(c, old) up to max(c, old).
      for (double b = std::min(c, old) + 1; b <= std::max(c, old); ++b) {
        const auto at = static_cast<std::size_t>(
            std::clamp<double>(b + offset, 0, double(counted_at.size() - 1)));
        if (counted_at[at] != k) {
          counted_at[at] = k;
          ++out.per_boundary;
        }
      }
      cell[std::size_t(i)] = c;
    }
  }
  for (char m : moved)
    out.particles_moved += m;
  return out;
}

}  // namespace mpmstab
