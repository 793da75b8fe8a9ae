#include "analysis/eigen_solve.hpp"

#include <Eigen/Eigenvalues>

namespace mpmstab {

namespace {

// One Eigen solver's eigenvalues and, when asked, its eigenvectors.
template <class Solver, class Matrix>
EigenPairs solve(const Matrix& A, bool vectors) {
  const Solver es(A, vectors);
  EigenPairs out;
  out.values = es.eigenvalues();
  if (vectors) out.vectors = es.eigenvectors();
  return out;
}

}  // namespace

EigenPairs eigen_pairs(const Eigen::MatrixXcd& A, bool vectors) {
  return solve<Eigen::ComplexEigenSolver<Eigen::MatrixXcd>>(A, vectors);
}

EigenPairs eigen_pairs(const Eigen::MatrixXd& A, bool vectors) {
  return solve<Eigen::EigenSolver<Eigen::MatrixXd>>(A, vectors);
}

}  // namespace mpmstab
