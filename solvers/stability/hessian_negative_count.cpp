#include "solvers/stability/hessian_negative_count.hpp"

#include <stdexcept>

namespace growshell {

HessianNegativeCount::HessianNegativeCount(SparseObjective& objective,
                                           const std::vector<Eigen::Index>& fixed_dofs)
    : objective_(objective), hessian_(objective.hessian_pattern()), fixed_(hessian_, fixed_dofs) {
  factorization_.analyze(hessian_);
}

int HessianNegativeCount::at(const Eigen::Ref<const Eigen::VectorXd>& x) {
  objective_.evaluate(x, nullptr, &hessian_);
  fixed_.apply(hessian_);
  const Eigen::Map<const Eigen::VectorXd> values(hessian_.valuePtr(), hessian_.nonZeros());
  if (!values.allFinite())
    throw std::runtime_error("HessianNegativeCount: the Hessian has non-finite entries");
  factorization_.factorize(hessian_);
  if (factorization_.zero_pivots() > 0)
    throw std::runtime_error("HessianNegativeCount: the Hessian is singular (zero pivot)");
  return factorization_.negative_eigenvalues();
}

}  // namespace growshell
