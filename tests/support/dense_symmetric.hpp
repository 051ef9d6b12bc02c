#pragma once
// The full dense matrix of a symmetric matrix stored as its upper triangle, for the tests'
// dense reference computations.

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace growshell::test_support {

inline Eigen::MatrixXd dense_symmetric(const Eigen::SparseMatrix<double>& upper) {
  const Eigen::MatrixXd u = Eigen::MatrixXd(upper);
  Eigen::MatrixXd full = u + u.transpose();
  full.diagonal() = u.diagonal();
  return full;
}

}  // namespace growshell::test_support
