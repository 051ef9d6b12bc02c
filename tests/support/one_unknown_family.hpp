#pragma once
// A parametrised energy of a single unknown, the base of the toy families that continuation
// tests trace: the derived class gives the energy, gradient, Hessian and dg/dlambda.

#include <Eigen/SparseCore>

#include "core/parametrized_objective.hpp"

namespace growshell::test_support {

/// dimension() 1 and a 1x1 Hessian pattern.
class OneUnknownFamily : public ParametrizedObjective {
 public:
  Eigen::Index dimension() const override { return 1; }
  Eigen::SparseMatrix<double> hessian_pattern() const override {
    Eigen::SparseMatrix<double> H(1, 1);
    H.insert(0, 0) = 0.0;
    H.makeCompressed();
    return H;
  }
};

}  // namespace growshell::test_support
