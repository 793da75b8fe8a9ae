#include "step/simulation.hpp"

#include <algorithm>
#include <type_traits>

#include "step/small_mass.hpp"

namespace mpmstab {

namespace {

std::variant<LinearBasis, GimpBasis, CpGimpBasis, BSpline2Basis, BSpline3Basis, CpdiBasis>
make_basis(const RunParams& p) {
  const double h = 1.0 / p.cells;
  const double lp = h / (2.0 * p.ppc);  // half-width lp = h / (2 m) of an undeformed particle
  const SplineWalls walls = p.bc == Boundary::periodic   ? SplineWalls::none
                            : p.walls == Walls::modified ? SplineWalls::modified
                                                         : SplineWalls::eliminate;
  switch (p.method) {
    case Method::mpm:
      return LinearBasis(h);
    case Method::gimp:
      return GimpBasis(h, lp);
    case Method::cpgimp:
      return CpGimpBasis(h, lp);  // lp_p = F_p lp
    case Method::bspline2:
      return BSpline2Basis(h, p.cells, walls);
    case Method::bspline3:
      return BSpline3Basis(h, p.cells, walls);
    case Method::cpdi:
      return CpdiBasis(h, lp);  // corners at x -/+ F_p lp
  }
  return GimpBasis(h, lp);
}

}  // namespace

int stencil_width(Method m) {
  switch (m) {
    case Method::mpm:
      return LinearBasis::width;
    case Method::gimp:
      return GimpBasis::width;
    case Method::cpgimp:
      return CpGimpBasis::width;
    case Method::bspline2:
      return BSpline2Basis::width;
    case Method::bspline3:
      return BSpline3Basis::width;
    case Method::cpdi:
      return CpdiBasis::width;
  }
  return GimpBasis::width;
}

Simulation::Simulation(const RunParams& p)
    : params_(p),
      scene_(make_scene(p)),
      law_(scene_->law()),
      g2p_rule_{p.transfer, p.flip_fraction, p.position_update},
      P_(scene_->initial_particles(p.cells, p.ppc, p.layout)),
      G_(p.cells, p.bc, p.walls, stencil_width(p.method)),
      basis_(make_basis(p)),
      exact_(*scene_, P_.X) {
  const auto n = static_cast<std::size_t>(P_.size());
  const int width = stencil_width(p.method);
  stencil2_.resize(width == 2 ? n : 0);
  stencil3_.resize(width == 3 ? n : 0);
  stencil4_.resize(width == 4 ? n : 0);
  // A scene without a body force leaves body_force_ null: its b stays the zeros set below.
  if (scene_->has_body_force()) body_force_ = scene_->body_force_at(P_.X);
  G_.extend_to_empty = !scene_info(p.scene).fills_grid;
  if (p.small_mass != SmallMass::none) {
    G_.small_mass = p.small_mass;
    G_.mass_cutoff = p.small_mass_fraction * scene_->rho0 * G_.h;
  }
  body_accel_.setZero(P_.size());
  if (p.transfer == Transfer::apic) P_.C.setZero(P_.size());  // starts from v_p alone
  if (p.start == VelocityStart::half_step) {
    // The leapfrog's staggered start: v_p = v(X_p, -dt / 2), dt the first step (validate()
    // admits the fixed and cfl policies only, whose step is known before it is taken).
    const double dt0 = std::min(*fixed_step(p), p.T);
    for (Eigen::Index q = 0; q < P_.size(); ++q)
      P_.v[q] = scene_->velocity(P_.X[q], -dt0 / 2);
  }
  if (p.transfer == Transfer::xpic) G_.correction.setZero(G_.slots());
}

template <int W>
void Simulation::series_phase(const Stencil<W>& S) {
  if (params_.transfer == Transfer::xpic) xpic_correction(S, P_, params_.xpic_order, G_, series_);
  if (params_.transfer == Transfer::fmpm) fmpm_velocity(S, P_, params_.fmpm_order, G_, series_);
}

template <int W>
void Simulation::small_mass_phase(const Stencil<W>& S, double dt) {
  if (G_.small_mass == SmallMass::momentum) small_mass_momentum(S, P_, dt, G_);
}

template <int W>
void Simulation::full_mass_velocity(const Stencil<W>& S) {
  if (params_.transfer == Transfer::fmpm) fmpm_velocity(S, P_, params_.fmpm_order, G_, series_);
}

template <class Basis>
bool Simulation::step(const Basis& basis, Stencil<Basis::width>& S, double dt, double t_body,
                      const StateCheck* check) {
  if (body_force_) body_force_->evaluate(t_body, body_accel_);  // b(X_p, t^n) or b(X_p, t^{n+1})
  const double* b = body_accel_.data();
  const bool apic = params_.transfer == Transfer::apic;
  switch (params_.update) {
    case UpdateOrder::usl:
      p2g(basis, P_, b, S, G_);                      // eqs. (5)-(7)
      if (apic) p2g_affine(S, P_.x.data(), P_, G_);  // APIC: q_i += sum_p S_ip m_p C_p (X_i - x_p)
      grid_update(G_, dt);                           // eqs. (7), (8)
      small_mass_phase(S, dt);                       // small-mass nodes: the momentum treatment
      series_phase(S);                               // XPIC, FMPM: the full-mass correction w_i
      if (g2p_and_stress(S, G_, dt, g2p_rule_, law_, P_, check)) return check != nullptr;
      g2p(S, G_, dt, g2p_rule_, P_);                     // eqs. (9), (10)
      return stress_update(S, G_, dt, law_, P_, check);  // eqs. (11), (13), (14) with v_i^{n+1}
    case UpdateOrder::usf:
      p2g(basis, P_, nullptr, S, G_);  // m_i, q_i; f_i with the new stress below
      if (apic) p2g_affine(S, P_.x.data(), P_, G_);
      grid_velocity(G_);                   // v_i^n = q_i / m_i
      full_mass_velocity(S);               // FMPM: v_i^n from the full mass matrix series
      stress_update(S, G_, dt, law_, P_);  // with v_i^n
      p2g_force(S, P_, b, G_);             // f_i with the new sigma_p and V_p = F_p V_p^0
      grid_update(G_, dt);
      small_mass_phase(S, dt);
      series_phase(S);
      return g2p(S, G_, dt, g2p_rule_, P_, check);
    case UpdateOrder::musl:
      p2g(basis, P_, b, S, G_);
      if (apic) p2g_affine(S, P_.x.data(), P_, G_);
      grid_update(G_, dt);
      small_mass_phase(S, dt);
      series_phase(S);
      if (apic) x_stencil_ = P_.x;  // the re-map's S_ip are at x^n, which g2p moves
      g2p(S, G_, dt, g2p_rule_, P_);
      p2g_momentum(S, P_, G_);                             // q_i = sum_p S_ip m_p v_p^{n+1}
      if (apic) p2g_affine(S, x_stencil_.data(), P_, G_);  // C_p from this g2p, about x_p^n
      grid_velocity(G_);                                   // v_i = q_i / m_i
      full_mass_velocity(S);
      return stress_update(S, G_, dt, law_, P_, check);  // with the re-mapped v_i
  }
  return false;
}

template <int W>
Stencil<W>& Simulation::stencil() {
  if constexpr (W == 2) {
    return stencil2_;
  } else if constexpr (W == 3) {
    return stencil3_;
  } else {
    return stencil4_;
  }
}

void Simulation::advance_to(double t_next, StateExtremes* extremes, bool with_error) {
  const double dt = t_next - t_;
  const double t_body = params_.body_force_time == BodyForceTime::start ? t_ : t_next;
  ErrorTerms terms;
  if (extremes && with_error) terms = error_terms_at(t_next);
  const StateCheck check{extremes && with_error ? &terms : nullptr, extremes};
  const bool checked = std::visit(
      [&](const auto& basis) {
        constexpr int W = std::decay_t<decltype(basis)>::width;
        return step(basis, stencil<W>(), dt, t_body, extremes ? &check : nullptr);
      },
      basis_);
  t_ = t_next;
  ++n_;
  if (extremes && !checked) *extremes = state_extremes(P_, check.error);
}

ErrorTerms Simulation::error_terms_at(double t) const {
  const ExactDisplacement::Terms exact = exact_.at(P_.X, t);
  return {P_.X.data(), exact.u, exact.factor};
}

double Simulation::max_error() const {
  return mpmstab::max_error(P_, error_terms_at(t_));
}

}  // namespace mpmstab
