#include "solvers/newton/cholmod_factorization.hpp"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/support/random_spd_grid.hpp"
#include "tests/support/random_vector.hpp"
#include "tests/support/scientific.hpp"
#include "tests/support/sparse_upper.hpp"

namespace growshell {
namespace {

using SpMat = Eigen::SparseMatrix<double>;
using test_support::random_spd_full;
using test_support::random_vector;
using test_support::scientific;

using test_support::upper_of;

Eigen::VectorXd reference_solve(const SpMat& full, const Eigen::VectorXd& b) {
  Eigen::SimplicialLDLT<SpMat> ldlt(full);
  EXPECT_EQ(ldlt.info(), Eigen::Success);
  return ldlt.solve(b);
}

double relative_error(const Eigen::VectorXd& x, const Eigen::VectorXd& ref) {
  return (x - ref).norm() / ref.norm();
}

// The test matrices are diagonally dominant with excess >= 0.1 and row sums <= ~13, so
// their condition number is below ~150; both solvers are backward stable, so a relative
// difference of 1e-10 leaves a margin of ~1e3 over eps * cond.
constexpr double kSolveTolerance = 1e-10;

TEST(CholmodFactorization, MatchesEigenLdltOnRandomSpdMatrix) {
  const SpMat full = random_spd_full(45, 7);  // n = 2025
  const SpMat upper = upper_of(full);
  const Eigen::VectorXd b = random_vector(full.rows(), 11);
  CholmodFactorization chol;
  chol.analyze(upper);
  EXPECT_EQ(chol.rows(), full.rows());
  EXPECT_GT(chol.factor_nonzeros(), static_cast<double>(upper.nonZeros()) - 1.0);
  EXPECT_GT(chol.factorization_flops(), 0.0);
  const FactorizationResult r = chol.factorize(upper);
  ASSERT_TRUE(r.positive_definite);
  EXPECT_EQ(r.failed_column, -1);
  const Eigen::VectorXd x = chol.solve(b);
  const double error = relative_error(x, reference_solve(full, b));
  EXPECT_LT(error, kSolveTolerance);
  EXPECT_LT((full * x - b).norm() / b.norm(), kSolveTolerance);
  RecordProperty("relative_difference_to_ldlt", scientific(error));
}

TEST(CholmodFactorization, IndefiniteMatrixIsReportedNotThrown) {
  SpMat full = random_spd_full(30, 3);
  const int bad = 377;
  // Making one diagonal entry very negative: every principal submatrix avoiding `bad` stays
  // diagonally dominant, so the first non-positive pivot is exactly that column.
  full.coeffRef(bad, bad) = -50.0;
  const SpMat upper = upper_of(full);
  CholmodFactorization chol;
  chol.analyze(upper);
  const FactorizationResult r = chol.factorize(upper);
  EXPECT_FALSE(r.positive_definite);
  EXPECT_EQ(r.failed_column, bad);
  EXPECT_THROW(chol.solve(Eigen::VectorXd::Ones(full.rows())), std::logic_error);
}

TEST(CholmodFactorization, ShiftFactorizesAPlusShiftIdentity) {
  const SpMat full = random_spd_full(30, 5);
  const SpMat upper = upper_of(full);
  const Eigen::VectorXd b = random_vector(full.rows(), 13);
  CholmodFactorization chol;
  chol.analyze(upper);
  const double shift = 2.5;
  ASSERT_TRUE(chol.factorize(upper, shift).positive_definite);
  SpMat identity(full.rows(), full.cols());
  identity.setIdentity();
  const SpMat shifted = full + shift * identity;
  const Eigen::VectorXd x = chol.solve(b);
  EXPECT_LT(relative_error(x, reference_solve(shifted, b)), kSolveTolerance);
  // Without the shift the solution is measurably different, so the shift was applied.
  EXPECT_GT(relative_error(x, reference_solve(full, b)), 1e-2);

  // A shift turns an indefinite matrix into a definite one.
  SpMat indefinite = full;
  indefinite.coeffRef(10, 10) = -3.0;
  const SpMat indefinite_upper = upper_of(indefinite);
  EXPECT_FALSE(chol.factorize(indefinite_upper).positive_definite);
  ASSERT_TRUE(chol.factorize(indefinite_upper, 100.0).positive_definite);
  const SpMat indefinite_shifted = indefinite + 100.0 * identity;
  EXPECT_LT(relative_error(chol.solve(b), reference_solve(indefinite_shifted, b)), kSolveTolerance);
}

TEST(CholmodFactorization, RefactorizationWithNewValuesReusesAnalysis) {
  const SpMat full = random_spd_full(30, 17);
  SpMat upper = upper_of(full);
  const Eigen::VectorXd b = random_vector(full.rows(), 19);
  CholmodFactorization chol;
  chol.analyze(upper);
  const double lnz = chol.factor_nonzeros();
  ASSERT_TRUE(chol.factorize(upper).positive_definite);
  const Eigen::VectorXd x1 = chol.solve(b);

  // New values on the same pattern: scale off-diagonals, keeping dominance.
  SpMat full2 = full;
  for (int col = 0; col < full2.outerSize(); ++col) {
    for (SpMat::InnerIterator it(full2, col); it; ++it) {
      if (it.row() != it.col()) it.valueRef() *= -0.5;
    }
  }
  SpMat upper2 = upper_of(full2);
  ASSERT_TRUE(chol.factorize(upper2).positive_definite);
  const Eigen::VectorXd x2 = chol.solve(b);
  EXPECT_EQ(chol.factor_nonzeros(), lnz);
  EXPECT_LT(relative_error(x2, reference_solve(full2, b)), kSolveTolerance);
  EXPECT_GT(relative_error(x2, x1), 1e-2);

  // A different pattern is rejected instead of silently corrupting the factor.
  SpMat other = upper_of(random_spd_full(31, 17));
  EXPECT_THROW(chol.factorize(other), std::runtime_error);
  SpMat extra = upper2;
  extra.coeffRef(0, 500) = 0.01;
  extra.makeCompressed();
  EXPECT_THROW(chol.factorize(extra), std::runtime_error);
}

TEST(CholmodFactorization, MetisAndAmdOrderingsGiveTheSameSolution) {
  const SpMat full = random_spd_full(45, 23);
  const SpMat upper = upper_of(full);
  const Eigen::VectorXd b = random_vector(full.rows(), 29);
  CholmodFactorization metis({FillReducingOrdering::Metis});
  CholmodFactorization amd({FillReducingOrdering::Amd});
  EXPECT_EQ(metis.ordering(), FillReducingOrdering::Metis);
  EXPECT_EQ(amd.ordering(), FillReducingOrdering::Amd);
  metis.analyze(upper);
  amd.analyze(upper);
  ASSERT_TRUE(metis.factorize(upper).positive_definite);
  ASSERT_TRUE(amd.factorize(upper).positive_definite);
  const Eigen::VectorXd x_metis = metis.solve(b);
  const Eigen::VectorXd x_amd = amd.solve(b);
  EXPECT_LT(relative_error(x_metis, x_amd), kSolveTolerance);
  RecordProperty("relative_difference_metis_amd", scientific(relative_error(x_metis, x_amd)));
  EXPECT_GT(metis.factor_nonzeros(), 0.0);
  EXPECT_GT(amd.factor_nonzeros(), 0.0);
  RecordProperty("lnz_metis", scientific(metis.factor_nonzeros()));
  RecordProperty("lnz_amd", scientific(amd.factor_nonzeros()));
  RecordProperty("flops_metis", scientific(metis.factorization_flops()));
  RecordProperty("flops_amd", scientific(amd.factorization_flops()));
}

TEST(CholmodFactorization, InvalidUseThrows) {
  const SpMat full = random_spd_full(10, 1);
  const SpMat upper = upper_of(full);
  CholmodFactorization chol;
  EXPECT_THROW(chol.factorize(upper), std::logic_error);
  EXPECT_THROW(chol.solve(Eigen::VectorXd::Ones(100)), std::logic_error);
  SpMat lower = full.triangularView<Eigen::Lower>();
  EXPECT_THROW(chol.analyze(lower), std::invalid_argument);
  EXPECT_THROW(chol.analyze(SpMat(3, 4)), std::invalid_argument);
  chol.analyze(upper);
  EXPECT_THROW(chol.factorize(upper, std::nan("")), std::invalid_argument);
  SpMat nan_upper = upper;
  nan_upper.valuePtr()[3] = std::nan("");
  EXPECT_THROW(chol.factorize(nan_upper), std::invalid_argument);
  ASSERT_TRUE(chol.factorize(upper).positive_definite);
  EXPECT_THROW(chol.solve(Eigen::VectorXd::Ones(99)), std::invalid_argument);

  CholmodFactorization moved = std::move(chol);
  EXPECT_EQ(moved.rows(), 100);
  EXPECT_NO_THROW(moved.solve(Eigen::VectorXd::Ones(100)));
}

}  // namespace
}  // namespace growshell
