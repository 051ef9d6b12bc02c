#pragma once
/// \file
/// Holding chosen degrees of freedom fixed in a Newton system without changing its pattern.

#include <Eigen/SparseCore>
#include <vector>

namespace growshell {

/// Fixed dofs of an upper-triangular Hessian pattern: their rows and columns are zeroed and
/// their diagonal set to the mean |diagonal| of the free dofs, so that a solve gives a zero
/// step there and the conditioning and the pattern stay unchanged. Positions in the value
/// array are found once at construction.
class FixedDofElimination {
 public:
  /// Throws std::invalid_argument naming the problem for a non-square, uncompressed or
  /// lower-triangular pattern, a fixed dof out of range or listed twice, or a fixed dof with
  /// no diagonal entry.
  FixedDofElimination(const Eigen::SparseMatrix<double>& upper_pattern,
                      const std::vector<Eigen::Index>& fixed_dofs);

  /// Applies the elimination to `hessian_upper` (which carries the pattern) and returns the
  /// mean |diagonal| of the free dofs used as the fixed pivots (1 if that mean is zero).
  double apply(Eigen::SparseMatrix<double>& hessian_upper) const;

  /// Zeroes the fixed entries of a vector (a gradient or a right-hand side).
  void zero_fixed(Eigen::VectorXd& v) const;

  bool is_fixed(Eigen::Index dof) const { return is_fixed_[static_cast<std::size_t>(dof)] != 0; }
  Eigen::Index free_count() const { return free_count_; }
  /// Largest |v_i| over the free dofs.
  double free_inf_norm(const Eigen::VectorXd& v) const;
  /// Position of the diagonal entry of column i in the value array.
  int diagonal_position(Eigen::Index i) const { return diagonal_[static_cast<std::size_t>(i)]; }

 private:
  std::vector<Eigen::Index> fixed_;
  std::vector<char> is_fixed_;
  std::vector<int> diagonal_;
  std::vector<int> fixed_off_diagonal_;
  Eigen::Index free_count_ = 0;
};

}  // namespace growshell
