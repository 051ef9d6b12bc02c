#include "solvers/newton/fixed_dof_elimination.hpp"

#include "solvers/newton/upper_triangle_check.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace growshell {

FixedDofElimination::FixedDofElimination(const Eigen::SparseMatrix<double>& pattern,
                                         const std::vector<Eigen::Index>& fixed_dofs)
    : fixed_(fixed_dofs) {
  check_upper_triangle(pattern, "Hessian pattern");
  const Eigen::Index n = pattern.rows();
  is_fixed_.assign(static_cast<std::size_t>(n), 0);
  for (const Eigen::Index d : fixed_dofs) {
    if (d < 0 || d >= n)
      throw std::invalid_argument("fixed dof " + std::to_string(d) + " is out of range [0, " +
                                  std::to_string(n) + ")");
    if (is_fixed_[static_cast<std::size_t>(d)])
      throw std::invalid_argument("fixed dof " + std::to_string(d) + " is listed twice");
    is_fixed_[static_cast<std::size_t>(d)] = 1;
  }
  free_count_ = n - static_cast<Eigen::Index>(fixed_dofs.size());
  diagonal_.assign(static_cast<std::size_t>(n), -1);
  const int* outer = pattern.outerIndexPtr();
  const int* inner = pattern.innerIndexPtr();
  for (Eigen::Index col = 0; col < n; ++col) {
    for (int k = outer[col]; k < outer[col + 1]; ++k) {
      const Eigen::Index row = inner[k];
      if (row == col)
        diagonal_[static_cast<std::size_t>(col)] = k;
      else if (is_fixed(row) || is_fixed(col))
        fixed_off_diagonal_.push_back(k);
    }
  }
  for (const Eigen::Index d : fixed_dofs)
    if (diagonal_[static_cast<std::size_t>(d)] < 0)
      throw std::invalid_argument("Hessian pattern has no diagonal entry for fixed dof " +
                                  std::to_string(d));
}

double FixedDofElimination::apply(Eigen::SparseMatrix<double>& hessian) const {
  double* values = hessian.valuePtr();
  double sum = 0.0;
  for (std::size_t i = 0; i < diagonal_.size(); ++i)
    if (!is_fixed_[i] && diagonal_[i] >= 0) sum += std::abs(values[diagonal_[i]]);
  double mean = free_count_ > 0 ? sum / static_cast<double>(free_count_) : 0.0;
  // An all-zero diagonal gives no scale; unit scale keeps shifts well defined.
  if (!(mean > 0.0)) mean = 1.0;
  for (const int k : fixed_off_diagonal_) values[k] = 0.0;
  for (const Eigen::Index d : fixed_) values[diagonal_[static_cast<std::size_t>(d)]] = mean;
  return mean;
}

void FixedDofElimination::zero_fixed(Eigen::VectorXd& v) const {
  for (const Eigen::Index d : fixed_) v[d] = 0.0;
}

double FixedDofElimination::free_inf_norm(const Eigen::VectorXd& v) const {
  double m = 0.0;
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (!is_fixed(i)) m = std::max(m, std::abs(v[i]));
  return m;
}

}  // namespace growshell
