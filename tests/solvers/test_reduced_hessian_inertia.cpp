// reduced_hessian_inertia: the inertia of Z^T H Z from the bordered matrix, against dense
// eigenvalues of Z^T H Z (Z from a QR factorisation of J^T) on random problems with chosen
// spectra, against block constructions whose reduced Hessian is known exactly (indefinite H
// with a positive definite reduction, negative directions inside the tangent space, a singular
// reduction), against the closed-form spectrum of a 10^5-dof chain, and its errors.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "solvers/stability/reduced_hessian_inertia.hpp"
#include "tests/support/count_below.hpp"

namespace growshell {
namespace {

using SpMat = Eigen::SparseMatrix<double>;
using test_support::count_below;
constexpr double kPi = 3.14159265358979323846;

Eigen::MatrixXd random_matrix(Eigen::Index rows, Eigen::Index cols, std::mt19937& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd a(rows, cols);
  for (Eigen::Index j = 0; j < cols; ++j)
    for (Eigen::Index i = 0; i < rows; ++i) a(i, j) = normal(rng);
  return a;
}

Eigen::MatrixXd random_orthogonal(Eigen::Index n, std::mt19937& rng) {
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(random_matrix(n, n, rng));
  return qr.householderQ();
}

// Q diag(eigenvalues) Q^T with a random orthogonal Q: a dense symmetric matrix with exactly
// the given spectrum (up to round-off).
Eigen::MatrixXd with_spectrum(const Eigen::VectorXd& eigenvalues, std::mt19937& rng) {
  const Eigen::MatrixXd q = random_orthogonal(eigenvalues.size(), rng);
  return q * eigenvalues.asDiagonal() * q.transpose();
}

// `negatives` eigenvalues in [-2, -0.1], the others in [0.1, 3].
Eigen::VectorXd random_spectrum(Eigen::Index n, int negatives, std::mt19937& rng) {
  std::uniform_real_distribution<double> magnitude(0.1, 1.0);
  Eigen::VectorXd e(n);
  for (Eigen::Index i = 0; i < n; ++i)
    e(i) = i < negatives ? -2.0 * magnitude(rng) : 3.0 * magnitude(rng);
  return e;
}

SpMat sparse_upper_of(const Eigen::MatrixXd& dense) {
  SpMat u = Eigen::MatrixXd(dense.triangularView<Eigen::Upper>()).sparseView();
  u.makeCompressed();
  return u;
}

SpMat sparse_of(const Eigen::MatrixXd& dense) {
  SpMat s = dense.sparseView();
  s.makeCompressed();
  return s;
}

std::vector<Eigen::Index> free_dofs_of(Eigen::Index n, const std::vector<Eigen::Index>& fixed) {
  std::vector<Eigen::Index> free;
  for (Eigen::Index i = 0; i < n; ++i)
    if (std::find(fixed.begin(), fixed.end(), i) == fixed.end()) free.push_back(i);
  return free;
}

// Reference: eigenvalues of Z^T H_f Z, Z an orthonormal basis of null(J_f) (the last nf - m
// columns of the Q of a Householder QR of J_f^T, valid for J_f of full rank m).
Eigen::VectorXd dense_reduced_eigenvalues(const Eigen::MatrixXd& h, const Eigen::MatrixXd& j,
                                          const std::vector<Eigen::Index>& fixed) {
  const std::vector<Eigen::Index> free = free_dofs_of(h.rows(), fixed);
  const auto nf = static_cast<Eigen::Index>(free.size());
  const Eigen::MatrixXd h_f = h(free, free);
  const Eigen::MatrixXd j_f = j(Eigen::all, free);
  Eigen::MatrixXd z = Eigen::MatrixXd::Identity(nf, nf);
  if (j.rows() > 0) {
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(j_f.transpose());
    const Eigen::MatrixXd q = qr.householderQ();
    z = q.rightCols(nf - j.rows());
  }
  const Eigen::MatrixXd reduced = z.transpose() * h_f * z;
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (reduced + reduced.transpose()))
      .eigenvalues();
}

// Orthonormal bases Y of range(J^T) and Z of null(J) (J full rank), n x m and n x (n - m).
struct SplitBasis {
  Eigen::MatrixXd y, z;
};
SplitBasis split_basis(const Eigen::MatrixXd& j) {
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(j.transpose());
  const Eigen::MatrixXd q = qr.householderQ();
  return {q.leftCols(j.rows()), q.rightCols(j.cols() - j.rows())};
}

// H = Z A Z^T + Y B Y^T + Z C Y^T + Y C^T Z^T: then Z^T H Z = A exactly in exact arithmetic.
Eigen::MatrixXd assemble_from_blocks(const SplitBasis& s, const Eigen::MatrixXd& a,
                                     const Eigen::MatrixXd& b, const Eigen::MatrixXd& c) {
  const Eigen::MatrixXd coupling = s.z * c * s.y.transpose();
  const Eigen::MatrixXd h = s.z * a * s.z.transpose() + s.y * b * s.y.transpose() + coupling +
                            coupling.transpose();
  return 0.5 * (h + h.transpose());
}

std::string runtime_message(const std::function<void()>& call) {
  try {
    call();
  } catch (const std::runtime_error& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("other exception: ") + e.what();
  }
  return "no exception";
}

std::string invalid_message(const std::function<void()>& call) {
  try {
    call();
  } catch (const std::invalid_argument& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("other exception: ") + e.what();
  }
  return "no exception";
}

// ---------------------------------------------------------------------------------------
// Random H (n = 30, chosen spectrum) and random J with m = 0, 1, 5 rows, with and without
// fixed dofs, over wildly different scales of H and of the rows of J (the counts must not
// depend on them): the counts equal the dense ones.
TEST(ReducedHessianInertia, MatchesDenseCountOnRandomProblems) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> log_scale(-6.0, 6.0);
  const Eigen::Index n = 30;
  const std::vector<std::vector<Eigen::Index>> fixed_sets = {{}, {3, 17, 29, 3}};
  int cases = 0;
  int reduced_below_plain = 0;
  double smallest_gap = std::numeric_limits<double>::infinity();
  for (const int m : {0, 1, 5}) {
    for (const int negatives : {0, 4, 11}) {
      for (const std::vector<Eigen::Index>& fixed : fixed_sets) {
        for (int trial = 0; trial < 3; ++trial) {
          const double h_scale = trial == 1 ? 1e-4 : 1.0;  // e.g. a shell Hessian in N/m
          const Eigen::MatrixXd h = h_scale * with_spectrum(random_spectrum(n, negatives, rng), rng);
          Eigen::MatrixXd j = random_matrix(m, n, rng);
          if (trial == 2) {
            for (Eigen::Index k = 0; k < m; ++k) j.row(k) *= std::pow(10.0, log_scale(rng));
          }
          const Eigen::VectorXd e = dense_reduced_eigenvalues(h, j, fixed);
          // Premise: no reduced eigenvalue so close to zero that its sign is round-off.
          const double gap = e.cwiseAbs().minCoeff() / e.cwiseAbs().maxCoeff();
          smallest_gap = std::min(smallest_gap, gap);
          ASSERT_GT(gap, 1e-8) << "m " << m << " negatives " << negatives << " trial " << trial;
          const ReducedInertia r = reduced_hessian_inertia(sparse_upper_of(h), sparse_of(j), fixed);
          const int expected = count_below(e, 0.0);
          EXPECT_EQ(r.negative, expected)
              << "m " << m << " negatives " << negatives << " fixed " << fixed.size()
              << " trial " << trial;
          EXPECT_EQ(r.zero, 0);
          EXPECT_EQ(r.constraints, m);
          EXPECT_EQ(r.free_dofs, fixed.empty() ? 30 : 27);  // the repeated 3 counts once
          // Restriction never adds negative directions, and m constraints remove at most m
          // (interlacing): neg(H_f) - m <= neg(Z^T H_f Z) <= neg(H_f).
          const int plain = count_below(dense_reduced_eigenvalues(h, j.topRows(0), fixed), 0.0);
          EXPECT_LE(r.negative, plain);
          EXPECT_GE(r.negative, plain - m);
          reduced_below_plain += r.negative < plain;
          ++cases;
        }
      }
    }
  }
  EXPECT_EQ(cases, 54);
  // The constraints did remove negative directions in some cases (measured: 15 of 54), so
  // the comparison is not just neg(H_f) against itself. Measured smallest |eigenvalue| of a
  // reduction relative to its largest: 2.8e-3, far above round-off, so the dense signs are
  // unambiguous.
  EXPECT_GE(reduced_below_plain, 5);
  RecordProperty("cases_with_fewer_reduced_negatives", reduced_below_plain);
  RecordProperty("smallest_relative_eigenvalue", std::to_string(smallest_gap));
}

// H with 5 negative eigenvalues whose reduction to null(J) (m = 5) is positive definite: the
// constraints block every unstable direction. In the basis [Z Y], H = [A C; C^T -3 I] with A
// positive definite, so by the Haynsworth inertia formula neg(H) = neg(-3 I - C^T A^-1 C) = 5.
TEST(ReducedHessianInertia, IndefiniteHessianWithPositiveDefiniteReduction) {
  std::mt19937 rng(7);
  const Eigen::Index n = 30, m = 5;
  const Eigen::MatrixXd j = random_matrix(m, n, rng);
  const SplitBasis s = split_basis(j);
  const Eigen::MatrixXd a = with_spectrum(random_spectrum(n - m, 0, rng), rng);
  const Eigen::MatrixXd c = 0.3 * random_matrix(n - m, m, rng);
  const Eigen::MatrixXd h = assemble_from_blocks(s, a, -3.0 * Eigen::MatrixXd::Identity(m, m), c);
  ASSERT_EQ(count_below(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(h).eigenvalues(), 0.0), 5);

  const ReducedInertia plain = reduced_hessian_inertia(sparse_upper_of(h), SpMat(0, n), {});
  EXPECT_EQ(plain.negative, 5);
  EXPECT_EQ(plain.zero, 0);
  EXPECT_EQ(plain.constraints, 0);
  const ReducedInertia reduced = reduced_hessian_inertia(sparse_upper_of(h), sparse_of(j), {});
  EXPECT_EQ(reduced.negative, 0);
  EXPECT_EQ(reduced.zero, 0);
  EXPECT_EQ(reduced.constraints, 5);
  EXPECT_EQ(reduced.free_dofs, 30);
  // Dropping one constraint frees a direction with a negative component: the reduction by the
  // other four keeps some of H's negative space (interlacing: at least 5 - 4 = 1).
  const ReducedInertia four =
      reduced_hessian_inertia(sparse_upper_of(h), sparse_of(j.topRows(4)), {});
  EXPECT_EQ(four.negative, count_below(dense_reduced_eigenvalues(h, j.topRows(4), {}), 0.0));
  EXPECT_GE(four.negative, 1);
}

// The other way round. For a fixed H, neg(Z^T H Z) <= neg(H) always (Z maps a negative
// subspace of Z^T H Z onto one of H), so constraints cannot create instability out of a
// positive definite H; in a contact problem that happens through the constraint curvature in
// the Lagrangian's Hessian (tests/contact_solver/test_contact_stability.cpp). The sharp case
// here: H's two negative directions lie in the tangent space (C = 0, B positive definite), so
// the constraints remove none of them and both counts are 2.
TEST(ReducedHessianInertia, NegativeDirectionsInTheTangentSpaceSurvive) {
  std::mt19937 rng(11);
  const Eigen::Index n = 30, m = 5;
  const Eigen::MatrixXd j = random_matrix(m, n, rng);
  const SplitBasis s = split_basis(j);
  const Eigen::MatrixXd a = with_spectrum(random_spectrum(n - m, 2, rng), rng);
  const Eigen::MatrixXd b = with_spectrum(random_spectrum(m, 0, rng), rng);
  const Eigen::MatrixXd h = assemble_from_blocks(s, a, b, Eigen::MatrixXd::Zero(n - m, m));
  EXPECT_EQ(reduced_hessian_inertia(sparse_upper_of(h), SpMat(0, n), {}).negative, 2);
  const ReducedInertia r = reduced_hessian_inertia(sparse_upper_of(h), sparse_of(j), {});
  EXPECT_EQ(r.negative, 2);
  EXPECT_EQ(r.zero, 0);
}

// Fixed dofs remove their rows and columns: a negative diagonal entry on a fixed dof no longer
// counts, and fixing a dof is the same as the constraint e_i^T dx = 0.
TEST(ReducedHessianInertia, FixedDofsAreRemoved) {
  std::mt19937 rng(5);
  const Eigen::Index n = 12;
  Eigen::VectorXd d = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
  d(4) = -1.0;
  d(9) = -0.5;
  Eigen::MatrixXd h = d.asDiagonal();
  h(0, 1) = h(1, 0) = 0.3;  // some coupling, still positive on the block {0, 1}
  EXPECT_EQ(reduced_hessian_inertia(sparse_upper_of(h), SpMat(0, n), {}).negative, 2);
  const ReducedInertia fixed = reduced_hessian_inertia(sparse_upper_of(h), SpMat(0, n), {4});
  EXPECT_EQ(fixed.negative, 1);
  EXPECT_EQ(fixed.free_dofs, 11);
  // The constraint dx_9 = 0 instead of fixing dof 9, together with fixed dof 4: stable.
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(1, n);
  j(0, 9) = 2.5;
  const ReducedInertia both = reduced_hessian_inertia(sparse_upper_of(h), sparse_of(j), {4});
  EXPECT_EQ(both.negative, 0);
  EXPECT_EQ(both.zero, 0);
  EXPECT_EQ(both.constraints, 1);
  EXPECT_EQ(both.free_dofs, 11);
  // Entries of J on fixed dofs are ignored: a constraint row touching fixed dof 4 as well.
  j(0, 4) = 7.0;
  EXPECT_EQ(reduced_hessian_inertia(sparse_upper_of(h), sparse_of(j), {4}).negative, 0);
  // Everything fixed, no constraints: the empty reduction.
  std::vector<Eigen::Index> all(static_cast<size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) all[static_cast<size_t>(i)] = i;
  const ReducedInertia none = reduced_hessian_inertia(sparse_upper_of(h), SpMat(0, n), all);
  EXPECT_EQ(none.negative, 0);
  EXPECT_EQ(none.zero, 0);
  EXPECT_EQ(none.free_dofs, 0);
}

// A singular reduced Hessian. Exactly singular first: H = [1 1; 1 1] on dofs {0, 1}, -1 on
// dof 2, 3 on dof 3, with dof 3 constrained: Z^T H Z = [1 1; 1 1] + [-1], eigenvalues 2, 0,
// -1, and the elimination meets the zero exactly (1 - 1 * 1 / 1), so MUMPS's default null-pivot
// threshold sees it.
TEST(ReducedHessianInertia, ExactlySingularReductionHasZeroCount) {
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(4, 4);
  h << 1, 1, 0, 0,  //
      1, 1, 0, 0,   //
      0, 0, -1, 0,  //
      0, 0, 0, 3;
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(1, 4);
  j(0, 3) = 1.0;
  const ReducedInertia r = reduced_hessian_inertia(sparse_upper_of(h), sparse_of(j), {});
  EXPECT_EQ(r.zero, 1);
  EXPECT_EQ(r.negative, 1);
  EXPECT_EQ(r.constraints, 1);
  EXPECT_EQ(r.free_dofs, 4);
}

// Singular only up to the round-off of forming H: A with eigenvalues {0, 0, -1, -2, then
// positive}, so Z^T H Z has two eigenvalues of order 1e-16 |H|. The round-off of the
// elimination is of the same order, so whether MUMPS's default threshold (sqrt(p) eps |K|)
// calls them zero is luck; a caller asking "singular to working accuracy" passes a threshold
// (here 1e-10, relative to the scaled |K|), and then both are counted, neither as negative.
// Shifting them to 0.5 makes the reduction regular again: no zero even with that threshold.
TEST(ReducedHessianInertia, SingularToRoundOffCountsZerosWithAThreshold) {
  std::mt19937 rng(3);
  const Eigen::Index n = 30, m = 5;
  const Eigen::MatrixXd j = random_matrix(m, n, rng);
  const SplitBasis s = split_basis(j);
  Eigen::VectorXd spectrum = random_spectrum(n - m, 0, rng);
  spectrum(0) = spectrum(1) = 0.0;
  spectrum(2) = -1.0;
  spectrum(3) = -2.0;
  const Eigen::MatrixXd a = with_spectrum(spectrum, rng);
  const Eigen::MatrixXd b = with_spectrum(random_spectrum(m, 2, rng), rng);
  const Eigen::MatrixXd c = 0.5 * random_matrix(n - m, m, rng);
  const Eigen::MatrixXd h = assemble_from_blocks(s, a, b, c);
  const Eigen::VectorXd e = dense_reduced_eigenvalues(h, j, {});
  ASSERT_LT(e.cwiseAbs().minCoeff(), 1e-13);  // premise: singular to round-off
  SymmetricIndefiniteOptions tolerant;
  tolerant.null_pivot_threshold = 1e-10;
  const ReducedInertia r = reduced_hessian_inertia(sparse_upper_of(h), sparse_of(j), {}, tolerant);
  EXPECT_EQ(r.zero, 2);
  EXPECT_EQ(r.negative, 2);
  // With the default threshold the two near-zero pivots land somewhere among zero, negative
  // and positive (measured: one negative, one positive, no zero); the clearly negative ones
  // are still all counted.
  const ReducedInertia d = reduced_hessian_inertia(sparse_upper_of(h), sparse_of(j), {});
  EXPECT_GE(d.negative, 2);
  EXPECT_LE(d.negative + d.zero, 4);
  RecordProperty("default_threshold_negative", d.negative);
  RecordProperty("default_threshold_zero", d.zero);

  spectrum(0) = spectrum(1) = 0.5;
  const Eigen::MatrixXd h2 = assemble_from_blocks(s, with_spectrum(spectrum, rng), b, c);
  const ReducedInertia r2 =
      reduced_hessian_inertia(sparse_upper_of(h2), sparse_of(j), {}, tolerant);
  EXPECT_EQ(r2.zero, 0);
  EXPECT_EQ(r2.negative, 2);
}

// A 10^5-dof chain with a closed-form answer, at the sizes the method is for. H = T - I with
// T = tridiag(-1, 2, -1) of order n = 99999: eigenvalues 2 - 2 cos(k pi / (n + 1)) - 1, so
// neg(H) = #{k : k < (n + 1) / 3} = 33333. Holding every tenth dof (i = 9, 19, ...) cuts the
// chain into 10^4 independent chains of 9 dofs with the same Dirichlet ends, so Z^T H Z =
// blockdiag(T_9 - I), neg = 10^4 #{k = 1..9 : 2 - 2 cos(k pi / 10) < 1} = 3 10^4 (the nearest
// eigenvalues 0.82 and 1.38 are far from 1). Half of the held dofs are fixed dofs, the other
// half constraints with random row scales: both mean dx_i = 0. AMD ordering: a chain has no
// separators for nested dissection to exploit, and MUMPS's automatic choice (SCOTCH) took 4x
// longer here.
TEST(ReducedHessianInertia, LongChainMatchesClosedFormSpectrum) {
  const Eigen::Index n = 99999;
  std::vector<Eigen::Triplet<double>> t;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (i > 0) t.emplace_back(i - 1, i, -1.0);
    t.emplace_back(i, i, 2.0 - 1.0);
  }
  SpMat h(n, n);
  h.setFromTriplets(t.begin(), t.end());
  h.makeCompressed();

  int expected_plain = 0;
  for (Eigen::Index k = 1; k <= n; ++k)
    expected_plain += 2.0 - 2.0 * std::cos(static_cast<double>(k) * kPi / static_cast<double>(n + 1)) < 1.0;
  ASSERT_EQ(expected_plain, 33333);
  SymmetricIndefiniteOptions amd;
  amd.ordering = IndefiniteOrdering::Amd;
  const ReducedInertia plain = reduced_hessian_inertia(h, SpMat(0, n), {}, amd);
  EXPECT_EQ(plain.negative, expected_plain);
  EXPECT_EQ(plain.zero, 0);

  std::vector<Eigen::Index> fixed;
  std::vector<Eigen::Triplet<double>> jt;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> scale(0.1, 10.0);
  int held = 0;
  for (Eigen::Index i = 9; i < n; i += 10, ++held) {
    if (held % 2 == 0) {
      fixed.push_back(i);
    } else {
      jt.emplace_back(static_cast<Eigen::Index>(jt.size()), i, scale(rng));
    }
  }
  SpMat j(static_cast<Eigen::Index>(jt.size()), n);
  j.setFromTriplets(jt.begin(), jt.end());
  ASSERT_EQ(held, 9999);
  const ReducedInertia r = reduced_hessian_inertia(h, j, fixed, amd);
  EXPECT_EQ(r.negative, 30000);
  EXPECT_EQ(r.zero, 0);
  EXPECT_EQ(r.constraints, 4999);
  EXPECT_EQ(r.free_dofs, n - 5000);
}

// Rank deficient J on the free dofs is an error, not a count: a dependent row (with H positive
// definite, where neg(K) = m - 1 < m also shows it, and with H indefinite, where neg(K) >= m
// and only the rank test sees it), a row living on fixed dofs only, more rows than free dofs.
TEST(ReducedHessianInertia, RankDeficientJacobianThrows) {
  std::mt19937 rng(13);
  const Eigen::Index n = 30;
  Eigen::MatrixXd j = random_matrix(3, n, rng);
  j.row(2) = j.row(0) - 2.0 * j.row(1);
  for (const int negatives : {0, 8}) {
    const Eigen::MatrixXd h = with_spectrum(random_spectrum(n, negatives, rng), rng);
    const std::string message =
        runtime_message([&] { reduced_hessian_inertia(sparse_upper_of(h), sparse_of(j), {}); });
    EXPECT_NE(message.find("rank deficient"), std::string::npos) << message;
    EXPECT_NE(message.find("1 of its 3 rows depend"), std::string::npos) << message;
    EXPECT_NE(message.find("Drop the dependent constraints"), std::string::npos) << message;
  }
  const Eigen::MatrixXd h = with_spectrum(random_spectrum(n, 3, rng), rng);
  Eigen::MatrixXd on_fixed = Eigen::MatrixXd::Zero(2, n);
  on_fixed(0, 1) = 1.0;
  on_fixed(1, 5) = 1.0;
  on_fixed(1, 6) = 1.0;
  const std::string message = runtime_message([&] {
    reduced_hessian_inertia(sparse_upper_of(h), sparse_of(on_fixed), {5, 6});
  });
  EXPECT_NE(message.find("row 1 has no nonzero entry on a free dof"), std::string::npos)
      << message;
  std::vector<Eigen::Index> most(27);
  for (int i = 0; i < 27; ++i) most[static_cast<size_t>(i)] = i;
  const std::string too_many = runtime_message([&] {
    reduced_hessian_inertia(sparse_upper_of(h), sparse_of(random_matrix(4, n, rng)), most);
  });
  EXPECT_NE(too_many.find("4 constraints on 3 free dofs"), std::string::npos) << too_many;
}

TEST(ReducedHessianInertia, RejectsBadInputNamingIt) {
  std::mt19937 rng(17);
  const Eigen::Index n = 6;
  const Eigen::MatrixXd h = with_spectrum(random_spectrum(n, 1, rng), rng);
  const SpMat hu = sparse_upper_of(h);
  const SpMat j = sparse_of(random_matrix(2, n, rng));
  EXPECT_NE(invalid_message([&] { reduced_hessian_inertia(hu, sparse_of(random_matrix(2, 5, rng)), {}); })
                .find("constraint_jacobian is 2 x 5, expected 6 columns"),
            std::string::npos);
  EXPECT_NE(invalid_message([&] { reduced_hessian_inertia(sparse_of(random_matrix(6, 5, rng)), j, {}); })
                .find("hessian_upper"),
            std::string::npos);
  EXPECT_NE(invalid_message([&] { reduced_hessian_inertia(sparse_of(h), j, {}); })
                .find("below the diagonal"),
            std::string::npos);
  EXPECT_NE(invalid_message([&] { reduced_hessian_inertia(hu, j, {0, 6}); })
                .find("fixed dof 6 (fixed_dofs[1]) is outside [0, 6)"),
            std::string::npos);
  EXPECT_NE(invalid_message([&] { reduced_hessian_inertia(hu, j, {-1}); }).find("fixed dof -1"),
            std::string::npos);
  SpMat bad_h = hu;
  bad_h.coeffRef(1, 3) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(invalid_message([&] { reduced_hessian_inertia(bad_h, j, {}); })
                .find("hessian_upper entry (1, 3) is not finite"),
            std::string::npos);
  SpMat bad_j = j;
  bad_j.coeffRef(1, 4) = std::numeric_limits<double>::infinity();
  EXPECT_NE(invalid_message([&] { reduced_hessian_inertia(hu, bad_j, {}); })
                .find("constraint_jacobian entry (1, 4) is not finite"),
            std::string::npos);
}

}  // namespace
}  // namespace growshell
