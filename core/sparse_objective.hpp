#pragma once
/// \file
/// The interface a Newton-type solver needs from a smooth energy of many unknowns.

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace growshell {

/// A smooth scalar function E(x) of n unknowns with a sparse symmetric Hessian whose
/// sparsity pattern does not depend on x.
///
/// Hessians are exchanged as the *upper triangle* (row <= column) of a column-major
/// compressed Eigen::SparseMatrix. hessian_pattern() gives that structure once; evaluate()
/// then overwrites the values of a matrix with exactly that structure (no allocation).
class SparseObjective {
 public:
  virtual ~SparseObjective() = default;

  /// Number of unknowns n.
  virtual Eigen::Index dimension() const = 0;

  /// Upper-triangular sparsity pattern (values unspecified) of the n x n Hessian.
  virtual Eigen::SparseMatrix<double> hessian_pattern() const = 0;

  /// Returns E(x). If `gradient` is non-null it receives dE/dx (resized to n).
  /// If `hessian_upper` is non-null it must carry the pattern of hessian_pattern();
  /// its values are overwritten with the upper triangle of d2E/dx2.
  /// A non-finite value signals that x is outside the domain of E (e.g. a degenerate
  /// surface); callers treat it as an infinitely high energy.
  virtual double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                          Eigen::VectorXd* gradient,
                          Eigen::SparseMatrix<double>* hessian_upper) = 0;
};

}  // namespace growshell
