#pragma once
/// \file
/// A one-parameter family of energies E(x; lambda), the input of continuation.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cmath>


namespace growshell {

/// E(x; lambda): a smooth energy of n unknowns and one parameter, with a sparse symmetric
/// Hessian (in x) whose pattern depends on neither. The parameter is an argument of every
/// evaluation, never state of the object: evaluating does not change what a later evaluation
/// returns. Hessians are exchanged as in SparseObjective (the upper triangle, on the pattern).
class ParametrizedObjective {
 public:
  virtual ~ParametrizedObjective() = default;

  /// Number of unknowns n.
  virtual Eigen::Index dimension() const = 0;

  /// Upper-triangular sparsity pattern (values unspecified) of the n x n Hessian.
  virtual Eigen::SparseMatrix<double> hessian_pattern() const = 0;

  /// E(x; lambda), with dE/dx and the upper triangle of d2E/dx2 on request (as
  /// SparseObjective::evaluate, including the non-finite value for an x outside the domain).
  virtual double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, double lambda,
                          Eigen::VectorXd* gradient,
                          Eigen::SparseMatrix<double>* hessian_upper) const = 0;

  /// Whether lambda lies in the family's domain (evaluate throws std::invalid_argument for one
  /// that does not). Continuation asks before evaluating a corrector's lambda, so that a
  /// diverging corrector fails its step instead of the trace. Every finite lambda by default.
  virtual bool accepts_parameter(double lambda) const { return std::isfinite(lambda); }

  /// d(gradient)/d(lambda) at (x, lambda).
  virtual Eigen::VectorXd gradient_parameter_derivative(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                        double lambda) const = 0;
};

}  // namespace growshell
