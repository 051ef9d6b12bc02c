#pragma once
/// \file
/// The storage contract every sparse factorisation in growshell shares: the upper triangle of
/// a square matrix, column-major, compressed, with strictly increasing row indices per column.

#include <Eigen/SparseCore>
#include <string>

namespace growshell {

/// Throws std::invalid_argument, prefixed with `who` (e.g. "CholmodFactorization::analyze"),
/// if `upper` is not square, not compressed, has an entry below the diagonal, or has row
/// indices that do not strictly increase within a column.
void check_upper_triangle(const Eigen::SparseMatrix<double>& upper, const std::string& who);

}  // namespace growshell
