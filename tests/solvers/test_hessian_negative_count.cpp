// HessianNegativeCount: the negative count of a sparse Hessian with fixed dofs removed equals
// the dense eigenvalue count of the remaining block; a singular Hessian is an error, not a
// count.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <limits>
#include <stdexcept>
#include <vector>

#include "solvers/stability/hessian_negative_count.hpp"

namespace growshell {
namespace {

/// E(x) = 1/2 x^T A(x) x with A = tridiag(c, d_i + s x_0^2, c): its Hessian at x = 0 is the
/// tridiagonal matrix, so the count is set by the diagonal d and the state moves it.
class Tridiagonal final : public SparseObjective {
 public:
  explicit Tridiagonal(std::vector<double> d, double c) : d_(std::move(d)), c_(c) {}
  Eigen::Index dimension() const override { return static_cast<Eigen::Index>(d_.size()); }
  Eigen::SparseMatrix<double> hessian_pattern() const override {
    return upper(Eigen::VectorXd::Zero(dimension()));
  }
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd* g,
                  Eigen::SparseMatrix<double>* H) override {
    const Eigen::MatrixXd A = dense(x);
    if (g) *g = A * x;
    if (H) *H = upper(x);
    return 0.5 * x.dot(A * x);
  }
  Eigen::MatrixXd dense(const Eigen::Ref<const Eigen::VectorXd>& x) const {
    const Eigen::Index n = dimension();
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
    for (Eigen::Index i = 0; i < n; ++i) {
      A(i, i) = d_[static_cast<std::size_t>(i)] + x(0) * x(0);
      if (i + 1 < n) A(i, i + 1) = A(i + 1, i) = c_;
    }
    return A;
  }

 private:
  Eigen::SparseMatrix<double> upper(const Eigen::VectorXd& x) const {
    const Eigen::MatrixXd A = dense(x);
    std::vector<Eigen::Triplet<double>> t;
    for (Eigen::Index i = 0; i < dimension(); ++i) {
      t.emplace_back(i, i, A(i, i));
      if (i + 1 < dimension()) t.emplace_back(i, i + 1, A(i, i + 1));
    }
    Eigen::SparseMatrix<double> H(dimension(), dimension());
    H.setFromTriplets(t.begin(), t.end());
    H.makeCompressed();
    return H;
  }
  std::vector<double> d_;
  double c_;
};

int dense_count(const Eigen::MatrixXd& A) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(A);
  return static_cast<int>((es.eigenvalues().array() < 0.0).count());
}

TEST(HessianNegativeCount, EqualsTheDenseCountWithFixedDofsRemoved) {
  Tridiagonal f({-2.0, 1.0, -0.5, 3.0, -1.5, 2.0}, 0.3);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6);
  HessianNegativeCount all(f, {});
  EXPECT_EQ(all.at(zero), dense_count(f.dense(zero)));
  EXPECT_EQ(all.at(zero), 3);
  // Fixing dofs 0 and 4 (both negative on the diagonal) leaves the block of 1, 2, 3, 5.
  HessianNegativeCount fixed(f, {0, 4});
  const std::vector<int> keep{1, 2, 3, 5};
  Eigen::MatrixXd block(4, 4);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) block(i, j) = f.dense(zero)(keep[i], keep[j]);
  EXPECT_EQ(fixed.at(zero), dense_count(block));
  EXPECT_EQ(fixed.at(zero), 1);
  // The state shifts the diagonal by x_0^2 = 4: everything is positive, and the same object
  // (analysed once) factorises the new values.
  Eigen::VectorXd x = zero;
  x(0) = 2.0;
  EXPECT_EQ(all.at(x), 0);
}

TEST(HessianNegativeCount, ASingularOrNonFiniteHessianIsAnError) {
  Tridiagonal f({0.0, 1.0, 2.0}, 0.0);  // exactly singular
  HessianNegativeCount count(f, {});
  EXPECT_THROW(count.at(Eigen::VectorXd::Zero(3)), std::runtime_error);
  Eigen::VectorXd nan = Eigen::VectorXd::Zero(3);
  nan(0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(count.at(nan), std::runtime_error);
}

}  // namespace
}  // namespace growshell
