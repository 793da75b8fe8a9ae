#include "step/small_mass.hpp"

#include "step/grid_nodes.hpp"

namespace mpmstab {

template <int W>
void small_mass_momentum(const Stencil<W>& S, const Particles& P, double dt, Grid& G) {
  const double* m = G.mass.data();
  const double* a = G.accel.data();
  Eigen::ArrayXd remapped = Eigen::ArrayXd::Zero(G.slots());  // sum_p S_ip m_p v_p*
  for (Eigen::Index p = 0; p < P.size(); ++p) {
    const auto pi = static_cast<std::size_t>(p);
    const int b = S.base[pi];
    double accel = 0;
    for (int k = 0; k < W; ++k)
      accel += S.w[k][pi] * a[b + k];
    const double momentum = P.mass[p] * (P.v[p] + dt * accel);
    for (int k = 0; k < W; ++k)
      remapped[b + k] += S.w[k][pi] * momentum;
  }
  if (G.bc == Boundary::periodic) detail::fold_images(G, {remapped.data()});
  double* v = G.velocity.data();
  double* acc = G.accel.data();
  const double* q = G.momentum.data();
  detail::on_node_ranges(
      G,
      [&](int lo, int hi) {
        for (int s = lo; s < hi; ++s) {
          if (!G.small(m[s])) continue;
          v[s] = remapped[s] / m[s];
          acc[s] = (v[s] - q[s] / m[s]) / dt;
        }
      },
      [](int, int) {});
  if (G.bc == Boundary::periodic) detail::copy_to_images(G, {v, acc});
}

template void small_mass_momentum<2>(const Stencil<2>&, const Particles&, double, Grid&);
template void small_mass_momentum<3>(const Stencil<3>&, const Particles&, double, Grid&);
template void small_mass_momentum<4>(const Stencil<4>&, const Particles&, double, Grid&);

}  // namespace mpmstab
