#include "analysis/stable_dt.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mpmstab {

StableDtInputs stable_dt_inputs(const Particles& P, const Grid& G, VelocityNorm vnorm,
                                Method method) {
  return stable_dt_inputs(P, state_extremes(P), G, vnorm, method);
}

StableDtInputs stable_dt_inputs(const Particles& P, const StateExtremes& e, const Grid& G,
                                VelocityNorm vnorm, Method method) {
  StableDtInputs in;
  in.F_max = e.F_abs_max;
  in.sigma_max = e.sigma_abs_max;
  in.sigmaF_max = e.sigmaF_abs_max;
  if (!std::isfinite(double(in.sigmaF_max))) {  // the product overflowed: take it in long double
    in.sigmaF_max = (P.sigma.cast<long double>() * P.F.cast<long double>()).abs().maxCoeff();
  }
  const auto nodes = G.velocity.segment(G.first_node_slot(), G.nodes());
  in.v_norm = vnorm == VelocityNorm::l2 ? nodes.matrix().norm() : nodes.abs().maxCoeff();
  if (method == Method::cpgimp) in.F_min = e.F_min;
  return in;
}

namespace {

// The factors of geo in the floating-point type `real`.
template <class real>
StableDtFactors<real> factors(const StableDtGeometry& geo) {
  StableDtFactors<real> f;
  const real m = geo.ppc;
  f.four_m = 4 * m;
  f.sqrt_m = std::sqrt(m);
  f.sqrt_E = std::sqrt(real(geo.E));
  f.inv_sqrt_E = 1 / f.sqrt_E;
  f.nine_h_sqrt_E = 9 * real(geo.h) * f.sqrt_E;
  f.h_sqrt_m = real(geo.h) * f.sqrt_m;
  f.gimp_position = 2 / (real(geo.width) * f.sqrt_m);
  return f;
}

// Eq. (108) in the floating-point type `real`.
template <class real>
real eq108(const StableDtInputs& in, const StableDtGeometry& geo, const StableDtFactors<real>& f,
           StressScaling sigma) {
  const real scale = sigma == StressScaling::scaled ? f.inv_sqrt_E : real(1);
  const real sigma_max = real(in.sigma_max) * scale;
  const real sigmaF_max = real(in.sigmaF_max) * scale;
  real position_term = 0;
  if (geo.method == Method::gimp) {
    position_term = f.gimp_position * sigmaF_max;
  } else if (geo.method == Method::cpgimp) {
    // l = min_p F_p h / m. An admissible state has F_min > 0; any other has no stable step.
    const real l = real(in.F_min) * real(geo.width);
    position_term = l > 0 ? 2 / (l * f.sqrt_m) * sigmaF_max : std::numeric_limits<real>::infinity();
  }
  const real denominator = f.four_m * (f.sqrt_E + real(in.F_max) + real(in.v_norm)) +
                           f.nine_h_sqrt_E * (real(in.F_max) + sigma_max + position_term);
  return f.h_sqrt_m / denominator;
}

}  // namespace

StableDtConstants stable_dt_constants(const StableDtGeometry& geo) {
  return factors<double>(geo);
}

double stable_dt(const StableDtInputs& in, const StableDtGeometry& geo, const StableDtConstants& c,
                 StressScaling sigma) {
  // In double; where an extreme but finite state overflows a double (for example
  // (sigma F)_max times 2 / (l sqrt m)), again in long double. A bound smaller than the
  // smallest positive double is that double: no step is stable.
  double dt = eq108<double>(in, geo, c, sigma);
  if (!(dt > 0) || !std::isfinite(dt)) {
    dt = static_cast<double>(eq108<long double>(in, geo, factors<long double>(geo), sigma));
  }
  return std::max(dt, std::numeric_limits<double>::denorm_min());
}

double stable_dt(const StableDtInputs& in, const StableDtGeometry& geo, StressScaling sigma) {
  return stable_dt(in, geo, stable_dt_constants(geo), sigma);
}

}  // namespace mpmstab
