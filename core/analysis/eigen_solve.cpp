#include "analysis/eigen_solve.hpp"

#include <Eigen/Eigenvalues>

namespace mpmstab {

EigenPairs eigen_pairs(const Eigen::MatrixXcd& A, bool vectors) {
  const Eigen::ComplexEigenSolver<Eigen::MatrixXcd> es(A, vectors);
  EigenPairs out;
  out.values = es.eigenvalues();
  if (vectors) out.vectors = es.eigenvectors();
  return out;
}

EigenPairs eigen_pairs(const Eigen::MatrixXd& A, bool vectors) {
  const Eigen::EigenSolver<Eigen::MatrixXd> es(A, vectors);
  EigenPairs out;
  out.values = es.eigenvalues();
  if (vectors) out.vectors = es.eigenvectors();
  return out;
}

}  // namespace mpmstab
