#pragma once
// A reproducible random vector with entries uniform in [-1, 1].

#include <Eigen/Core>
#include <random>

namespace growshell::test_support {

inline Eigen::VectorXd random_vector(Eigen::Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = d(rng);
  return v;
}

}  // namespace growshell::test_support
