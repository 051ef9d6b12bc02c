#pragma once
/// \file
/// The number of negative eigenvalues of an objective's Hessian with some dofs held fixed,
/// from the inertia of a sparse LDL^T factorisation (exact on unstable states, where a
/// Cholesky test only says "not definite"). Analysed once, factorised per state.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "core/sparse_objective.hpp"
#include "solvers/newton/fixed_dof_elimination.hpp"
#include "solvers/stability/symmetric_indefinite_factorization.hpp"

namespace growshell {

class HessianNegativeCount {
 public:
  /// Holds a reference: `objective` must outlive it. Throws as FixedDofElimination for bad
  /// fixed dofs.
  HessianNegativeCount(SparseObjective& objective, const std::vector<Eigen::Index>& fixed_dofs);

  /// Negative eigenvalues of the Hessian at x with the fixed dofs removed. Throws
  /// std::runtime_error (naming the cause) if the Hessian is not finite, cannot be factorised
  /// or is singular (a zero pivot: the count is then undefined).
  int at(const Eigen::Ref<const Eigen::VectorXd>& x);

 private:
  SparseObjective& objective_;
  Eigen::SparseMatrix<double> hessian_;
  FixedDofElimination fixed_;
  SymmetricIndefiniteFactorization factorization_;
};

}  // namespace growshell
