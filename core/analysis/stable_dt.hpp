// The paper's time-step bound, eq. (108), evaluated from a state.
//
//   dt <= h sqrt(m) / ( 4 m (sqrt(E) + F_max + ||v||)
//                       + 9 h sqrt(E) (F_max + sigma_max + (2 / (l sqrt(m))) (sigma F)_max) )
//
// m = particles per cell, F_max = max_p |F_p|, sigma_max = max_p |sigma_p|,
// (sigma F)_max = max_p |sigma_p F_p|, ||v|| = norm of the nodal velocity vector, l = 2 lp the
// particle width. For linear MPM the position-Lipschitz term (2 / (l sqrt m)) (sigma F)_max is
// absent: the paper shows linear MPM has no such constant (section 4.4, eq. 77 onwards).
// For cpGIMP, whose widths follow F (l_p = F_p h / m), l is the smallest current width
// min_p F_p h / m: the bound holds for the narrowest support, where the position-Lipschitz
// constant of the basis is largest.
// The options (params.hpp) pick how sigma enters and which norm ||v|| is.
#pragma once

#include "base/failure.hpp"
#include "base/params.hpp"
#include "base/particles.hpp"
#include "step/grid.hpp"

namespace mpmstab {

struct StableDtInputs {
  double F_max = 0;            // max_p |F_p|
  double sigma_max = 0;        // max_p |sigma_p|
  long double sigmaF_max = 0;  // max_p |sigma_p F_p| (long double: it may exceed a double)
  double v_norm = 0;           // ||v_N||, Euclidean or maximum norm over the distinct nodes
  double F_min = 1;            // min_p F_p (cpGIMP only, which scales the width by it)
};

struct StableDtGeometry {
  Method method;
  double E;
  double h;
  int ppc;       // m
  double width;  // l = 2 lp = h / m; for cpGIMP the reference width, times F_min
};

// Reductions over the state after a step (F_min for cpGIMP only).
// (sigma F)_max is taken as max |sigma_p| |F_p| in long double, so it does not overflow.
StableDtInputs stable_dt_inputs(const Particles& P, const Grid& G, VelocityNorm vnorm,
                                Method method);
// The same from the state's extremes, already taken (e = state_extremes(P), failure.hpp).
StableDtInputs stable_dt_inputs(const Particles& P, const StateExtremes& e, const Grid& G,
                                VelocityNorm vnorm, Method method);

// Eq. (108). Finite and positive for every finite input: the denominator is >= 4 m sqrt(E) > 0,
// it is summed again in long double where a double overflows, and the result is at least the
// smallest positive double.
double stable_dt(const StableDtInputs& in, const StableDtGeometry& geo, StressScaling sigma);

// The factors of eq. (108) that depend on the geometry alone (square roots, products), in the
// floating-point type `real`: once per run for a run that evaluates it every step (stable_dt
// with them is stable_dt without them, bit for bit).
template <class real>
struct StableDtFactors {
  real four_m = 0;         // 4 m
  real sqrt_m = 0;         // sqrt(m)
  real sqrt_E = 0;         // sqrt(E)
  real inv_sqrt_E = 0;     // 1 / sqrt(E), the scaled stress's factor
  real nine_h_sqrt_E = 0;  // 9 h sqrt(E)
  real h_sqrt_m = 0;       // h sqrt(m)
  real gimp_position = 0;  // 2 / (l sqrt(m)), uGIMP's position-Lipschitz factor
};
using StableDtConstants = StableDtFactors<double>;
StableDtConstants stable_dt_constants(const StableDtGeometry& geo);
double stable_dt(const StableDtInputs& in, const StableDtGeometry& geo,
                 const StableDtConstants& constants, StressScaling sigma);

}  // namespace mpmstab
