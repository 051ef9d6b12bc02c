#pragma once
/// \file
/// The shell energy as a one-parameter family in the excess angle, the input of continuation.

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "core/parametrized_objective.hpp"
#include "libshell/assembly/shell_model.hpp"

namespace growshell {

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
