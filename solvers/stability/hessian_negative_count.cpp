#include "solvers/stability/hessian_negative_count.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace growshell {

HessianNegativeCount::HessianNegativeCount(const ParametrizedObjective& family,
                                           const std::vector<Eigen::Index>& fixed_dofs)
    : family_(family), hessian_(family.hessian_pattern()), fixed_(hessian_, fixed_dofs) {
  factorization_.analyze(hessian_);
}

int HessianNegativeCount::at(const Eigen::Ref<const Eigen::VectorXd>& x, double lambda) {
  family_.evaluate(x, lambda, nullptr, &hessian_);
  fixed_.apply(hessian_);
  const Eigen::Map<const Eigen::VectorXd> values(hessian_.valuePtr(), hessian_.nonZeros());
  if (!values.allFinite())
    throw std::runtime_error("HessianNegativeCount: the Hessian has non-finite entries");
  factorization_.factorize(hessian_);
  if (factorization_.zero_pivots() > 0)
    throw std::runtime_error("HessianNegativeCount: the Hessian is singular (zero pivot)");
  negative_ = factorization_.negative_eigenvalues();
  return negative_;
}

int HessianNegativeCount::negative_orthogonal_to(
    const Eigen::Ref<const Eigen::VectorXd>& direction) const {
  if (negative_ < 0)
    throw std::logic_error("HessianNegativeCount::negative_orthogonal_to: call at(x, lambda) first");
  if (direction.size() != hessian_.rows())
    throw std::invalid_argument("HessianNegativeCount::negative_orthogonal_to: the direction has " +
                                std::to_string(direction.size()) + " entries, the Hessian " +
                                std::to_string(hessian_.rows()) + " rows");
  if (!direction.allFinite())
    throw std::invalid_argument(
        "HessianNegativeCount::negative_orthogonal_to: the direction is not finite");
  const double schur = inverse_quadratic_form(fixed_, factorization_, direction,
                                              "HessianNegativeCount::negative_orthogonal_to");
  return schur < 0.0 ? negative_ - 1 : negative_;
}

double inverse_quadratic_form(const FixedDofElimination& fixed,
                              const SymmetricIndefiniteFactorization& factorization,
                              Eigen::VectorXd direction, const std::string& caller) {
  fixed.zero_fixed(direction);
  if (fixed.free_inf_norm(direction) == 0.0)
    throw std::invalid_argument(caller + ": the direction vanishes on the free dofs");
  // The fixed dofs' rows and columns of the eliminated Hessian are zero off the diagonal, so
  // with d zero there the solve is H_f^{-1} d on the free dofs and zero on the fixed ones.
  const double value = direction.dot(factorization.solve(direction));
  if (!std::isfinite(value) || value == 0.0)
    throw std::runtime_error(caller +
                             ": d^T H^-1 d is zero or not finite: the Hessian restricted to the "
                             "hyperplane is singular");
  return value;
}

}  // namespace growshell
