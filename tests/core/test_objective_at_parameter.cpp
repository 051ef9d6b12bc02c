// ObjectiveAtParameter: the member of a family at one parameter, as a SparseObjective; it
// forwards the family's dimension, pattern and evaluation at its own parameter and leaves the
// family as it was.
#include <gtest/gtest.h>

#include <Eigen/SparseCore>
#include <cmath>
#include <limits>

#include "core/objective_at_parameter.hpp"

namespace growshell {
namespace {

/// E(x; lambda) = sum_i (x_i - lambda)^2 / 2 + lambda x_0 x_1 on two unknowns.
class Quadratic final : public ParametrizedObjective {
 public:
  Eigen::Index dimension() const override { return 2; }
  Eigen::SparseMatrix<double> hessian_pattern() const override {
    Eigen::SparseMatrix<double> H(2, 2);
    H.insert(0, 0) = 0.0;
    H.insert(0, 1) = 0.0;
    H.insert(1, 1) = 0.0;
    H.makeCompressed();
    return H;
  }
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, double lambda, Eigen::VectorXd* g,
                  Eigen::SparseMatrix<double>* H) const override {
    if (g) *g = Eigen::Vector2d(x(0) - lambda + lambda * x(1), x(1) - lambda + lambda * x(0));
    if (H) {
      H->coeffRef(0, 0) = 1.0;
      H->coeffRef(0, 1) = lambda;
      H->coeffRef(1, 1) = 1.0;
    }
    return 0.5 * (x.array() - lambda).square().sum() + lambda * x(0) * x(1);
  }
  Eigen::VectorXd gradient_parameter_derivative(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                double) const override {
    return Eigen::Vector2d(-1.0 + x(1), -1.0 + x(0));
  }
  bool accepts_parameter(double lambda) const override { return lambda > -1.0; }
};

TEST(ObjectiveAtParameter, EvaluatesTheFamilyAtItsOwnParameter) {
  const Quadratic family;
  ObjectiveAtParameter at_half(family, 0.5);
  ObjectiveAtParameter at_two(family, 2.0);
  EXPECT_EQ(at_half.parameter(), 0.5);
  EXPECT_EQ(&at_half.family(), &family);
  EXPECT_EQ(at_half.dimension(), 2);
  EXPECT_EQ(at_half.hessian_pattern().nonZeros(), 3);
  const Eigen::Vector2d x(0.3, -0.4);
  Eigen::VectorXd g, g_family;
  Eigen::SparseMatrix<double> H = at_half.hessian_pattern(), H_family = H;
  const double e = at_half.evaluate(x, &g, &H);
  EXPECT_EQ(e, family.evaluate(x, 0.5, &g_family, &H_family));
  EXPECT_EQ(g, g_family);
  EXPECT_EQ(H.coeff(0, 1), 0.5);
  // Two members of one family do not see each other.
  EXPECT_EQ(at_two.evaluate(x, nullptr, nullptr), family.evaluate(x, 2.0, nullptr, nullptr));
  EXPECT_EQ(at_half.evaluate(x, nullptr, nullptr), e);
}

TEST(ParametrizedObjective, AcceptsEveryFiniteParameterUnlessItSaysOtherwise) {
  const Quadratic restricted;
  EXPECT_TRUE(restricted.accepts_parameter(0.0));
  EXPECT_FALSE(restricted.accepts_parameter(-2.0));
  struct Open final : ParametrizedObjective {
    Eigen::Index dimension() const override { return 1; }
    Eigen::SparseMatrix<double> hessian_pattern() const override { return {}; }
    double evaluate(const Eigen::Ref<const Eigen::VectorXd>&, double, Eigen::VectorXd*,
                    Eigen::SparseMatrix<double>*) const override {
      return 0.0;
    }
    Eigen::VectorXd gradient_parameter_derivative(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                  double) const override {
      return Eigen::VectorXd::Zero(x.size());
    }
  } open;
  EXPECT_TRUE(open.accepts_parameter(-1e300));
  EXPECT_FALSE(open.accepts_parameter(std::numeric_limits<double>::infinity()));
  EXPECT_FALSE(open.accepts_parameter(std::nan("")));
}

}  // namespace
}  // namespace growshell
