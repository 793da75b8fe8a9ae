// The displacement error in L2 over the body and over time (docs/theory.md, "Measured
// quantities", error_l2_time):
//   e_n^2 = sum_p V_p^0 (u_p^n - u(X_p, t_n))^2 / sum_p V_p^0,
//   error_l2_time = sqrt( sum_n (t_n - t_{n-1}) e_n^2 / t_N ),
// the root mean square of the error over the body and the run, the time integral taken with the
// value at the end of each step. No instant weighs more than its share of the run, so an instant
// where the exact displacement vanishes cannot make it small.
#pragma once

#include <optional>

#include <Eigen/Core>

#include "base/particles.hpp"
#include "scenes/scene.hpp"

namespace mpmstab {

class Scene;

class ErrorL2InTime {
 public:
  ErrorL2InTime(const Particles& P, const Scene& scene);
  // The state after a step that reached time t.
  void after_step(const Particles& P, double t);
  // nullopt before any step has been observed (a run that failed in its first step).
  std::optional<double> value() const;

 private:
  ExactDisplacement exact_;  // u(X_p, t)
  double volume_ = 0;        // sum_p V_p^0
  double t_ = 0;             // the time reached
  double integral_ = 0;      // sum_n dt_n e_n^2
};

}  // namespace mpmstab
