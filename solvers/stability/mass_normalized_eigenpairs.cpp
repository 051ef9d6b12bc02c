#include "solvers/stability/mass_normalized_eigenpairs.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace growshell {

Eigenpairs lowest_mass_normalized_eigenpairs_of_matrix(const Eigen::SparseMatrix<double>& upper,
                                                       const Eigen::VectorXd& dof_mass,
                                                       const std::vector<Eigen::Index>& fixed_dofs,
                                                       const EigenpairOptions& options) {
  const Eigen::Index n = upper.rows();
  if (dof_mass.size() != n)
    throw std::invalid_argument("lowest_mass_normalized_eigenpairs: dof_mass has " +
                                std::to_string(dof_mass.size()) + " entries, the matrix " +
                                std::to_string(n) + " rows");
  std::vector<char> fixed(static_cast<std::size_t>(n), 0);
  for (const Eigen::Index d : fixed_dofs)
    if (d >= 0 && d < n) fixed[static_cast<std::size_t>(d)] = 1;  // others: rejected below
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (fixed[static_cast<std::size_t>(i)]) continue;
    if (!(std::isfinite(dof_mass(i)) && dof_mass(i) > 0.0))
      throw std::invalid_argument("lowest_mass_normalized_eigenpairs: the mass of free dof " +
                                  std::to_string(i) + " is " + std::to_string(dof_mass(i)) +
                                  "; it must be finite and > 0");
    scale(i) = 1.0 / std::sqrt(dof_mass(i));
  }
  Eigen::SparseMatrix<double> scaled = upper;
  for (Eigen::Index col = 0; col < scaled.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(scaled, col); it; ++it)
      it.valueRef() *= scale(it.row()) * scale(it.col());
  Eigenpairs pairs = lowest_eigenpairs_of_matrix(scaled, fixed_dofs, options);
  pairs.vectors = scale.asDiagonal() * pairs.vectors;
  return pairs;
}

Eigenpairs lowest_mass_normalized_eigenpairs(SparseObjective& objective,
                                             const Eigen::Ref<const Eigen::VectorXd>& x,
                                             const Eigen::VectorXd& dof_mass,
                                             const std::vector<Eigen::Index>& fixed_dofs,
                                             const EigenpairOptions& options) {
  if (x.size() != objective.dimension())
    throw std::invalid_argument("lowest_mass_normalized_eigenpairs: x has " +
                                std::to_string(x.size()) + " entries, the objective " +
                                std::to_string(objective.dimension()));
  Eigen::SparseMatrix<double> hessian = objective.hessian_pattern();
  objective.evaluate(x, nullptr, &hessian);
  return lowest_mass_normalized_eigenpairs_of_matrix(hessian, dof_mass, fixed_dofs, options);
}

}  // namespace growshell
