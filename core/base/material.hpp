// Material laws of the 1D bar. In 1D the Cauchy stress and the first Piola-Kirchhoff stress
// coincide (sigma = P F / J with J = F), so one function of F gives the stress both ways.
//
//  - linear:      sigma = E (F - 1), the paper's law (eq. 109, section 5.1);
//  - neo_hookean: sigma = (E / 2) (F - 1 / F), the 1D neo-Hookean law of the manufactured
//                 solution of Steffen et al. (2008). Its slope at F = 1 is E, as for the linear
//                 law; it stiffens without bound in compression (sigma -> -inf as F -> 0).
#pragma once

#include <cmath>

namespace mpmstab {

enum class Material { linear, neo_hookean };

struct MaterialLaw {
  Material kind = Material::linear;
  double E = 0;  // Young's modulus

  double stress(double F) const {
    return kind == Material::linear ? E * (F - 1.0) : 0.5 * E * (F - 1.0 / F);
  }
  // The strain energy per unit reference volume, W(F) with W(1) = 0 and dW/dF = stress(F):
  // linear E (F - 1)^2 / 2; neo-Hookean E (F^2 - 1) / 4 - (E / 2) ln F (not finite for F <= 0).
  double energy(double F) const {
    return kind == Material::linear ? 0.5 * E * (F - 1.0) * (F - 1.0)
                                    : 0.25 * E * (F * F - 1.0) - 0.5 * E * std::log(F);
  }
};

}  // namespace mpmstab
