#include "stable_dt.hpp"

#include <cmath>

namespace mpmstab {

StableDtInputs stable_dt_inputs(const Particles& P, const Grid& G, VelocityNorm vnorm) {
  StableDtInputs in;
  in.F_max = P.F.abs().maxCoeff();
  in.sigma_max = P.sigma.abs().maxCoeff();
  in.sigmaF_max = (P.sigma * P.F).abs().maxCoeff();
  const auto nodes = G.velocity.segment(Grid::kOffset, G.nodes());
  in.v_norm = vnorm == VelocityNorm::l2 ? nodes.matrix().norm() : nodes.abs().maxCoeff();
  return in;
}

double stable_dt(const StableDtInputs& in, const StableDtGeometry& geo, StressScaling sigma) {
  const double m = geo.ppc;
  const double sqrt_m = std::sqrt(m);
  const double sqrt_E = std::sqrt(geo.E);
  const double scale = sigma == StressScaling::scaled ? 1.0 / sqrt_E : 1.0;
  const double sigma_max = in.sigma_max * scale;
  const double sigmaF_max = in.sigmaF_max * scale;
  const double position_term =
      geo.method == Method::gimp ? 2.0 / (geo.width * sqrt_m) * sigmaF_max : 0.0;
  const double denominator = 4.0 * m * (sqrt_E + in.F_max + in.v_norm) +
                             9.0 * geo.h * sqrt_E * (in.F_max + sigma_max + position_term);
  return geo.h * sqrt_m / denominator;
}

}  // namespace mpmstab
