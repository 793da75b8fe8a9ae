// p2g for the bases beyond the paper's (B-splines, CPDI), in a translation unit of their own
// (p2g_kernel.hpp says why).
#include "step/p2g_kernel.hpp"

namespace mpmstab {

void p2g(const BSpline2Basis& basis, const Particles& P, const double* body_accel,
         Stencil<BSpline2Basis::width>& S, Grid& G) {
  p2g_any(basis, P, body_accel, S, G);
}

void p2g(const BSpline3Basis& basis, const Particles& P, const double* body_accel,
         Stencil<BSpline3Basis::width>& S, Grid& G) {
  p2g_any(basis, P, body_accel, S, G);
}

void p2g(const CpdiBasis& basis, const Particles& P, const double* body_accel,
         Stencil<CpdiBasis::width>& S, Grid& G) {
  p2g_any(basis, P, body_accel, S, G);
}

}  // namespace mpmstab
