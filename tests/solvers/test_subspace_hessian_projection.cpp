#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "solvers/stability/subspace_hessian_projection.hpp"

namespace growshell {
namespace {

using Sparse = Eigen::SparseMatrix<double>;

/// A random symmetric n x n matrix's upper triangle with about `fill` of its entries stored,
/// the diagonal always.
Sparse random_upper(int n, double fill, std::mt19937& rng) {
  std::uniform_real_distribution<double> value(-1.0, 1.0), coin(0.0, 1.0);
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i <= j; ++i)
      if (i == j || coin(rng) < fill) t.emplace_back(i, j, value(rng));
  Sparse m(n, n);
  m.setFromTriplets(t.begin(), t.end());
  m.makeCompressed();
  return m;
}

/// An orbit-like basis: the rows shuffled and dealt into groups of 1 to 4, each group a column
/// with random signs, normalised; every fifth row is left out (a dof odd under a symmetry that
/// fixes it).
Sparse random_orbit_basis(int n, std::mt19937& rng) {
  std::vector<int> rows(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) rows[static_cast<std::size_t>(i)] = i;
  std::shuffle(rows.begin(), rows.end(), rng);
  std::uniform_int_distribution<int> size(1, 4), sign(0, 1);
  std::vector<Eigen::Triplet<double>> t;
  int column = 0;
  std::size_t k = 0;
  while (k < rows.size()) {
    const auto group = std::min<std::size_t>(static_cast<std::size_t>(size(rng)), rows.size() - k);
    if (rows[k] % 5 == 0) {
      ++k;
      continue;
    }
    const double scale = 1.0 / std::sqrt(static_cast<double>(group));
    for (std::size_t g = 0; g < group; ++g)
      t.emplace_back(rows[k + g], column, (sign(rng) ? 1.0 : -1.0) * scale);
    k += group;
    ++column;
  }
  Sparse q(n, column);
  q.setFromTriplets(t.begin(), t.end());
  q.makeCompressed();
  return q;
}

Eigen::MatrixXd symmetric_dense(const Sparse& upper) {
  return Eigen::MatrixXd(Sparse(upper.selfadjointView<Eigen::Upper>()));
}

TEST(SubspaceHessianProjection, AgreesWithTheDenseProductAndCoversItsStructure) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 5; ++trial) {
    const int n = 40 + 7 * trial;
    const Sparse h = random_upper(n, 0.15, rng);
    const Sparse q = random_orbit_basis(n, rng);
    const SubspaceHessianProjection projection(h, q);
    Sparse projected;  // no structure yet: project() gives it the pattern
    projection.project(h, projected);
    const Eigen::MatrixXd Q(q);
    const Eigen::MatrixXd expected = Q.transpose() * symmetric_dense(h) * Q;
    EXPECT_LT((symmetric_dense(projected) - expected).cwiseAbs().maxCoeff(), 1e-14)
        << "trial " << trial;
    // Every structural nonzero of the product is in the pattern: with all of H's values 1 and
    // |Q|, nothing can cancel.
    Sparse ones = h;
    std::fill(ones.valuePtr(), ones.valuePtr() + ones.nonZeros(), 1.0);
    const Eigen::MatrixXd reach = Eigen::MatrixXd(Sparse(q.cwiseAbs())).transpose() *
                                  symmetric_dense(ones) * Eigen::MatrixXd(Sparse(q.cwiseAbs()));
    const Eigen::MatrixXd in_pattern = symmetric_dense(projection.pattern());
    for (Eigen::Index j = 0; j < reach.cols(); ++j)
      for (Eigen::Index i = 0; i <= j; ++i)
        EXPECT_EQ(reach(i, j) > 0.0, in_pattern(i, j) > 0.0) << i << ", " << j;
    // A second projection into the same matrix overwrites, not accumulates.
    projection.project(h, projected);
    EXPECT_LT((symmetric_dense(projected) - expected).cwiseAbs().maxCoeff(), 1e-14);
  }
}

TEST(SubspaceHessianProjection, OffDiagonalEntriesMeetingOnTheDiagonalCountTwice) {
  // H = [[1, 2], [2, 3]], Q = (1, 1)^T / sqrt(2): Q^T H Q = (1 + 2 * 2 + 3) / 2 = 4.
  Sparse h(2, 2);
  h.insert(0, 0) = 1.0;
  h.insert(0, 1) = 2.0;
  h.insert(1, 1) = 3.0;
  h.makeCompressed();
  Sparse q(2, 1);
  q.insert(0, 0) = std::sqrt(0.5);
  q.insert(1, 0) = std::sqrt(0.5);
  q.makeCompressed();
  Sparse projected;
  SubspaceHessianProjection(h, q).project(h, projected);
  ASSERT_EQ(projected.nonZeros(), 1);
  EXPECT_NEAR(projected.coeff(0, 0), 4.0, 1e-15);
}

TEST(SubspaceHessianProjection, BadInputIsNamed) {
  std::mt19937 rng(3);
  const Sparse h = random_upper(10, 0.3, rng);
  Sparse q(10, 2);
  q.insert(4, 0) = 1.0;
  q.insert(4, 1) = 1.0;  // row 4 in two columns: not an orbit basis
  q.makeCompressed();
  try {
    SubspaceHessianProjection projection(h, q);
    ADD_FAILURE() << "a row with two nonzeros was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("row 4 of the basis"), std::string::npos) << e.what();
  }
  const Sparse good = random_orbit_basis(10, rng);
  EXPECT_THROW(SubspaceHessianProjection(h, Sparse(good.topRows(9))), std::invalid_argument);
  Sparse lower = Sparse(h.transpose());
  lower.makeCompressed();
  EXPECT_THROW(SubspaceHessianProjection(lower, good), std::invalid_argument);
  // A Hessian of another structure than the one the projection was built for.
  const SubspaceHessianProjection projection(h, good);
  Sparse other = random_upper(10, 0.6, rng);
  Sparse projected;
  EXPECT_THROW(projection.project(other, projected), std::invalid_argument);
}

}  // namespace
}  // namespace growshell
