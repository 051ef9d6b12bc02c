#pragma once
/// \file
/// The shell energy plus the contact penalty as a one-parameter family in the excess angle,
/// so that pseudo-arclength continuation can follow a branch through self-contact, also where
/// it is unstable.

#include <Eigen/Core>

#include "core/parametrized_objective.hpp"
#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_penalty.hpp"

namespace growshell {

/// E(x; phi_e) + P(x) for a ShellModel E and a ContactPenalty P over the same unknowns. P does
/// not depend on phi_e, so d(gradient)/d(phi_e) is the shell's. The Hessian pattern is the
/// union of both, fixed for the object's lifetime (i.e. for one pair set). Holds references:
/// the model and the penalty must outlive it.
class PenalizedGrowthFamily final : public ParametrizedObjective {
 public:
  /// Throws std::invalid_argument as PenalizedEnergy (different dimensions, bad patterns).
  PenalizedGrowthFamily(ShellModel& model, ContactPenalty& penalty)
      : model_(model), energy_(model, penalty) {}
  Eigen::Index dimension() const override { return energy_.dimension(); }
  Eigen::SparseMatrix<double> hessian_pattern() const override { return energy_.hessian_pattern(); }
  /// E + P (J), with summed gradient (N) and Hessian (N/m) on request.
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd* gradient,
                  Eigen::SparseMatrix<double>* hessian_upper) override {
    return energy_.evaluate(x, gradient, hessian_upper);
  }
  void set_parameter(double lambda) override { model_.set_excess_angle(lambda); }
  double parameter() const override { return model_.excess_angle(); }
  Eigen::VectorXd gradient_parameter_derivative(const Eigen::Ref<const Eigen::VectorXd>& x) override {
    return model_.gradient_excess_angle_derivative(x);
  }
  /// P at the last evaluate (J).
  double last_penalty() const { return energy_.last_penalty(); }

 private:
  ShellModel& model_;
  PenalizedEnergy energy_;
};

}  // namespace growshell
