#pragma once
// The number of entries of a vector (e.g. eigenvalues) strictly below a value.

#include <Eigen/Core>

namespace growshell::test_support {

inline int count_below(const Eigen::VectorXd& values, double bound) {
  return static_cast<int>((values.array() < bound).count());
}

}  // namespace growshell::test_support
