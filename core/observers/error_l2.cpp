#include "observers/error_l2.hpp"

#include <cmath>

#include "scenes/scene_registry.hpp"

namespace mpmstab {

ErrorL2InTime::ErrorL2InTime(const Particles& P, const Scene& scene) : exact_(scene, P.X) {
  for (Eigen::Index p = 0; p < P.size(); ++p)
    volume_ += P.volume0[p];
}

void ErrorL2InTime::after_step(const Particles& P, double t) {
  const ExactDisplacement::Terms exact = exact_.at(P.X, t);
  const double f = exact.factor;
  double sum = 0;
  for (Eigen::Index p = 0; p < P.size(); ++p) {
    const double e = (P.x[p] - P.X[p]) - exact.u[p] * f;
    sum += P.volume0[p] * e * e;
  }
  integral_ += (t - t_) * sum / volume_;
  t_ = t;
}

std::optional<double> ErrorL2InTime::value() const {
  if (t_ <= 0) return std::nullopt;
  return std::sqrt(integral_ / t_);
}

}  // namespace mpmstab
