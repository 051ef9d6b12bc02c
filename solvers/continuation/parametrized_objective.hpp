#pragma once
/// \file
/// A one-parameter family of energies E(x; lambda), the input of continuation.

#include <Eigen/Core>

#include "libshell/assembly/shell_model.hpp"
#include "solvers/newton/sparse_objective.hpp"

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

/// The shell energy as a family in the excess angle phi_e (radians). Holds a reference to the
/// model, which must outlive it.
class ShellGrowthFamily final : public ParametrizedObjective {
 public:
  explicit ShellGrowthFamily(ShellModel& model) : model_(model) {}
  Eigen::Index dimension() const override { return model_.dimension(); }
  Eigen::SparseMatrix<double> hessian_pattern() const override { return model_.hessian_pattern(); }
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd* gradient,
                  Eigen::SparseMatrix<double>* hessian_upper) override {
    return model_.evaluate(x, gradient, hessian_upper);
  }
  void set_parameter(double lambda) override { model_.set_excess_angle(lambda); }
  double parameter() const override { return model_.excess_angle(); }
  Eigen::VectorXd gradient_parameter_derivative(const Eigen::Ref<const Eigen::VectorXd>& x) override {
    return model_.gradient_excess_angle_derivative(x);
  }

 private:
  ShellModel& model_;
};

}  // namespace growshell
