#pragma once
// The upper triangle (row <= column) of a square sparse matrix, compressed: the form in which
// the library's factorisations and eigensolvers take symmetric matrices.

#include <Eigen/SparseCore>

namespace growshell::test_support {

inline Eigen::SparseMatrix<double> upper_of(const Eigen::SparseMatrix<double>& full) {
  Eigen::SparseMatrix<double> u = full.triangularView<Eigen::Upper>();
  u.makeCompressed();
  return u;
}

}  // namespace growshell::test_support
