#include "stable_dt.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mpmstab {

StableDtInputs stable_dt_inputs(const Particles& P, const Grid& G, VelocityNorm vnorm) {
  StableDtInputs in;
  in.F_max = P.F.abs().maxCoeff();
  in.sigma_max = P.sigma.abs().maxCoeff();
  in.sigmaF_max = (P.sigma * P.F).abs().maxCoeff();
  if (!std::isfinite(double(in.sigmaF_max))) {  // the product overflowed: take it in long double
    in.sigmaF_max = (P.sigma.cast<long double>() * P.F.cast<long double>()).abs().maxCoeff();
  }
  const auto nodes = G.velocity.segment(Grid::kOffset, G.nodes());
  in.v_norm = vnorm == VelocityNorm::l2 ? nodes.matrix().norm() : nodes.abs().maxCoeff();
  return in;
}

double stable_dt(const StableDtInputs& in, const StableDtGeometry& geo, StressScaling sigma) {
  // The denominator is summed in long double: products such as (sigma F) times 2 / (l sqrt m)
  // overflow a double for extreme but finite states, and the bound must stay finite and
  // positive for every finite state. Where it is smaller than the smallest positive double, it
  // is that smallest double: no step is stable.
  using real = long double;
  const real m = geo.ppc;
  const real sqrt_m = std::sqrt(m);
  const real sqrt_E = std::sqrt(real(geo.E));
  const real scale = sigma == StressScaling::scaled ? 1 / sqrt_E : real(1);
  const real sigma_max = real(in.sigma_max) * scale;
  const real sigmaF_max = real(in.sigmaF_max) * scale;
  const real position_term =
      geo.method == Method::gimp ? 2 / (real(geo.width) * sqrt_m) * sigmaF_max : real(0);
  const real denominator = 4 * m * (sqrt_E + real(in.F_max) + real(in.v_norm)) +
                           9 * real(geo.h) * sqrt_E * (real(in.F_max) + sigma_max + position_term);
  const double dt = static_cast<double>(real(geo.h) * sqrt_m / denominator);
  return std::max(dt, std::numeric_limits<double>::denorm_min());
}
}  // namespace mpmstab
