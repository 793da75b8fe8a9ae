#include "step/xpic.hpp"

#include "step/grid_nodes.hpp"
#include "step/shape.hpp"

namespace mpmstab {

namespace {

// out = Q y: y taken to the particles (sum_j S_jp y_j), back to the nodes mass-weighted and
// divided by m_i on free nodes with mass; zero on fixed slots, images copied.
template <int W>
void apply_Q(const Stencil<W>& S, const Particles& P, const Grid& G, const Eigen::ArrayXd& y,
             Eigen::ArrayXd& out, Eigen::ArrayXd& at_particles) {
  const auto n = static_cast<std::size_t>(P.size());
  for (std::size_t p = 0; p < n; ++p) {
    const int b = S.base[p];
    double s = 0.0;
    for (int k = 0; k < W; ++k)
      s += S.w[k][p] * y[b + k];
    at_particles[static_cast<Eigen::Index>(p)] = s;
  }
  out.setZero();
  for (std::size_t p = 0; p < n; ++p) {
    const double mu =
        P.mass[static_cast<Eigen::Index>(p)] * at_particles[static_cast<Eigen::Index>(p)];
    const int b = S.base[p];
    for (int k = 0; k < W; ++k)
      out[b + k] += S.w[k][p] * mu;
  }
  double* o = out.data();
  if (G.bc == Boundary::periodic) detail::fold_images(G, {o});
  detail::divide_by_mass(G, o, o);
}

void size_work(const Grid& G, const Particles& P, SeriesWork& work) {
  if (work.term.size() != G.slots()) {
    work.term.resize(G.slots());
    work.projected.resize(G.slots());
  }
  if (work.at_particles.size() != P.size()) work.at_particles.resize(P.size());
}

}  // namespace

template <int W>
void series_correction(const Stencil<W>& S, const Particles& P, const Grid& G, int order,
                       const Eigen::ArrayXd& v, Eigen::ArrayXd& w, SeriesWork& work) {
  size_work(G, P, work);
  w.setZero(G.slots());
  work.term = v;  // r = 0
  for (int r = 1; r < order; ++r) {
    apply_Q(S, P, G, work.term, work.projected, work.at_particles);
    work.term -= work.projected;  // (I - Q)^r v; fixed slots stay zero
    w += work.term;
  }
}

template <int W>
void xpic_correction(const Stencil<W>& S, const Particles& P, int m, Grid& G, SeriesWork& work) {
  // v^n = q_i / m_i with the boundary conditions, from the folded sums of grid_update.
  work.start.resize(G.slots());
  detail::divide_by_mass(G, G.momentum.data(), work.start.data());
  series_correction(S, P, G, m, work.start, G.correction, work);
}

template <int W>
void fmpm_velocity(const Stencil<W>& S, const Particles& P, int k, Grid& G, SeriesWork& work) {
  if (k <= 1) return;
  series_correction(S, P, G, k, G.velocity, work.start, work);
  G.velocity += work.start;  // zero on fixed slots; images were copied in every term
}

#define MPMSTAB_INSTANTIATE(W)                                                                 \
  template void series_correction(const Stencil<W>&, const Particles&, const Grid&, int,       \
                                  const Eigen::ArrayXd&, Eigen::ArrayXd&, SeriesWork&);        \
  template void xpic_correction(const Stencil<W>&, const Particles&, int, Grid&, SeriesWork&); \
  template void fmpm_velocity(const Stencil<W>&, const Particles&, int, Grid&, SeriesWork&);
MPMSTAB_INSTANTIATE(2)
MPMSTAB_INSTANTIATE(3)
MPMSTAB_INSTANTIATE(4)
#undef MPMSTAB_INSTANTIATE

}  // namespace mpmstab
