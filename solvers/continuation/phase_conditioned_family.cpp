#include "solvers/continuation/phase_conditioned_family.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace growshell {

PhaseConditionedFamily::PhaseConditionedFamily(const ParametrizedObjective& family,
                                               Eigen::VectorXd functional, double value)
    : family_(family), functional_(std::move(functional)), value_(value) {
  const Eigen::Index n = family_.dimension();
  if (functional_.size() != n)
    throw std::invalid_argument("PhaseConditionedFamily: the functional has " +
                                std::to_string(functional_.size()) + " entries, the family " +
                                std::to_string(n) + " unknowns");
  if (!functional_.allFinite() || !std::isfinite(value_))
    throw std::invalid_argument("PhaseConditionedFamily: the functional and its value must be finite");
  if (functional_.lpNorm<Eigen::Infinity>() == 0.0)
    throw std::invalid_argument("PhaseConditionedFamily: the functional vanishes");
  const Eigen::SparseMatrix<double> family_pattern = family_.hessian_pattern();
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(family_pattern.nonZeros() + n + 1));
  for (Eigen::Index col = 0; col < family_pattern.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(family_pattern, col); it; ++it)
      entries.emplace_back(it.row(), it.col(), 1.0);
  for (Eigen::Index i = 0; i < n; ++i)
    if (functional_(i) != 0.0) entries.emplace_back(i, n, 1.0);
  entries.emplace_back(n, n, 1.0);
  pattern_.resize(n + 1, n + 1);
  pattern_.setFromTriplets(entries.begin(), entries.end());
  pattern_.makeCompressed();
}

double PhaseConditionedFamily::evaluate(const Eigen::Ref<const Eigen::VectorXd>& z, double lambda,
                                        Eigen::VectorXd* gradient,
                                        Eigen::SparseMatrix<double>* hessian_upper) const {
  const Eigen::Index n = family_.dimension();
  if (z.size() != n + 1)
    throw std::invalid_argument("PhaseConditionedFamily::evaluate: needs " + std::to_string(n + 1) +
                                " unknowns, got " + std::to_string(z.size()));
  const auto x = z.head(n);
  const double mu = z(n);
  Eigen::VectorXd family_gradient;
  Eigen::SparseMatrix<double> family_hessian;
  if (hessian_upper) family_hessian = family_.hessian_pattern();
  const double energy = family_.evaluate(x, lambda, gradient ? &family_gradient : nullptr,
                                         hessian_upper ? &family_hessian : nullptr);
  const double constraint = functional_.dot(x) - value_;
  if (gradient) {
    gradient->resize(n + 1);
    gradient->head(n) = family_gradient + mu * functional_;
    (*gradient)(n) = constraint;
  }
  if (hessian_upper) {
    // The first n columns have H's structure, in the same order; the last holds c and 0.
    double* values = hessian_upper->valuePtr();
    const Eigen::Index h = family_hessian.nonZeros();
    std::copy(family_hessian.valuePtr(), family_hessian.valuePtr() + h, values);
    Eigen::Index k = h;
    for (Eigen::SparseMatrix<double>::InnerIterator it(*hessian_upper, n); it; ++it, ++k)
      values[k] = it.row() < n ? functional_(it.row()) : 0.0;
  }
  return energy + mu * constraint;
}

Eigen::VectorXd PhaseConditionedFamily::gradient_parameter_derivative(
    const Eigen::Ref<const Eigen::VectorXd>& z, double lambda) const {
  const Eigen::Index n = family_.dimension();
  Eigen::VectorXd d(n + 1);
  d.head(n) = family_.gradient_parameter_derivative(z.head(n), lambda);
  d(n) = 0.0;
  return d;
}

double phase_multiplier(const Eigen::Ref<const Eigen::VectorXd>& gradient,
                        const Eigen::Ref<const Eigen::VectorXd>& functional,
                        const std::vector<Eigen::Index>& fixed_dofs) {
  if (gradient.size() != functional.size())
    throw std::invalid_argument("phase_multiplier: the gradient has " +
                                std::to_string(gradient.size()) + " entries, the functional " +
                                std::to_string(functional.size()));
  Eigen::VectorXd c = functional;
  for (const Eigen::Index d : fixed_dofs)
    if (d >= 0 && d < c.size()) c(d) = 0.0;
  const double norm2 = c.squaredNorm();
  if (!(norm2 > 0.0))
    throw std::invalid_argument("phase_multiplier: the functional vanishes on the free unknowns");
  return -c.dot(gradient) / norm2;
}

}  // namespace growshell
