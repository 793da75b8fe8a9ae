#include "stable_dt.hpp"

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

// Eq. (108) in the floating-point type `real`.
template <class real>
real eq108(const StableDtInputs& in, const StableDtGeometry& geo, StressScaling sigma) {
  const real m = geo.ppc;
  const real sqrt_m = std::sqrt(m);
  const real sqrt_E = std::sqrt(real(geo.E));
  const real scale = sigma == StressScaling::scaled ? 1 / sqrt_E : real(1);
  const real sigma_max = real(in.sigma_max) * scale;
  const real sigmaF_max = real(in.sigmaF_max) * scale;
  real position_term = 0;
  if (geo.method == Method::gimp) {
    position_term = 2 / (real(geo.width) * sqrt_m) * sigmaF_max;
  } else if (geo.method == Method::cpgimp) {
    // l = min_p F_p h / m. An admissible state has F_min > 0; any other has no stable step.
    const real l = real(in.F_min) * real(geo.width);
    position_term = l > 0 ? 2 / (l * sqrt_m) * sigmaF_max : std::numeric_limits<real>::infinity();
  }
  const real denominator = 4 * m * (sqrt_E + real(in.F_max) + real(in.v_norm)) +
                           9 * real(geo.h) * sqrt_E * (real(in.F_max) + sigma_max + position_term);
  return real(geo.h) * sqrt_m / denominator;
}

}  // namespace

double stable_dt(const StableDtInputs& in, const StableDtGeometry& geo, StressScaling sigma) {
  // In double; where an extreme but finite state overflows a double (for example
  // (sigma F)_max times 2 / (l sqrt m)), again in long double. A bound smaller than the
  // smallest positive double is that double: no step is stable.
  double dt = eq108<double>(in, geo, sigma);
  if (!(dt > 0) || !std::isfinite(dt)) {
    dt = static_cast<double>(eq108<long double>(in, geo, sigma));
  }
  return std::max(dt, std::numeric_limits<double>::denorm_min());
}

}  // namespace mpmstab
