// turning_back_event ends a trace at the first fold, so that its samples are single-valued in
// the parameter; on the S-curve lambda = y - y^3 the folds are at lambda = +-2/(3 sqrt 3).
#include "solvers/continuation/turning_back_event.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "support/one_unknown_family.hpp"

namespace growshell {
namespace {

/// E = y^4/4 - y^2/2 + lambda y in one unknown: g = y^3 - y + lambda, the S-curve
/// lambda = y - y^3 with folds at y = +-1/sqrt 3.
class SCurve : public test_support::OneUnknownFamily {
 public:
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, double lambda, Eigen::VectorXd* g,
                  Eigen::SparseMatrix<double>* H) const override {
    const double y = x(0);
    if (g) *g = Eigen::VectorXd::Constant(1, y * y * y - y + lambda);
    if (H) H->coeffRef(0, 0) = 3 * y * y - 1;
    return y * y * y * y / 4 - y * y / 2 + lambda * y;
  }
  Eigen::VectorXd gradient_parameter_derivative(const Eigen::Ref<const Eigen::VectorXd>&,
                                                double) const override {
    return Eigen::VectorXd::Constant(1, 1.0);
  }
};

/// Steps of 0.1 to 0.25 in arclength, the fold located to 1e-7, and lambda within [-3, 3].
ArclengthOptions options() {
  ArclengthOptions o;
  o.initial_step = 0.1;
  o.max_step = 0.25;
  o.gradient_tolerance = 1e-12;
  o.special_point_tolerance = 1e-7;
  o.parameter_min = -3.0;
  o.parameter_max = 3.0;
  return o;
}

TEST(TurningBackEvent, EndsTheTraceJustPastTheFirstFold) {
  const SCurve curve;
  const double fold = 2.0 / (3.0 * std::sqrt(3.0));
  // From y = -1.5 (lambda = 1.875) towards decreasing lambda: the lower branch y < -1/sqrt 3
  // runs down to the fold at lambda = -fold, where the middle branch turns back up.
  const double y0 = -1.5, lambda0 = y0 - y0 * y0 * y0;
  const Eigen::VectorXd x0 = Eigen::VectorXd::Constant(1, y0);
  std::vector<BranchSample> samples;
  const BranchTrace trace = trace_branch(curve, x0, lambda0, -1, {}, options(),
                                         [&](const BranchSample& s) { samples.push_back(s); }, {});
  ASSERT_EQ(trace.special_points.size(), 2u);  // without the event: both folds
  std::vector<BranchSample> stopped;
  const BranchTrace ended = trace_branch_along(
      curve, x0, lambda0, Eigen::VectorXd::Zero(1), -1.0, {}, options(),
      [&](const BranchSample& s) { stopped.push_back(s); }, {}, {turning_back_event(-1)}, {});
  EXPECT_TRUE(ended.reached_bound);
  EXPECT_EQ(ended.message, "stopped at event 'turns_back'");
  ASSERT_EQ(ended.events.size(), 1u);
  EXPECT_NEAR(ended.events[0].parameter, -fold, 1e-6);
  // The fold as a special point too, and nothing after it: every sample but the last lies on
  // the lower branch, each below the one before, and the last just past the fold.
  ASSERT_EQ(ended.special_points.size(), 1u);
  EXPECT_NEAR(ended.special_points[0].parameter, -fold, 1e-6);
  ASSERT_GE(stopped.size(), 5u);
  for (std::size_t i = 1; i + 1 < stopped.size(); ++i) {
    EXPECT_LT(stopped[i].parameter, stopped[i - 1].parameter) << "sample " << i;
    EXPECT_LT(stopped[i].x(0), -1.0 / std::sqrt(3.0)) << "sample " << i;
  }
  EXPECT_NEAR(stopped.back().parameter, -fold, 1e-6);
  EXPECT_LT(stopped.size(), samples.size());

  // Upwards from the same start nothing turns back before the bound.
  const BranchTrace up = trace_branch_along(curve, x0, lambda0, Eigen::VectorXd::Zero(1), 1.0, {},
                                            options(), {}, {}, {turning_back_event(+1)}, {});
  EXPECT_TRUE(up.events.empty());
  EXPECT_EQ(up.message, "reached the parameter bound");

  EXPECT_THROW(turning_back_event(0), std::invalid_argument);
  EXPECT_THROW(turning_back_event(2), std::invalid_argument);
}

}  // namespace
}  // namespace growshell
