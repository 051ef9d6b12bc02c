// lowest_mass_normalized_eigenpairs: the generalised problem H v = lambda M v with a diagonal
// mass, against Eigen's dense generalised solver; M-orthonormal vectors, zero at fixed dofs; the
// count of negative eigenvalues is H's; bad masses are named.
#include "solvers/stability/mass_normalized_eigenpairs.hpp"
#include "tests/support/sparse_upper.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace growshell {
namespace {

using SpMat = Eigen::SparseMatrix<double>;

// A sparse symmetric matrix with 3 negative eigenvalues: a random banded symmetric part plus a
// diagonal, on n dofs.
SpMat banded_symmetric(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, i < 3 ? -2.0 - i : 4.0 + 0.1 * i);
    for (int k = 1; k <= 2 && i + k < n; ++k) {
      const double w = 0.3 * normal(rng);
      t.emplace_back(i, i + k, w);
      t.emplace_back(i + k, i, w);
    }
  }
  SpMat a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

using test_support::upper_of;

TEST(MassNormalizedEigenpairs, AgreeWithTheDenseGeneralisedSolver) {
  const int n = 60;
  const SpMat H = banded_symmetric(n, 3);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> mass(0.01, 5.0);  // masses spread over 2.7 decades
  Eigen::VectorXd m(n);
  for (int i = 0; i < n; ++i) m(i) = mass(rng);
  const std::vector<Eigen::Index> fixed = {10, 41};
  // Dense reference on the free block.
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < n; ++i)
    if (std::find(fixed.begin(), fixed.end(), i) == fixed.end()) keep.push_back(i);
  const Eigen::MatrixXd dense(H);
  const auto k = static_cast<Eigen::Index>(keep.size());
  Eigen::MatrixXd A(k, k);
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(k, k);
  for (Eigen::Index a = 0; a < k; ++a) {
    B(a, a) = m(keep[static_cast<std::size_t>(a)]);
    for (Eigen::Index b = 0; b < k; ++b)
      A(a, b) = dense(keep[static_cast<std::size_t>(a)], keep[static_cast<std::size_t>(b)]);
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> reference(A, B);
  ASSERT_EQ(reference.info(), Eigen::Success);

  EigenpairOptions options;
  options.count = 5;
  options.block_size = 16;  // eigenvalues 5 and 6 of this draw are close: a wider block
  const Eigenpairs pairs = lowest_mass_normalized_eigenpairs_of_matrix(upper_of(H), m, fixed, options);
  ASSERT_TRUE(pairs.converged) << pairs.message << " values " << pairs.values.transpose();
  ASSERT_EQ(pairs.values.size(), 5);
  for (int j = 0; j < 5; ++j) {
    // Residual tolerance 1e-10 of the scaled matrix's norm (entries up to 5 / 0.01: ||DHD|| of
    // O(1e3)): eigenvalue errors below 1e-7.
    EXPECT_NEAR(pairs.values(j), reference.eigenvalues()(j), 1e-7)
        << "eigenvalue " << j;
  }
  EXPECT_LT(pairs.values(2), 0.0);  // three negative pivots of H, three negative eigenvalues
  EXPECT_GT(pairs.values(3), 0.0);
  // M-orthonormal, zero at the fixed dofs, and H v = lambda M v.
  const Eigen::MatrixXd gram = pairs.vectors.transpose() * m.asDiagonal() * pairs.vectors;
  EXPECT_LT((gram - Eigen::MatrixXd::Identity(5, 5)).cwiseAbs().maxCoeff(), 1e-10);
  for (const Eigen::Index d : fixed) EXPECT_EQ(pairs.vectors.row(d).cwiseAbs().maxCoeff(), 0.0);
  for (int j = 0; j < 5; ++j) {
    Eigen::VectorXd r = dense * pairs.vectors.col(j) - pairs.values(j) * m.cwiseProduct(pairs.vectors.col(j));
    for (const Eigen::Index d : fixed) r(d) = 0.0;  // the fixed rows are not equations
    // r = D^-1 (D H D w - lambda w): the scaled residual (< 1e-7) times sqrt(m) <= 2.3.
    EXPECT_LT(r.norm(), 3e-7) << "pair " << j;
  }
}

TEST(MassNormalizedEigenpairs, UnitMassIsTheStandardProblem) {
  const SpMat H = banded_symmetric(40, 11);
  EigenpairOptions options;
  options.count = 4;
  const Eigenpairs plain = lowest_eigenpairs_of_matrix(upper_of(H), {}, options);
  const Eigenpairs unit =
      lowest_mass_normalized_eigenpairs_of_matrix(upper_of(H), Eigen::VectorXd::Ones(40), {}, options);
  EXPECT_EQ(plain.values, unit.values);
}

TEST(MassNormalizedEigenpairs, RejectsMassesThatAreNotPositive) {
  const SpMat H = upper_of(banded_symmetric(12, 1));
  Eigen::VectorXd m = Eigen::VectorXd::Ones(12);
  m(5) = 0.0;
  try {
    lowest_mass_normalized_eigenpairs_of_matrix(H, m, {});
    FAIL() << "a zero mass was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("the mass of free dof 5 is 0"), std::string::npos) << e.what();
  }
  // A fixed dof may have any mass.
  EXPECT_NO_THROW(lowest_mass_normalized_eigenpairs_of_matrix(H, m, {5}));
  try {
    lowest_mass_normalized_eigenpairs_of_matrix(H, Eigen::VectorXd::Ones(11), {});
    FAIL() << "a mass vector of the wrong size was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("dof_mass has 11 entries, the matrix 12 rows"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace growshell
