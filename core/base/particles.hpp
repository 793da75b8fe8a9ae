// Particle state as a struct of arrays: one Eigen array per quantity, index p = particle.
#pragma once

#include <Eigen/Core>

namespace mpmstab {

struct Particles {
  Eigen::ArrayXd X;        // reference position X_p (fixed)
  Eigen::ArrayXd x;        // current position x_p (unwrapped, also for periodic boundaries)
  Eigen::ArrayXd v;        // velocity v_p
  Eigen::ArrayXd F;        // deformation gradient F_p
  Eigen::ArrayXd sigma;    // stress sigma_p = E (F_p - 1)
  Eigen::ArrayXd mass;     // m_p = rho0 h / m
  Eigen::ArrayXd volume0;  // V_p^0 = h / m; the current volume is V_p = F_p V_p^0 (eq. 6)

  // APIC's affine velocity C_p (dv/dx) per particle: sized only when the transfer is apic.
  Eigen::ArrayXd C;

  Eigen::Index size() const { return x.size(); }

  void resize(Eigen::Index n) {
    for (Eigen::ArrayXd* a : {&X, &x, &v, &F, &sigma, &mass, &volume0})
      a->resize(n);
  }
};

}  // namespace mpmstab
