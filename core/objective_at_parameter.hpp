#pragma once
/// \file
/// One member of a parametrised family, E(.; lambda) at a fixed lambda, as the SparseObjective
/// that a Newton solver minimises.

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "core/parametrized_objective.hpp"
#include "core/sparse_objective.hpp"

namespace growshell {

/// The member E(.; lambda) of a family at one fixed lambda, as a SparseObjective. Holds a
/// reference: `family` must outlive it.
class ObjectiveAtParameter final : public SparseObjective {
 public:
  ObjectiveAtParameter(const ParametrizedObjective& family, double lambda)
      : family_(family), lambda_(lambda) {}

  Eigen::Index dimension() const override { return family_.dimension(); }
  Eigen::SparseMatrix<double> hessian_pattern() const override { return family_.hessian_pattern(); }
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd* gradient,
                  Eigen::SparseMatrix<double>* hessian_upper) override {
    return family_.evaluate(x, lambda_, gradient, hessian_upper);
  }

  double parameter() const { return lambda_; }
  const ParametrizedObjective& family() const { return family_; }

 private:
  const ParametrizedObjective& family_;
  double lambda_;
};

}  // namespace growshell
