#include "solvers/continuation/symmetric_subspace_family.hpp"

#include <stdexcept>
#include <string>

namespace growshell {

namespace {

const SymmetricSubspace& checked(const ParametrizedObjective& full,
                                 const SymmetricSubspace& subspace) {
  if (subspace.full_dimension() != full.dimension())
    throw std::invalid_argument("SymmetricSubspaceFamily: the subspace is for " +
                                std::to_string(subspace.full_dimension()) +
                                " unknowns, the family has " + std::to_string(full.dimension()));
  return subspace;
}

}  // namespace

SymmetricSubspaceFamily::SymmetricSubspaceFamily(const ParametrizedObjective& full,
                                                 const SymmetricSubspace& subspace)
    : full_(full),
      subspace_(checked(full, subspace)),
      basis_transpose_(subspace.basis().transpose()),
      projection_(full.hessian_pattern(), subspace.basis()) {}

double SymmetricSubspaceFamily::evaluate(const Eigen::Ref<const Eigen::VectorXd>& y, double lambda,
                                         Eigen::VectorXd* gradient,
                                         Eigen::SparseMatrix<double>* hessian_upper) const {
  const Eigen::VectorXd x = subspace_.expand(y);
  Eigen::VectorXd full_gradient;
  Eigen::SparseMatrix<double> full_hessian;
  if (hessian_upper) full_hessian = projection_.full_pattern();
  const double e = full_.evaluate(x, lambda, gradient ? &full_gradient : nullptr,
                                  hessian_upper ? &full_hessian : nullptr);
  if (gradient) *gradient = basis_transpose_ * full_gradient;
  if (hessian_upper) projection_.project(full_hessian, *hessian_upper);
  return e;
}

Eigen::VectorXd SymmetricSubspaceFamily::gradient_parameter_derivative(
    const Eigen::Ref<const Eigen::VectorXd>& y, double lambda) const {
  return basis_transpose_ * full_.gradient_parameter_derivative(subspace_.expand(y), lambda);
}

}  // namespace growshell
