#include "solvers/continuation/symmetric_subspace_family.hpp"

#include <stdexcept>
#include <string>

namespace growshell {

namespace {

/// The upper triangle of `product` written into `upper_pattern`'s values (zero elsewhere);
/// every entry of the product's upper triangle must be in the pattern.
void scatter_upper(const Eigen::SparseMatrix<double>& product,
                   Eigen::SparseMatrix<double>& upper_pattern) {
  std::fill(upper_pattern.valuePtr(), upper_pattern.valuePtr() + upper_pattern.nonZeros(), 0.0);
  for (Eigen::Index j = 0; j < product.outerSize(); ++j) {
    const int* rows = upper_pattern.innerIndexPtr();
    const int begin = upper_pattern.outerIndexPtr()[j], end = upper_pattern.outerIndexPtr()[j + 1];
    int position = begin;
    for (Eigen::SparseMatrix<double>::InnerIterator it(product, j); it; ++it) {
      if (it.row() > j) break;  // inner indices are sorted
      while (position < end && rows[position] < it.row()) ++position;
      if (position == end || rows[position] != it.row())
        throw std::logic_error("SymmetricSubspaceFamily: Hessian entry outside the pattern");
      upper_pattern.valuePtr()[position] = it.value();
    }
  }
}

}  // namespace

SymmetricSubspaceFamily::SymmetricSubspaceFamily(const ParametrizedObjective& full,
                                                 const SymmetricSubspace& subspace)
    : full_(full), subspace_(subspace) {
  if (subspace.full_dimension() != full.dimension())
    throw std::invalid_argument("SymmetricSubspaceFamily: the subspace is for " +
                                std::to_string(subspace.full_dimension()) +
                                " unknowns, the family has " + std::to_string(full.dimension()));
  basis_transpose_ = subspace.basis().transpose();
  // Structural pattern from absolute values, so that no entry cancels to a structural gap.
  Eigen::SparseMatrix<double> ones = full.hessian_pattern();
  std::fill(ones.valuePtr(), ones.valuePtr() + ones.nonZeros(), 1.0);
  const Eigen::SparseMatrix<double> symmetric_ones = ones.selfadjointView<Eigen::Upper>();
  const Eigen::SparseMatrix<double> abs_basis = subspace.basis().cwiseAbs();
  Eigen::SparseMatrix<double> product =
      Eigen::SparseMatrix<double>(abs_basis.transpose()) * symmetric_ones * abs_basis;
  pattern_ = product.triangularView<Eigen::Upper>();
  pattern_.makeCompressed();  // values: structural counts (positive, for an analysis)
}

double SymmetricSubspaceFamily::evaluate(const Eigen::Ref<const Eigen::VectorXd>& y, double lambda,
                                         Eigen::VectorXd* gradient,
                                         Eigen::SparseMatrix<double>* hessian_upper) const {
  const Eigen::VectorXd x = subspace_.expand(y);
  Eigen::VectorXd full_gradient;
  Eigen::SparseMatrix<double> full_hessian;
  if (hessian_upper) full_hessian = full_.hessian_pattern();
  const double e = full_.evaluate(x, lambda, gradient ? &full_gradient : nullptr,
                                  hessian_upper ? &full_hessian : nullptr);
  if (gradient) *gradient = basis_transpose_ * full_gradient;
  if (hessian_upper) {
    const Eigen::SparseMatrix<double> symmetric = full_hessian.selfadjointView<Eigen::Upper>();
    const Eigen::SparseMatrix<double> product = basis_transpose_ * symmetric * subspace_.basis();
    if (hessian_upper->nonZeros() != pattern_.nonZeros() ||
        hessian_upper->cols() != pattern_.cols())
      *hessian_upper = pattern_;
    scatter_upper(product, *hessian_upper);
  }
  return e;
}

Eigen::VectorXd SymmetricSubspaceFamily::gradient_parameter_derivative(
    const Eigen::Ref<const Eigen::VectorXd>& y, double lambda) const {
  return basis_transpose_ * full_.gradient_parameter_derivative(subspace_.expand(y), lambda);
}

}  // namespace growshell
