#pragma once
// The dense eigenproblems of the analyses (the spectral radius of a step's linearised map, the
// Bloch symbol's eigenvalues and the dispersion branches), solved by Eigen in one translation
// unit: its solvers are compiled once, not in every analysis that needs one.
#include <Eigen/Core>

namespace mpmstab {

struct EigenPairs {
  Eigen::VectorXcd values;
  Eigen::MatrixXcd vectors;  // column j belongs to values[j]; empty unless asked for
};

// Eigen::ComplexEigenSolver on a complex matrix (eigenvectors when `vectors`).
EigenPairs eigen_pairs(const Eigen::MatrixXcd& A, bool vectors);
// Eigen::EigenSolver on a real matrix (eigenvectors when `vectors`).
EigenPairs eigen_pairs(const Eigen::MatrixXd& A, bool vectors);

}  // namespace mpmstab
