// The time error of the fixed-step scheme on one grid (docs/theory.md, "Time order"): the
// difference between the particle displacements of runs that differ only in their time step.
// On the same grid and layout the spatial error is common to both runs and cancels; what is
// left is the error the time step makes.
//
// Every run steps through the same sample instants t_k = min(k Delta, T), Delta = C_s h / c
// (the coarsest step), each sample interval cut into m equal substeps (a Courant number C_s / m).
// At each t_k the runs are compared with the reference (m_ref substeps, much smaller):
//   d_k = max_p |x_p(t_k) - x_p^ref(t_k)|,
// and a run's time error is max_k d_k (and the root mean square of the same difference over the
// particles and the samples). No instant is chosen: every sample of the run counts.
#pragma once

#include <optional>
#include <vector>

#include "base/params.hpp"

namespace mpmstab {

struct TimeErrorPoint {
  int substeps = 0;     // m: substeps per sample interval
  double courant = 0;   // c dt / h = C_s / m
  bool stable = false;  // every state of the run and of the reference was admissible
  std::optional<double> max_difference;  // max_k max_p |x_p - x_p^ref| (stable runs)
  std::optional<double> rms_difference;  // sqrt(mean_k mean_p (x_p - x_p^ref)^2) (stable runs)
  long long particle_steps = 0;
};

struct TimeErrorStudy {
  double sample_courant = 0;  // C_s
  int reference_substeps = 0;
  bool reference_stable = false;
  long long reference_particle_steps = 0;
  std::vector<TimeErrorPoint> points;  // in the order of `substeps`
};

// `p`: the case (its dt and policy are not used). Requires sample_courant > 0, every substep
// count >= 1 and reference_substeps above each of them.
TimeErrorStudy time_errors(const RunParams& p, double sample_courant,
                           const std::vector<int>& substeps, int reference_substeps);

}  // namespace mpmstab
