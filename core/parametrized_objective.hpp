#pragma once
/// \file
/// A one-parameter family of energies E(x; lambda), the input of continuation.

#include <Eigen/Core>

#include "core/sparse_objective.hpp"

namespace growshell {

/// E(x; lambda) with the SparseObjective interface at the current lambda, plus the parameter
/// and d(gradient)/d(lambda).
class ParametrizedObjective : public SparseObjective {
 public:
  /// Sets lambda for subsequent evaluations.
  virtual void set_parameter(double lambda) = 0;
  virtual double parameter() const = 0;
  /// d(gradient)/d(lambda) at x and the current lambda.
  virtual Eigen::VectorXd gradient_parameter_derivative(const Eigen::Ref<const Eigen::VectorXd>& x) = 0;
};

}  // namespace growshell
