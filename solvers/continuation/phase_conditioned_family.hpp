#pragma once
/// \file
/// A parametrised energy with one linear phase condition, c . x = b, held by a Lagrange
/// multiplier mu: the unknowns are (x, mu), and the "energy" is the Lagrangian
/// L(x, mu; lambda) = E(x; lambda) + mu (c . x - b), whose stationary points are the states on
/// the hyperplane where the gradient of E is parallel to c, g(x; lambda) = -mu c.
///
/// A continuous symmetry of the problem that the discretisation breaks only slightly (the turn
/// of a fold pattern over a mesh without rotational symmetry) leaves a nearly neutral
/// direction along which the discrete branch can fold or drift for reasons of the mesh alone.
/// A phase condition transverse to that direction fixes the pattern's place on its orbit, as
/// pins fix the rigid motions; mu c is then the force that holds it there, the mesh's share of
/// the equilibrium, which vanishes where the discretisation has the symmetry. The Hessian of L,
/// [[H, c], [c^T, 0]], has one negative eigenvalue more than H restricted to the hyperplane
/// c . dx = 0 (and one positive more).

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "core/parametrized_objective.hpp"

namespace growshell {

/// Holds a reference: `family` must outlive it.
class PhaseConditionedFamily final : public ParametrizedObjective {
 public:
  /// `functional` c (one entry per unknown of `family`, not all zero, finite) and the value b
  /// it is held at. Throws std::invalid_argument otherwise.
  PhaseConditionedFamily(const ParametrizedObjective& family, Eigen::VectorXd functional,
                         double value);

  /// n + 1: the family's unknowns, then the multiplier mu.
  Eigen::Index dimension() const override { return family_.dimension() + 1; }
  /// H's pattern, plus the last column: the nonzeros of c and the diagonal (n, n).
  Eigen::SparseMatrix<double> hessian_pattern() const override { return pattern_; }
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& z, double lambda,
                  Eigen::VectorXd* gradient,
                  Eigen::SparseMatrix<double>* hessian_upper) const override;
  bool accepts_parameter(double lambda) const override { return family_.accepts_parameter(lambda); }
  /// (d g / d lambda, 0).
  Eigen::VectorXd gradient_parameter_derivative(const Eigen::Ref<const Eigen::VectorXd>& z,
                                                double lambda) const override;

  const Eigen::VectorXd& functional() const { return functional_; }
  double value() const { return value_; }

 private:
  const ParametrizedObjective& family_;
  Eigen::VectorXd functional_;
  double value_;
  Eigen::SparseMatrix<double> pattern_;
};

/// The multiplier mu that best balances the gradient g of the unconstrained energy at a state
/// on the hyperplane, over the free unknowns (those not in `fixed_dofs`, whose gradient
/// entries are the pins' reactions): mu = -(c_f . g_f) / (c_f . c_f). At a converged point of
/// a phase-conditioned trace this is the multiplier the trace solved for. Throws
/// std::invalid_argument for mismatched sizes or a functional that vanishes on the free dofs.
double phase_multiplier(const Eigen::Ref<const Eigen::VectorXd>& gradient,
                        const Eigen::Ref<const Eigen::VectorXd>& functional,
                        const std::vector<Eigen::Index>& fixed_dofs);

}  // namespace growshell
