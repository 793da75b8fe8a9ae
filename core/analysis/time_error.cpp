#include "analysis/time_error.hpp"

#include <algorithm>
#include <cmath>

#include "base/failure.hpp"
#include "step/simulation.hpp"

namespace mpmstab {

namespace {

// The positions at every sample instant of one run with m substeps per sample interval; empty
// when a state was inadmissible.
struct Trajectory {
  std::vector<Eigen::ArrayXd> x;  // x[k]: positions at t_k (k = 1..)
  bool admissible = true;
  long long particle_steps = 0;
};

Trajectory trajectory(const RunParams& p, const std::vector<double>& samples, int m) {
  RunParams q = p;
  q.stepping.policy = TimeStepPolicy::fixed;
  Simulation sim(q);
  const double max_F = max_admissible_F(p.method, p.ppc);
  Trajectory tr;
  tr.x.reserve(samples.size());
  double t = 0;
  for (const double t_next : samples) {
    for (int j = 1; j <= m; ++j) {
      sim.advance_to(j == m ? t_next : t + (t_next - t) * j / m);
      if (detect_failure(sim.particles(), p.bc, max_F)) {
        tr.admissible = false;
        tr.particle_steps = sim.steps() * sim.particles().size();
        return tr;
      }
    }
    tr.x.push_back(sim.particles().x);
    t = t_next;
  }
  tr.particle_steps = sim.steps() * sim.particles().size();
  return tr;
}

}  // namespace

TimeErrorStudy time_errors(const RunParams& p, double sample_courant,
                           const std::vector<int>& substeps, int reference_substeps) {
  const double h = 1.0 / p.cells;
  const double delta = sample_courant * h / wave_speed(p);
  std::vector<double> samples;
  for (long long k = 1;; ++k) {
    const double t = static_cast<double>(k) * delta;
    if (t >= p.T - 1e-9 * delta) {
      samples.push_back(p.T);
      break;
    }
    samples.push_back(t);
  }
  TimeErrorStudy study;
  study.sample_courant = sample_courant;
  study.reference_substeps = reference_substeps;
  const Trajectory ref = trajectory(p, samples, reference_substeps);
  study.reference_stable = ref.admissible;
  study.reference_particle_steps = ref.particle_steps;
  for (const int m : substeps) {
    TimeErrorPoint point;
    point.substeps = m;
    point.courant = sample_courant / m;
    const Trajectory run = trajectory(p, samples, m);
    point.particle_steps = run.particle_steps;
    point.stable = run.admissible && ref.admissible;
    if (point.stable) {
      double max_d = 0, sum_sq = 0, count = 0;
      for (std::size_t k = 0; k < samples.size(); ++k) {
        const Eigen::ArrayXd d = run.x[k] - ref.x[k];
        for (Eigen::Index i = 0; i < d.size(); ++i) {
          max_d = std::max(max_d, std::abs(d[i]));
          sum_sq += d[i] * d[i];
        }
        count += static_cast<double>(d.size());
      }
      point.max_difference = max_d;
      point.rms_difference = std::sqrt(sum_sq / count);
    }
    study.points.push_back(point);
  }
  return study;
}

}  // namespace mpmstab
