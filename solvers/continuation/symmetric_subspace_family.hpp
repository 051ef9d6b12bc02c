#pragma once
/// \file
/// A parametrised energy restricted to a symmetric subspace: E_r(y; lambda) = E(Q y; lambda)
/// with gradient Q^T g and Hessian Q^T H Q. Its equilibria are the equilibria of E that have
/// the symmetry, whenever E is invariant under it (then g(Q y) lies in the subspace). For an
/// E that breaks the symmetry slightly (a contact pair set chosen with index tie-breaks), they
/// are the equilibria of the symmetrised energy, which equals E on the subspace.

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "core/parametrized_objective.hpp"
#include "solvers/stability/subspace_hessian_projection.hpp"
#include "solvers/continuation/symmetric_subspace.hpp"

namespace growshell {

/// Holds references: `full` and `subspace` must outlive it.
class SymmetricSubspaceFamily final : public ParametrizedObjective {
 public:
  /// Throws std::invalid_argument if the subspace is for another dimension.
  SymmetricSubspaceFamily(const ParametrizedObjective& full, const SymmetricSubspace& subspace);

  Eigen::Index dimension() const override { return subspace_.dimension(); }
  /// Upper triangle of the structure of Q^T H Q (fixed: the entries that a stored entry of
  /// the full pattern reaches).
  Eigen::SparseMatrix<double> hessian_pattern() const override { return projection_.pattern(); }
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& y, double lambda,
                  Eigen::VectorXd* gradient,
                  Eigen::SparseMatrix<double>* hessian_upper) const override;
  bool accepts_parameter(double lambda) const override { return full_.accepts_parameter(lambda); }
  Eigen::VectorXd gradient_parameter_derivative(const Eigen::Ref<const Eigen::VectorXd>& y,
                                                double lambda) const override;

  const SymmetricSubspace& subspace() const { return subspace_; }

 private:
  const ParametrizedObjective& full_;
  const SymmetricSubspace& subspace_;
  Eigen::SparseMatrix<double> basis_transpose_;
  SubspaceHessianProjection projection_;  ///< Q^T H Q in one pass over H's values
};

}  // namespace growshell
