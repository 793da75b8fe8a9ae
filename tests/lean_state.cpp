// The lean loop's initial state: the bar scene's particles at t = 0 and its body force's profile
// (lean_step.hpp). Compiled with the library's flags, unlike lean_step.cpp: Eigen stays here.
#include "lean_step.hpp"
#include "scenes/bar.hpp"

namespace mpmstab::lean {

State bar_state(const RunParams& p) {
  const BarScene bar(p.E, p.A);
  const Particles P = bar.initial_particles(p.cells, p.ppc);
  State s;
  for (Eigen::Index i = 0; i < P.size(); ++i) {
    s.x.push_back(P.x[i]), s.v.push_back(P.v[i]), s.F.push_back(P.F[i]);
    s.sigma.push_back(P.sigma[i]), s.mass.push_back(P.mass[i]);
    s.volume0.push_back(P.volume0[i]), s.body.push_back(bar.body_force_profile(P.X[i]));
  }
  return s;
}

}  // namespace mpmstab::lean
