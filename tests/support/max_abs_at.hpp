#pragma once
// The largest |g_d| over a list of indices d, e.g. the gradient at pinned unknowns.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

namespace growshell::test_support {

inline double max_abs_at(const Eigen::VectorXd& g, const std::vector<Eigen::Index>& dofs) {
  double m = 0.0;
  for (const Eigen::Index d : dofs) m = std::max(m, std::abs(g(d)));
  return m;
}

}  // namespace growshell::test_support
