#include "solvers/stability/positive_definiteness.hpp"

#include "solvers/newton/cholmod_factorization.hpp"
#include "solvers/newton/fixed_dof_elimination.hpp"

namespace growshell {

bool hessian_is_positive_definite(SparseObjective& objective,
                                  const Eigen::Ref<const Eigen::VectorXd>& x,
                                  const std::vector<Eigen::Index>& fixed_dofs,
                                  double zero_tolerance) {
  Eigen::SparseMatrix<double> hessian = objective.hessian_pattern();
  const FixedDofElimination fixed(hessian, fixed_dofs);
  objective.evaluate(x, nullptr, &hessian);
  const double mean_diagonal = fixed.apply(hessian);
  CholmodFactorization cholesky;
  cholesky.analyze(hessian);
  return cholesky.factorize(hessian, zero_tolerance * mean_diagonal).positive_definite;
}

}  // namespace growshell
