#include "simulation.hpp"

#include "phases.hpp"

namespace mpmstab {

namespace {

std::variant<LinearBasis, GimpBasis> make_basis(const RunParams& p) {
  const double h = 1.0 / p.cells;
  if (p.method == Method::mpm) return LinearBasis(h);
  return GimpBasis(h, h / (2.0 * p.ppc));  // fixed half-width lp = h / (2 m)
}

}  // namespace

Simulation::Simulation(const RunParams& p)
    : params_(p),
      scene_(p.E, p.A),
      P_(scene_.initial_particles(p.cells, p.ppc)),
      G_(p.cells, p.bc),
      basis_(make_basis(p)) {
  const auto n = static_cast<std::size_t>(P_.size());
  stencil_mpm_.resize(p.method == Method::mpm ? n : 0);
  stencil_gimp_.resize(p.method == Method::gimp ? n : 0);
  body_profile_ = P_.X.unaryExpr([&](double X) { return scene_.body_force_profile(X); });
  u_profile_ = P_.X.unaryExpr([&](double X) { return scene_.displacement_profile(X); });
  body_accel_.setZero(P_.size());
}

template <class Basis, class StencilT>
void Simulation::step(const Basis& basis, StencilT& stencil, double dt) {
  body_accel_ = body_profile_ * scene_.body_force_factor(t_);  // b(X_p, t^n)
  p2g(basis, P_, body_accel_.data(), stencil, G_);             // eqs. (5)-(7)
  grid_update(G_, dt);                                         // eqs. (7), (8)
  g2p(stencil, G_, dt, params_.position_update, P_);           // eqs. (9), (10)
  stress_update(stencil, G_, dt, params_.E, P_);               // eqs. (11), (13), (14)
}

void Simulation::advance_to(double t_next) {
  const double dt = t_next - t_;
  if (const auto* gimp = std::get_if<GimpBasis>(&basis_)) {
    step(*gimp, stencil_gimp_, dt);
  } else {
    step(std::get<LinearBasis>(basis_), stencil_mpm_, dt);
  }
  t_ = t_next;
  ++n_;
}

double Simulation::max_error() const {
  const double factor = scene_.displacement_factor(t_);
  return ((P_.x - P_.X) - u_profile_ * factor).abs().maxCoeff();
}

}  // namespace mpmstab
