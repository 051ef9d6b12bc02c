// rigid_free_eigenpairs: eigenpairs of H v = lambda M v on the M-orthogonal complement of the
// rigid motions, from pinned eigenpairs, against a dense computation on that complement; a
// pinned eigenvalue lies below the rigid-free one; fewer pinned modes give upper bounds.
#include "solvers/stability/rigid_free_eigenpairs.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <random>
#include <stdexcept>
#include <vector>

#include "libshell/mesh/rigid_motion.hpp"

namespace growshell {
namespace {

// A point cloud x (n points), masses m, and a symmetric H >= 0 that annihilates the six rigid
// velocity fields of x: H = P^T A P with A symmetric positive definite and P the M-orthogonal
// projector off the rigid fields.
struct Problem {
  Eigen::VectorXd x, mass;
  Eigen::MatrixXd rigid, H;
};

Problem make_problem(int points, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.5, 2.0);
  Problem p;
  const int n = 3 * points;
  p.x = Eigen::VectorXd::NullaryExpr(n, [&] { return normal(rng); });
  p.mass = Eigen::VectorXd::NullaryExpr(n, [&] { return uniform(rng); });
  for (int v = 0; v < points; ++v) p.mass.segment<3>(3 * v).setConstant(p.mass(3 * v));
  p.rigid = rigid_velocity_fields(p.x, Eigen::Vector3d(0.1, -0.2, 0.3));
  const Eigen::MatrixXd G = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return normal(rng); });
  const Eigen::MatrixXd A = G.transpose() * G + n * Eigen::MatrixXd::Identity(n, n);
  const Eigen::MatrixXd MR = p.mass.asDiagonal() * p.rigid;
  const Eigen::MatrixXd P = Eigen::MatrixXd::Identity(n, n) -
                            p.rigid * (p.rigid.transpose() * MR).ldlt().solve(MR.transpose());
  p.H = P.transpose() * A * P;
  p.H = 0.5 * (p.H + p.H.transpose()).eval();
  return p;
}

// All eigenpairs of H v = mu M v with the dofs `pins` held at zero (dense), M-orthonormal.
Eigenpairs pinned_eigenpairs(const Problem& p, const std::vector<Eigen::Index>& pins) {
  const Eigen::Index n = p.mass.size();
  std::vector<Eigen::Index> free;
  for (Eigen::Index i = 0; i < n; ++i)
    if (std::find(pins.begin(), pins.end(), i) == pins.end()) free.push_back(i);
  const auto m = static_cast<Eigen::Index>(free.size());
  Eigen::MatrixXd Hf(m, m), Mf = Eigen::MatrixXd::Zero(m, m);
  for (Eigen::Index a = 0; a < m; ++a) {
    Mf(a, a) = p.mass(free[a]);
    for (Eigen::Index b = 0; b < m; ++b) Hf(a, b) = p.H(free[a], free[b]);
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(Hf, Mf);
  Eigenpairs e;
  e.values = solver.eigenvalues();
  e.vectors = Eigen::MatrixXd::Zero(n, m);
  for (Eigen::Index a = 0; a < m; ++a) e.vectors.row(free[a]) = solver.eigenvectors().row(a);
  return e;
}

// The eigenvalues of H on the M-orthogonal complement of the rigid fields (dense).
Eigen::VectorXd complement_eigenvalues(const Problem& p) {
  const Eigen::MatrixXd MR = p.mass.asDiagonal() * p.rigid;
  // An orthonormal basis of the complement of span(M R) in the Euclidean sense is an
  // M-orthogonal complement of span(R).
  const Eigen::FullPivHouseholderQR<Eigen::MatrixXd> qr(MR);
  const Eigen::MatrixXd Q = qr.matrixQ();
  const Eigen::MatrixXd Z = Q.rightCols(Q.cols() - 6);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(
      Z.transpose() * p.H * Z, Z.transpose() * p.mass.asDiagonal() * Z);
  return solver.eigenvalues();
}

const std::vector<Eigen::Index> kPins = {0, 1, 2, 4, 5, 8};  // three points, as the studies pin

TEST(RigidFreeEigenpairs, FromAllPinnedModesTheyAreTheComplementsExactly) {
  const Problem p = make_problem(12, 7);
  const Eigenpairs pinned = pinned_eigenpairs(p, kPins);
  const Eigen::VectorXd exact = complement_eigenvalues(p);
  const RigidFreeEigenpairs r = rigid_free_eigenpairs(pinned, p.rigid, p.mass, 5);
  ASSERT_EQ(r.values.size(), 5);
  for (int k = 0; k < 5; ++k) {
    EXPECT_NEAR(r.values(k), exact(k), 1e-9 * exact(k)) << k;
    // Pinning only lowers an eigenvalue of this positive problem.
    EXPECT_LT(pinned.values(k), r.values(k)) << k;
    const Eigen::VectorXd v = r.vectors.col(k);
    EXPECT_NEAR(v.dot(p.mass.asDiagonal() * v), 1.0, 1e-9);
    EXPECT_LT((p.rigid.transpose() * p.mass.asDiagonal() * v).norm(), 1e-9);
    // An eigenvector of H on the complement: H v = lambda M v less a rigid force.
    const Eigen::VectorXd residual = p.H * v - r.values(k) * p.mass.asDiagonal() * v;
    const Eigen::MatrixXd MR = p.mass.asDiagonal() * p.rigid;
    const Eigen::VectorXd off_rigid =
        residual - MR * (MR.transpose() * MR).ldlt().solve(MR.transpose() * residual);
    EXPECT_LT(off_rigid.norm(), 1e-8 * r.values(k)) << k;
  }
}

TEST(RigidFreeEigenpairs, FromTheLowestPinnedModesTheyAreUpperBounds) {
  const Problem p = make_problem(12, 11);
  Eigenpairs pinned = pinned_eigenpairs(p, kPins);
  const Eigen::VectorXd exact = complement_eigenvalues(p);
  Eigenpairs lowest;
  lowest.values = pinned.values.head(9);
  lowest.vectors = pinned.vectors.leftCols(9);
  const RigidFreeEigenpairs r = rigid_free_eigenpairs(lowest, p.rigid, p.mass, 3);
  for (int k = 0; k < 3; ++k) {
    EXPECT_GE(r.values(k), exact(k) * (1 - 1e-12)) << k;
    EXPECT_LT(r.values(k), 1.5 * exact(k)) << k;  // measured within 20 % on this problem
  }
}

TEST(RigidFreeEigenpairs, RefusesMismatchedSizesAndACountBelowOne) {
  const Problem p = make_problem(6, 3);
  const Eigenpairs pinned = pinned_eigenpairs(p, kPins);
  EXPECT_THROW(rigid_free_eigenpairs(pinned, p.rigid, p.mass, 0), std::invalid_argument);
  EXPECT_THROW(rigid_free_eigenpairs(pinned, p.rigid.topRows(9), p.mass, 2), std::invalid_argument);
  Eigenpairs broken = pinned;
  broken.values.conservativeResize(2);
  EXPECT_THROW(rigid_free_eigenpairs(broken, p.rigid, p.mass, 2), std::invalid_argument);
}

}  // namespace
}  // namespace growshell
