// The energy of the particles and the energy balance of a run (docs/theory.md, "Energy").
//
// With rho0 = 1 and unit cross-section, at step n:
//   kinetic  K_n = sum_p 1/2 m_p v_p^2,
//   strain   U_n = sum_p V_p^0 W(F_p)   (W the material's strain energy density, material.hpp),
//   work     W_n = sum_{k <= n} sum_p m_p b_p dt_k (v_p^{k-1} + v_p^k) / 2, the work of each
//            step's body-force impulse m_p b_p dt_k (b at the step's body-force time) on the
//            particle velocity it changes: an impulse J that takes a velocity from v_a to v_b
//            gives the kinetic energy J (v_a + v_b) / 2. With the velocity of a symplectic Euler
//            step read at the half steps, (v^{k-1} + v^k) / 2 is the velocity at the kick's time,
//            so the sum is the midpoint rule of int b v dt,
//   balance  e_n = (K_n + U_n - W_n) - (K_0 + U_0),
// all per the initial energy K_0 + U_0 where a measure is relative. The walls do no work: their
// nodes do not move. Every sum runs over the particles in their order: the same bits on every
// run.
#pragma once

#include <cstdint>
#include <optional>

#include <Eigen/Core>

#include "base/material.hpp"
#include "base/particles.hpp"
#include "scenes/scene.hpp"

namespace mpmstab {

// The balance error |e_n| / (K_0 + U_0) above which a run's energy is said to have left its
// balance: the step at which a run first exceeds it is recorded (energy_warning_step).
inline constexpr double kEnergyWarning = 0.1;

// K_n, U_n and one step's body-force work sum_p m_p b_p dt (v_before_p + v_p) / 2 (0 without a
// body force: b empty), in one pass over the particles: each sum adds its terms in particle
// order, as three loops would, and the three independent chains of additions overlap instead of
// each waiting on its own (a GIMP run with --energy: 8.75 -> 7.96 ns per particle-step on an
// AMD EPYC with the AVX-512 kernels, against three loops).
struct EnergySums {
  double kinetic = 0;
  double strain = 0;
  double work = 0;
};
EnergySums energy_sums(const Particles& P, const MaterialLaw& law, const Eigen::ArrayXd& v_before,
                       const Eigen::ArrayXd& b, double dt);

// The energies of one recorded step.
struct EnergySample {
  double kinetic = 0;
  double strain = 0;
  double work = 0;
  double balance = 0;  // e_n / (K_0 + U_0)
  ExactEnergy exact;   // the scene's exact energies at the step's time
};

// What the energy observer gives a run's record (RunResult).
struct EnergySummary {
  std::optional<double> error_max;           // max_n |e_n| / (K_0 + U_0)
  std::optional<double> exact_error_max;     // max_n |(K + U)_n - (K + U)(t_n)| / (K_0 + U_0)
  std::optional<double> drift;               // least-squares slope of e_n / (K_0 + U_0) per period
  std::optional<std::int64_t> warning_step;  // first n with |e_n| / (K_0 + U_0) > kEnergyWarning
};

// Follows a run's energy step by step: before_step() keeps the velocities the step starts from,
// after_step() takes the energies of the state it left. Nothing is allocated per step.
class EnergyObserver {
 public:
  EnergyObserver(const Particles& P, const MaterialLaw& law, const Scene& scene);

  void before_step(const Particles& P);
  // `b`: the body force per unit mass the step applied at each particle (empty when the scene
  // has none); t: the time the step reached.
  EnergySample after_step(const Particles& P, const Eigen::ArrayXd& b, double t, std::int64_t step);

  // Null where the initial energy is zero (nothing to compare with).
  EnergySummary summary() const;

 private:
  MaterialLaw law_;
  const Scene& scene_;
  double initial_ = 0;  // K_0 + U_0
  double work_ = 0;
  Eigen::ArrayXd v_before_;
  double t_before_ = 0;
  double error_max_ = 0;
  double exact_error_max_ = 0;
  std::optional<std::int64_t> warning_step_;
  // Least squares of e_n / (K_0 + U_0) against t_n (t_0 = 0, e_0 = 0 included).
  double n_ = 1, st_ = 0, stt_ = 0, se_ = 0, ste_ = 0;
};

}  // namespace mpmstab
