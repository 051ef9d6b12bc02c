#pragma once
/// \file
/// The number of negative eigenvalues of an objective's Hessian with some dofs held fixed,
/// from the inertia of a sparse LDL^T factorisation (exact on unstable states, where a
/// Cholesky test only says "not definite"). Analysed once, factorised per state. The count
/// can leave out one direction: that of the Hessian restricted to the hyperplane orthogonal
/// to it, e.g. without a neutral mode that a continuous symmetry of the physics leaves free
/// and the mesh only nearly so.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "core/parametrized_objective.hpp"
#include "solvers/newton/fixed_dof_elimination.hpp"
#include "solvers/stability/symmetric_indefinite_factorization.hpp"

namespace growshell {

class HessianNegativeCount {
 public:
  /// Holds a reference: `family` must outlive it. Throws as FixedDofElimination for bad
  /// fixed dofs.
  HessianNegativeCount(const ParametrizedObjective& family,
                       const std::vector<Eigen::Index>& fixed_dofs);

  /// Negative eigenvalues of the Hessian at (x, lambda) with the fixed dofs removed. Throws
  /// std::runtime_error (naming the cause) if the Hessian is not finite, cannot be factorised
  /// or is singular (a zero pivot: the count is then undefined).
  int at(const Eigen::Ref<const Eigen::VectorXd>& x, double lambda);

  /// Negative eigenvalues of the Hessian of the last at(), H_f (fixed dofs removed),
  /// restricted to the free vectors orthogonal to `direction` (its fixed entries are
  /// ignored): neg(H_f) - 1 if d^T H_f^{-1} d < 0, else neg(H_f), d the free part of
  /// `direction`. Why: the bordered matrix K = [H_f d; d^T 0] has, by Haynsworth's inertia
  /// additivity over the Schur complement -d^T H_f^{-1} d, In(K) = In(H_f) + In(-d^T H_f^{-1}
  /// d), and by the bordered-matrix inertia theorem (reduced_hessian_inertia.hpp) neg(K) =
  /// neg(H_f | d-perp) + 1. One solve with the factorisation at(x) already made. If d is
  /// (close to) an eigenvector of an eigenvalue near zero, that eigenvalue's sign no longer
  /// enters the count, while a crossing of any other eigenvalue does.
  /// Throws std::logic_error before the first at(), std::invalid_argument if `direction` has
  /// the wrong size, is not finite or vanishes on the free dofs, std::runtime_error if
  /// d^T H_f^{-1} d is zero or not finite (the count is then undefined).
  int negative_orthogonal_to(const Eigen::Ref<const Eigen::VectorXd>& direction) const;

 private:
  const ParametrizedObjective& family_;
  Eigen::SparseMatrix<double> hessian_;
  FixedDofElimination fixed_;
  SymmetricIndefiniteFactorization factorization_;
  int negative_ = -1;  ///< of the last at(); -1 before it
};

/// d^T H_f^{-1} d for the Hessian H_f eliminated by `fixed` and factorised by `factorization`,
/// d the direction with its fixed entries zeroed (the eliminated rows and columns are zero off
/// the diagonal, so the solve is H_f^{-1} d on the free dofs). Its sign decides whether leaving
/// d out lowers the negative count by one (HessianNegativeCount::negative_orthogonal_to).
/// Throws std::invalid_argument naming `caller` if d vanishes on the free dofs, and
/// std::runtime_error if the value is zero or not finite (H_f restricted to the hyperplane
/// orthogonal to d is then singular).
double inverse_quadratic_form(const FixedDofElimination& fixed,
                              const SymmetricIndefiniteFactorization& factorization,
                              Eigen::VectorXd direction, const std::string& caller);

}  // namespace growshell
