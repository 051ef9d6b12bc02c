#include "solvers/stability/symmetric_indefinite_factorization.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "solvers/newton/cholmod_factorization.hpp"
#include "tests/support/count_below.hpp"
#include "tests/support/random_spd_grid.hpp"
#include "tests/support/random_vector.hpp"
#include "tests/support/scientific.hpp"
#include "tests/support/sparse_upper.hpp"

namespace growshell {
namespace {

using SpMat = Eigen::SparseMatrix<double>;
using Triplets = std::vector<Eigen::Triplet<double>>;
using test_support::count_below;
using test_support::random_spd_full;
using test_support::random_vector;
using test_support::scientific;

// Edges of a side x side grid (4-neighbours plus one diagonal): mesh-like sparsity, so that
// the ordering and the elimination tree are those of a 2-D problem.
std::vector<std::pair<int, int>> grid_edges(int side) {
  std::vector<std::pair<int, int>> edges;
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      const int v = i * side + j;
      if (j + 1 < side) edges.emplace_back(v, v + 1);
      if (i + 1 < side) edges.emplace_back(v, v + side);
      if (i + 1 < side && j + 1 < side) edges.emplace_back(v, v + side + 1);
    }
  }
  return edges;
}

// A matrix with the 4-fold rotational symmetry of a ring of four identical random patches:
// block circulant with diagonal block B (a random patch) and coupling C from each patch to the
// next (right edge of one to left edge of the next, plus a few random long-range couplings so
// that C is generic and not symmetric). A commutes with the cyclic shift P of the patches; on
// P's eigenspaces for the eigenvalues i and -i it acts as the Hermitian B + iC - iC^T and its
// complex conjugate, which share their eigenvalues: about half the spectrum of A consists of
// exact double eigenvalues, as for symmetric shells. Diagonally dominant, hence SPD.
SpMat c4_symmetric_spd_full(int side, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> weight(-1.0, 1.0);
  std::uniform_real_distribution<double> excess(0.1, 1.0);
  std::uniform_int_distribution<int> node(0, side * side - 1);
  const int m = side * side;
  Triplets patch;     // B, upper and lower
  Triplets coupling;  // C: (row in patch k, column in patch k + 1)
  for (const auto& [a, b] : grid_edges(side)) {
    const double w = weight(rng);
    patch.emplace_back(a, b, w);
    patch.emplace_back(b, a, w);
  }
  for (int i = 0; i < side; ++i) coupling.emplace_back(i * side + side - 1, i * side, weight(rng));
  for (int k = 0; k < side; ++k) coupling.emplace_back(node(rng), node(rng), weight(rng));
  // Every patch node has the same absolute off-diagonal row sum in every copy.
  Eigen::VectorXd row_sum = Eigen::VectorXd::Zero(m);
  for (const auto& e : patch) row_sum[e.row()] += std::abs(e.value());
  for (const auto& e : coupling) {
    row_sum[e.row()] += std::abs(e.value());  // C block of the row
    row_sum[e.col()] += std::abs(e.value());  // C^T block of the row
  }
  Eigen::VectorXd diagonal(m);
  for (int v = 0; v < m; ++v) diagonal[v] = row_sum[v] + excess(rng);

  const int n = 4 * m;
  Triplets t;
  for (int k = 0; k < 4; ++k) {
    const int self = k * m;
    const int next = ((k + 1) % 4) * m;
    for (const auto& e : patch) t.emplace_back(self + e.row(), self + e.col(), e.value());
    for (const auto& e : coupling) {
      t.emplace_back(self + e.row(), next + e.col(), e.value());
      t.emplace_back(next + e.col(), self + e.row(), e.value());
    }
    for (int v = 0; v < m; ++v) t.emplace_back(self + v, self + v, diagonal[v]);
  }
  SpMat a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

// Graph Laplacian of the grid with random positive weights: symmetric positive semidefinite,
// singular with the constant null vector, and non-integer entries, so that its pivots are zero
// only up to round-off.
SpMat weighted_laplacian_full(int side, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> weight(0.1, 1.0);
  const int n = side * side;
  Triplets t;
  for (const auto& [a, b] : grid_edges(side)) {
    const double w = weight(rng);
    t.emplace_back(a, b, -w);
    t.emplace_back(b, a, -w);
    t.emplace_back(a, a, w);
    t.emplace_back(b, b, w);
  }
  SpMat a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

SpMat block_diagonal(const SpMat& a, const SpMat& b) {
  Triplets t;
  for (int col = 0; col < a.outerSize(); ++col) {
    for (SpMat::InnerIterator it(a, col); it; ++it) t.emplace_back(it.row(), it.col(), it.value());
  }
  const auto offset = static_cast<int>(a.rows());
  for (int col = 0; col < b.outerSize(); ++col) {
    for (SpMat::InnerIterator it(b, col); it; ++it) {
      t.emplace_back(offset + it.row(), offset + it.col(), it.value());
    }
  }
  SpMat m(a.rows() + b.rows(), a.cols() + b.cols());
  m.setFromTriplets(t.begin(), t.end());
  return m;
}

using test_support::upper_of;

// A - sigma*I on the pattern of `upper` (which stores every diagonal entry).
SpMat shifted(const SpMat& upper, double sigma) {
  SpMat s = upper;  // NOLINT(performance-unnecessary-copy-initialization): written below
  for (int col = 0; col < s.outerSize(); ++col) {
    for (SpMat::InnerIterator it(s, col); it; ++it) {
      if (it.row() == it.col()) it.valueRef() -= sigma;
    }
  }
  return s;
}

Eigen::VectorXd eigenvalues(const SpMat& full) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Eigen::MatrixXd(full), Eigen::EigenvaluesOnly);
  EXPECT_EQ(eig.info(), Eigen::Success);
  return eig.eigenvalues();  // ascending
}

double distance_to_spectrum(const Eigen::VectorXd& lambda, double sigma) {
  return (lambda.array() - sigma).abs().minCoeff();
}

// The inertia of A - sigma*I is exact as long as the backward error of the LDL^T
// factorisation, a modest multiple of eps * ||A|| ~ 1e-15 for these O(10) matrices, cannot
// move an eigenvalue across sigma. Shifts are therefore kept at least this far from the
// spectrum, a margin of ~1e6 over the backward error.
constexpr double kMinShiftDistance = 1e-8;

// Eigenvalues closer than this (relative to ||A|| ~ 10) belong to one (multiple) eigenvalue:
// the exact double eigenvalues of the symmetric matrix differ only by round-off (~1e-13),
// while distinct eigenvalues of these 500 x 500 matrices are ~1e-2 apart on average.
constexpr double kClusterTolerance = 1e-9;

TEST(SymmetricIndefiniteFactorization, InertiaMatchesDenseCountOnRandomSparseMatrix) {
  const SpMat full = random_spd_full(22, 7);  // n = 484
  const SpMat upper = upper_of(full);
  const Eigen::VectorXd lambda = eigenvalues(full);
  const auto n = static_cast<int>(lambda.size());

  // Midpoints between consecutive eigenvalues, from below the spectrum to above it, plus
  // random shifts anywhere in it.
  std::vector<double> sigmas = {lambda[0] - 1.0, lambda[n - 1] + 1.0};
  for (int k : {0, 1, 2, 50, 120, 241, 242, 300, 420, 481, 482}) {
    sigmas.push_back(0.5 * (lambda[k] + lambda[k + 1]));
  }
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> anywhere(lambda[0], lambda[n - 1]);
  for (int i = 0; i < 20; ++i) sigmas.push_back(anywhere(rng));

  SymmetricIndefiniteFactorization ldlt;
  ldlt.analyze(shifted(upper, sigmas.front()));
  EXPECT_EQ(ldlt.rows(), n);
  double min_distance = 1e300;
  for (double sigma : sigmas) {
    const double distance = distance_to_spectrum(lambda, sigma);
    ASSERT_GT(distance, kMinShiftDistance) << "shift " << sigma << " too close to the spectrum";
    min_distance = std::min(min_distance, distance);
    ldlt.factorize(shifted(upper, sigma));
    EXPECT_EQ(ldlt.negative_eigenvalues(), count_below(lambda, sigma)) << "shift " << sigma;
    EXPECT_EQ(ldlt.zero_pivots(), 0) << "shift " << sigma;
  }
  RecordProperty("min_distance_shift_to_spectrum", scientific(min_distance));
}

TEST(SymmetricIndefiniteFactorization, InertiaCountsDoubleEigenvaluesOfSymmetricMatrix) {
  const SpMat full = c4_symmetric_spd_full(11, 5);  // n = 4 * 121 = 484
  const SpMat upper = upper_of(full);
  const Eigen::VectorXd lambda = eigenvalues(full);
  const auto n = static_cast<int>(lambda.size());

  // Group the spectrum into clusters of equal eigenvalues; premise: the symmetry makes
  // 121 exact pairs (the P-eigenspaces for i and -i each hold 121 eigenvalues).
  std::vector<int> cluster_end;  // one past the last index of each cluster
  for (int i = 1; i <= n; ++i) {
    if (i == n || lambda[i] - lambda[i - 1] > kClusterTolerance) cluster_end.push_back(i);
  }
  int pairs = 0;
  int largest_cluster = 1;
  double max_pair_split = 0.0;
  for (size_t c = 0; c < cluster_end.size(); ++c) {
    const int first = c == 0 ? 0 : cluster_end[c - 1];
    const int size = cluster_end[c] - first;
    if (size == 2) {
      ++pairs;
      max_pair_split = std::max(max_pair_split, lambda[first + 1] - lambda[first]);
    }
    largest_cluster = std::max(largest_cluster, size);
  }
  ASSERT_EQ(pairs, 121);
  ASSERT_EQ(largest_cluster, 2);
  RecordProperty("double_eigenvalues", pairs);
  RecordProperty("max_split_within_pair", scientific(max_pair_split));

  // Every gap between clusters, and just below and above every double eigenvalue: a pair
  // crossing the shift changes the count by two (and the determinant's sign not at all).
  SymmetricIndefiniteFactorization ldlt;
  ldlt.analyze(upper);
  int pair_crossings = 0;
  double min_distance = 1e300;
  for (size_t c = 0; c + 1 < cluster_end.size(); ++c) {
    const int below = cluster_end[c];  // eigenvalues in clusters 0..c
    const double sigma = 0.5 * (lambda[below - 1] + lambda[below]);
    const double distance = distance_to_spectrum(lambda, sigma);
    ASSERT_GT(distance, kMinShiftDistance);
    min_distance = std::min(min_distance, distance);
    ldlt.factorize(shifted(upper, sigma));
    ASSERT_EQ(ldlt.negative_eigenvalues(), below) << "shift " << sigma;
    ASSERT_EQ(ldlt.zero_pivots(), 0);

    const int first = c == 0 ? 0 : cluster_end[c - 1];
    if (below - first == 2) {
      // Shifts a distance `delta` either side of the pair, well inside the neighbouring gaps.
      const double gap_below = first == 0 ? 1.0 : lambda[first] - lambda[first - 1];
      const double delta = 0.25 * std::min(gap_below, lambda[below] - lambda[below - 1]);
      ASSERT_GT(delta, kMinShiftDistance);
      ldlt.factorize(shifted(upper, lambda[first] - delta));
      const int before = ldlt.negative_eigenvalues();
      ldlt.factorize(shifted(upper, lambda[first] + delta));
      const int after = ldlt.negative_eigenvalues();
      EXPECT_EQ(before, first);
      EXPECT_EQ(after - before, 2) << "double eigenvalue " << lambda[first];
      ++pair_crossings;
    }
  }
  EXPECT_EQ(pair_crossings, 121);
  RecordProperty("min_distance_shift_to_spectrum", scientific(min_distance));
}

TEST(SymmetricIndefiniteFactorization, SolveMatchesDenseSolveOnIndefiniteMatrices) {
  for (const bool symmetric : {false, true}) {
    const SpMat full = symmetric ? c4_symmetric_spd_full(11, 9) : random_spd_full(22, 13);
    const SpMat upper = upper_of(full);
    const Eigen::VectorXd lambda = eigenvalues(full);
    const auto n = static_cast<int>(lambda.size());
    // The widest gap in the middle half of the spectrum: about half the eigenvalues negative.
    int k = n / 4;
    for (int i = n / 4; i < 3 * n / 4; ++i) {
      if (lambda[i + 1] - lambda[i] > lambda[k + 1] - lambda[k]) k = i;
    }
    const double sigma = 0.5 * (lambda[k] + lambda[k + 1]);
    const SpMat a_upper = shifted(upper, sigma);
    SpMat identity(n, n);
    identity.setIdentity();
    const Eigen::MatrixXd a_dense = Eigen::MatrixXd(full - sigma * identity);
    const double condition =
        (lambda.array() - sigma).abs().maxCoeff() / (lambda.array() - sigma).abs().minCoeff();
    // Both solvers are backward stable; the forward error is at most ~cond * eps * (a modest
    // growth factor). With cond below 1e4 that is ~1e-12, leaving a margin of ~1e2 to 1e-10.
    ASSERT_LT(condition, 1e4);

    SymmetricIndefiniteFactorization ldlt;
    ldlt.analyze(a_upper);
    ldlt.factorize(a_upper);
    EXPECT_EQ(ldlt.negative_eigenvalues(), k + 1);
    const Eigen::VectorXd b = random_vector(n, 17);
    const Eigen::VectorXd x = ldlt.solve(b);
    const Eigen::VectorXd x_dense = a_dense.partialPivLu().solve(b);
    const double error = (x - x_dense).norm() / x_dense.norm();
    EXPECT_LT(error, 1e-10);
    EXPECT_LT((a_dense * x - b).norm() / b.norm(), 1e-12);
    const std::string which = symmetric ? "c4_" : "random_";
    RecordProperty(which + "condition_number", scientific(condition));
    RecordProperty(which + "relative_difference_to_dense", scientific(error));
  }
}

TEST(SymmetricIndefiniteFactorization, SingularMatrixHasNullPivotsAndSolveThrows) {
  const SpMat laplacian = weighted_laplacian_full(22, 3);  // connected: nullity 1
  const Eigen::VectorXd lambda = eigenvalues(laplacian);
  // Premise: one eigenvalue zero up to round-off, the next clearly positive.
  ASSERT_LT(std::abs(lambda[0]), 1e-12);
  ASSERT_GT(lambda[1], 1e-3);
  RecordProperty("laplacian_lambda_0", scientific(lambda[0]));
  RecordProperty("laplacian_lambda_1", scientific(lambda[1]));

  SymmetricIndefiniteFactorization ldlt;
  const SpMat upper = upper_of(laplacian);
  ldlt.analyze(upper);
  ldlt.factorize(upper);
  EXPECT_EQ(ldlt.zero_pivots(), 1);
  EXPECT_EQ(ldlt.negative_eigenvalues(), 0);
  // Documented behaviour: no solve with a singular factor, even for a consistent system
  // (b = A v), since MUMPS cannot tell whether a right-hand side is consistent.
  const Eigen::VectorXd b = laplacian * random_vector(laplacian.rows(), 5);
  EXPECT_THROW(ldlt.solve(b), std::runtime_error);

  // The same pattern shifted off the spectrum is regular again: the null pivot was A's.
  ldlt.factorize(shifted(upper, 0.5 * lambda[1]));
  EXPECT_EQ(ldlt.zero_pivots(), 0);
  EXPECT_EQ(ldlt.negative_eigenvalues(), 1);
  EXPECT_NO_THROW(ldlt.solve(b));

  // Two disconnected copies: nullity 2.
  const SpMat two = upper_of(block_diagonal(laplacian, weighted_laplacian_full(15, 4)));
  SymmetricIndefiniteFactorization ldlt2;
  ldlt2.analyze(two);
  ldlt2.factorize(two);
  EXPECT_EQ(ldlt2.zero_pivots(), 2);
  EXPECT_EQ(ldlt2.negative_eigenvalues(), 0);

  // Singular and indefinite: the null pivot is not counted as negative, whatever its sign.
  const SpMat negative_block = -random_spd_full(12, 21);  // 144 negative eigenvalues
  const SpMat mixed = upper_of(block_diagonal(laplacian, negative_block));
  SymmetricIndefiniteFactorization ldlt3;
  ldlt3.analyze(mixed);
  ldlt3.factorize(mixed);
  EXPECT_EQ(ldlt3.zero_pivots(), 1);
  EXPECT_EQ(ldlt3.negative_eigenvalues(), 144);
}

TEST(SymmetricIndefiniteFactorization, RefactorizationWithNewValuesReusesAnalysis) {
  const SpMat full = random_spd_full(20, 29);
  const SpMat upper = upper_of(full);
  const Eigen::VectorXd lambda = eigenvalues(full);
  const Eigen::VectorXd b = random_vector(full.rows(), 31);
  SymmetricIndefiniteFactorization reused;
  reused.analyze(upper);  // analysed once, on the SPD matrix
  for (int k : {10, 150, 300, 398}) {
    const double sigma = 0.5 * (lambda[k] + lambda[k + 1]);
    const SpMat a = shifted(upper, sigma);
    reused.factorize(a);
    SymmetricIndefiniteFactorization fresh;
    fresh.analyze(a);
    fresh.factorize(a);
    EXPECT_EQ(reused.negative_eigenvalues(), k + 1);
    EXPECT_EQ(fresh.negative_eigenvalues(), k + 1);
    const Eigen::VectorXd x_reused = reused.solve(b);
    const Eigen::VectorXd x_fresh = fresh.solve(b);
    // Same kind of bound as in SolveMatchesDenseSolve; these shifts are not the widest gaps,
    // so allow for condition numbers up to ~1e5.
    EXPECT_LT((x_reused - x_fresh).norm() / x_fresh.norm(), 1e-9) << "shift " << sigma;
  }

  // A different pattern is rejected, and leaves no factor behind.
  SpMat extra = upper;
  extra.coeffRef(0, 300) = 0.01;
  extra.makeCompressed();
  EXPECT_THROW(reused.factorize(extra), std::runtime_error);
  EXPECT_THROW(reused.negative_eigenvalues(), std::logic_error);
  EXPECT_THROW(reused.factorize(upper_of(random_spd_full(21, 29))), std::runtime_error);
  reused.factorize(upper);
  EXPECT_EQ(reused.negative_eigenvalues(), 0);
}

TEST(SymmetricIndefiniteFactorization, OrderingsGiveTheSameInertia) {
  const SpMat full = random_spd_full(22, 37);
  const SpMat upper = upper_of(full);
  const Eigen::VectorXd lambda = eigenvalues(full);
  const double sigma = 0.5 * (lambda[199] + lambda[200]);
  const SpMat a = shifted(upper, sigma);
  for (IndefiniteOrdering ordering : {IndefiniteOrdering::Automatic, IndefiniteOrdering::Amd,
                                      IndefiniteOrdering::Scotch, IndefiniteOrdering::Metis}) {
    SymmetricIndefiniteFactorization ldlt({ordering, 0.0});
    ldlt.analyze(a);
    ldlt.factorize(a);
    EXPECT_EQ(ldlt.negative_eigenvalues(), 200);
    const std::string used = ldlt.ordering_used();
    if (ordering == IndefiniteOrdering::Amd) {
      EXPECT_EQ(used, "AMD");
    }
    if (ordering == IndefiniteOrdering::Scotch) {
      EXPECT_EQ(used, "SCOTCH");
    }
    RecordProperty("ordering_used_" + std::to_string(static_cast<int>(ordering)), used);
  }
}

TEST(SymmetricIndefiniteFactorization, PositiveDefiniteExactlyWhenCholmodSucceeds) {
  const SpMat full = random_spd_full(22, 41);
  const SpMat upper = upper_of(full);
  const Eigen::VectorXd lambda = eigenvalues(full);
  const auto n = static_cast<int>(lambda.size());
  // Shifts from well below the spectrum to just either side of the smallest eigenvalue and
  // into the interior: the definite/indefinite boundary is lambda[0].
  const double gap = lambda[1] - lambda[0];
  const std::vector<double> sigmas = {lambda[0] - 10.0,           lambda[0] - 1e-3 * gap,
                                      lambda[0] - 1e-6 * gap,     lambda[0] + 1e-6 * gap,
                                      lambda[0] + 1e-3 * gap,     0.5 * (lambda[0] + lambda[1]),
                                      lambda[n / 2] + 1e-3 * gap, lambda[n - 1] + 1.0};
  SymmetricIndefiniteFactorization ldlt;
  CholmodFactorization chol;
  ldlt.analyze(upper);
  chol.analyze(upper);
  int definite = 0;
  for (double sigma : sigmas) {
    ASSERT_GT(distance_to_spectrum(lambda, sigma), kMinShiftDistance);
    const SpMat a = shifted(upper, sigma);
    ldlt.factorize(a);
    const bool ldlt_definite = ldlt.negative_eigenvalues() == 0 && ldlt.zero_pivots() == 0;
    EXPECT_EQ(chol.factorize(a).positive_definite, ldlt_definite) << "shift " << sigma;
    EXPECT_EQ(ldlt_definite, sigma < lambda[0]) << "shift " << sigma;
    definite += ldlt_definite ? 1 : 0;
  }
  EXPECT_EQ(definite, 3);
  RecordProperty("smallest_distance_to_lambda_min", scientific(1e-6 * gap));
}

TEST(SymmetricIndefiniteFactorization, InvalidUseThrows) {
  EXPECT_THROW(SymmetricIndefiniteFactorization({IndefiniteOrdering::Automatic, -1.0}),
               std::invalid_argument);
  const SpMat full = random_spd_full(5, 1);
  const SpMat upper = upper_of(full);
  SymmetricIndefiniteFactorization ldlt;
  EXPECT_EQ(ldlt.rows(), 0);
  EXPECT_THROW(ldlt.factorize(upper), std::logic_error);
  EXPECT_THROW(ldlt.ordering_used(), std::logic_error);
  SpMat full_compressed = full;
  full_compressed.makeCompressed();
  EXPECT_THROW(ldlt.analyze(full_compressed), std::invalid_argument);  // has a lower triangle
  EXPECT_THROW(ldlt.analyze(SpMat(3, 4)), std::invalid_argument);
  EXPECT_THROW(ldlt.analyze(SpMat(0, 0)), std::invalid_argument);
  ldlt.analyze(upper);
  EXPECT_THROW(ldlt.negative_eigenvalues(), std::logic_error);
  EXPECT_THROW(ldlt.zero_pivots(), std::logic_error);
  EXPECT_THROW(ldlt.solve(Eigen::VectorXd::Ones(25)), std::logic_error);
  SpMat bad = upper;
  bad.coeffRef(3, 3) = std::nan("");
  EXPECT_THROW(ldlt.factorize(bad), std::invalid_argument);
  ldlt.factorize(upper);
  EXPECT_THROW(ldlt.solve(Eigen::VectorXd::Ones(24)), std::invalid_argument);

  // Moving transfers the factor; the moved-from object reports misuse instead of crashing.
  SymmetricIndefiniteFactorization moved = std::move(ldlt);
  EXPECT_EQ(moved.rows(), 25);
  EXPECT_EQ(moved.negative_eigenvalues(), 0);
  EXPECT_LT((full * moved.solve(Eigen::VectorXd::Ones(25)) - Eigen::VectorXd::Ones(25)).norm(),
            1e-12);
  EXPECT_EQ(ldlt.rows(), 0);  // NOLINT(bugprone-use-after-move): documented state
  EXPECT_THROW(ldlt.factorize(upper), std::logic_error);
}

}  // namespace
}  // namespace growshell
