#pragma once
// A random symmetric positive definite matrix with a mesh-like pattern, for the factorisation
// tests: the weighted 2-D grid graph (side x side nodes, 4-neighbour edges plus one diagonal)
// with random-sign edge weights, made strictly diagonally dominant with a random positive
// excess, so that its spectrum is generic (simple) and the orderings matter.

#include <Eigen/SparseCore>
#include <cmath>
#include <random>
#include <vector>

namespace growshell::test_support {

/// The full (both triangles) matrix of side^2 rows from the generator seeded with `seed`.
inline Eigen::SparseMatrix<double> random_spd_full(int side, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> weight(-1.0, 1.0);
  std::uniform_real_distribution<double> excess(0.1, 1.0);
  const int n = side * side;
  std::vector<Eigen::Triplet<double>> t;
  Eigen::VectorXd row_sum = Eigen::VectorXd::Zero(n);
  auto add_edge = [&](int a, int b) {
    const double w = weight(rng);
    t.emplace_back(a, b, w);
    t.emplace_back(b, a, w);
    row_sum[a] += std::abs(w);
    row_sum[b] += std::abs(w);
  };
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      const int v = i * side + j;
      if (j + 1 < side) add_edge(v, v + 1);
      if (i + 1 < side) add_edge(v, v + side);
      if (i + 1 < side && j + 1 < side) add_edge(v, v + side + 1);
    }
  }
  for (int v = 0; v < n; ++v) t.emplace_back(v, v, row_sum[v] + excess(rng));
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

}  // namespace growshell::test_support
