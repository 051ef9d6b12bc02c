#pragma once
/// \file
/// The interface a constrained minimiser (Ipopt) needs from a set of smooth inequality
/// constraints c_k(x) >= 0, e.g. contact gaps. Patterns are fixed for the object's lifetime,
/// because Ipopt's structure is fixed during one solve: a contact set is rebuilt between
/// solves, never during one.

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace growshell {

/// m smooth functions c_k(x) of n unknowns, feasible where c_k(x) >= 0.
class InequalityConstraints {
 public:
  virtual ~InequalityConstraints() = default;

  /// Number of unknowns n.
  virtual Eigen::Index dimension() const = 0;
  /// Number of constraints m.
  virtual Eigen::Index count() const = 0;

  /// Structural pattern (values unspecified) of the m x n Jacobian dc/dx, row-major
  /// compressed. Every entry that evaluate() may ever make nonzero is in it.
  virtual Eigen::SparseMatrix<double, Eigen::RowMajor> jacobian_pattern() const = 0;

  /// Structural pattern of the upper triangle (row <= column, column-major compressed) of
  /// sum_k w_k d2c_k/dx2, like SparseObjective::hessian_pattern().
  virtual Eigen::SparseMatrix<double> hessian_pattern() const = 0;

  /// c(x) into `values` (resized to m). If `jacobian` is non-null it must carry
  /// jacobian_pattern(); its values are overwritten. Units: those of the constraint (metres
  /// for a gap), so that multipliers are forces.
  virtual void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd& values,
                        Eigen::SparseMatrix<double, Eigen::RowMajor>* jacobian) = 0;

  /// The upper triangle of sum_k weights_k d2c_k/dx2 at x into `hessian_upper`, which carries
  /// hessian_pattern() (values overwritten).
  virtual void weighted_hessian(const Eigen::Ref<const Eigen::VectorXd>& x,
                                const Eigen::Ref<const Eigen::VectorXd>& weights,
                                Eigen::SparseMatrix<double>& hessian_upper) = 0;
};

}  // namespace growshell
