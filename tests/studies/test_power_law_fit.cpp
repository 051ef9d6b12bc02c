#include "studies/power_law_fit.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace growshell {
namespace {

TEST(PowerLawFit, RecoversAnExactLawAboveItsLimit) {
  // phi_max - 2.57 = 3.6 h^0.28 at four thicknesses: the fit must give A and p to rounding.
  std::vector<double> h = {0.04, 0.02, 0.01, 0.005}, phi;
  for (double t : h) phi.push_back(2.57 + 3.6 * std::pow(t, 0.28));
  const auto fit = fit_power_law(h, phi, 2.57);
  ASSERT_TRUE(fit.has_value());
  EXPECT_NEAR(fit->amplitude, 3.6, 1e-12);
  EXPECT_NEAR(fit->exponent, 0.28, 1e-13);
  EXPECT_EQ(fit->points, 4);
  EXPECT_LT(fit->max_relative_misfit, 1e-13);
  EXPECT_EQ(fit->limit, 2.57);
}

TEST(PowerLawFit, MisfitIsTheLargestRelativeDeviation) {
  // Two points on y = x^2 and one 10 % above it: the line through the logs is the
  // least-squares one, and the misfit is computed from it, not assumed.
  const std::vector<double> x = {1.0, 2.0, 4.0};
  const std::vector<double> y = {1.0, 4.0 * 1.1, 16.0};
  const auto fit = fit_power_law(x, y, 0.0);
  ASSERT_TRUE(fit.has_value());
  // By hand: u = (0, l, 2l), v = (0, 2l + e, 4l), l = ln 2, e = ln 1.1; the mean residual
  // is e / 3 and the slope stays 2 (the middle point has no lever arm), so ln A = e / 3; the
  // outer points are then 1.1^(1/3) - 1 = 3.2 % off, the middle one 1 - 1.1^(-2/3) = 6.2 %.
  EXPECT_NEAR(fit->exponent, 2.0, 1e-14);
  EXPECT_NEAR(fit->amplitude, std::cbrt(1.1), 1e-14);
  EXPECT_NEAR(fit->max_relative_misfit, 1.0 - std::pow(1.1, -2.0 / 3.0), 1e-14);
}

TEST(PowerLawFit, LeavesOutPointsAtOrBelowTheLimitAndNonFiniteOnes) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> x = {0.04, 0.02, 0.01, 0.005, -1.0};
  const std::vector<double> y = {3.0, nan, 2.5, 2.0 + 0.5 * std::pow(0.005, 1.5), 7.0};
  const auto fit = fit_power_law(x, y, 2.0);
  ASSERT_TRUE(fit.has_value());
  EXPECT_EQ(fit->points, 3);  // 0.04, 0.01 and 0.005; the NaN and x <= 0 are left out
  const auto none = fit_power_law({0.04, 0.02}, {2.0, 1.0}, 2.0);
  EXPECT_FALSE(none.has_value());  // both at or below the limit
  EXPECT_FALSE(fit_power_law({0.02, 0.02}, {3.0, 4.0}, 0.0).has_value());  // one abscissa
}

TEST(PowerLawFit, RejectsMismatchedInput) {
  EXPECT_THROW(fit_power_law({1.0, 2.0}, {1.0}, 0.0), std::invalid_argument);
  EXPECT_THROW(fit_power_law({1.0, 2.0}, {1.0, 2.0}, std::numeric_limits<double>::infinity()),
               std::invalid_argument);
}

}  // namespace
}  // namespace growshell
