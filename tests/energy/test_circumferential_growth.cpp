// The circumferential growth law: the target metric in closed form, with and without the
// smoothed centre, and its derivative in phi_e against central differences.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <utility>

#include "libshell/energy/circumferential_growth.hpp"

namespace growshell {
namespace {

// The flat reference with A = I: at X = (r, 0, 0) the circumferential direction is e_y, so
// abar = diag(1, lambda(r)^2) with lambda(r) = 1 + w(r) phi_e / (2 pi).
const Eigen::Matrix<double, 3, 2> kFlatTangents = Eigen::Matrix<double, 3, 2>::Identity();

TEST(CircumferentialGrowth, PointGrowthIsTheSameAtEveryRadius) {
  const CircumferentialGrowth growth;
  const double phi = 3.0, lambda = 1 + phi / (2 * std::numbers::pi);
  for (double r : {1e-6, 0.01, 1.0}) {
    const Eigen::Matrix2d abar = target_metric(growth, {r, 0, 0}, kFlatTangents, phi);
    EXPECT_NEAR(abar(0, 0), 1.0, 1e-15);
    EXPECT_NEAR(abar(1, 1), lambda * lambda, 1e-14);
    EXPECT_NEAR(abar(0, 1), 0.0, 1e-15);
  }
}

TEST(CircumferentialGrowth, SmoothedGrowthRisesFromNoneAtTheCentreToFullFarAway) {
  CircumferentialGrowth growth;
  growth.smoothing_radius = 0.01;
  EXPECT_EQ(excess_angle_weight(growth, 0.0), 0.0);
  EXPECT_NEAR(excess_angle_weight(growth, 0.01), 0.5, 1e-15);
  EXPECT_NEAR(excess_angle_weight(growth, 1.0), 1.0 / (1.0 + 1e-4), 1e-15);
  const double phi = 3.0;
  for (double r : {1e-4, 0.01, 0.1}) {
    const double w = r * r / (r * r + 1e-4), lambda = 1 + w * phi / (2 * std::numbers::pi);
    const Eigen::Matrix2d abar = target_metric(growth, {r, 0, 0}, kFlatTangents, phi);
    EXPECT_NEAR(abar(1, 1), lambda * lambda, 1e-14) << "r = " << r;
    EXPECT_NEAR(abar(0, 0), 1.0, 1e-15);
  }
}

TEST(CircumferentialGrowth, GaussianProfileChangesTheGrowthOnlyInsideTheCore) {
  CircumferentialGrowth growth;
  growth.smoothing_radius = 0.01;
  growth.smoothing_profile = GrowthSmoothingProfile::Gaussian;
  EXPECT_EQ(excess_angle_weight(growth, 0.0), 0.0);
  EXPECT_NEAR(excess_angle_weight(growth, 0.01), 1.0 - std::exp(-1.0), 1e-15);
  EXPECT_NEAR(excess_angle_weight(growth, 1e-4), 1e-4 - 0.5e-8 + 1e-12 / 6, 1e-17);  // x - x^2/2 + x^3/6, x = (r/eps)^2
  EXPECT_GT(excess_angle_weight(growth, 0.03), 1.0 - 1.3e-4);   // 1 - e^-9 at 3 eps
  EXPECT_EQ(excess_angle_weight(growth, 0.1), 1.0);             // e^-100 below rounding
  const double phi = 3.0;
  const double w = 1.0 - std::exp(-4.0), lambda = 1 + w * phi / (2 * std::numbers::pi);
  EXPECT_NEAR(target_metric(growth, {0.0, 0.02, 0}, kFlatTangents, phi)(0, 0), lambda * lambda,
              1e-14);  // on the y axis the circumferential direction is -x
}

TEST(CircumferentialGrowth, ExcessAngleDerivativeMatchesCentralDifferences) {
  // Central differences with step 1e-5 on the quadratic lambda^2: exact up to rounding.
  const std::pair<double, GrowthSmoothingProfile> cases[] = {
      {0.0, GrowthSmoothingProfile::Rational},
      {0.03, GrowthSmoothingProfile::Rational},
      {0.03, GrowthSmoothingProfile::Gaussian}};
  for (const auto& [eps, profile] : cases) {
    CircumferentialGrowth growth;
    growth.smoothing_radius = eps;
    growth.smoothing_profile = profile;
    Eigen::Matrix<double, 3, 2> A;
    A << 1.1, 0.2, -0.1, 0.9, 0.05, 0.1;  // a tilted, sheared reference
    const Eigen::Vector3d X(0.02, -0.03, 0.0);
    const double phi = 2.0, step = 1e-5;
    const Eigen::Matrix2d fd = (target_metric(growth, X, A, phi + step) -
                                target_metric(growth, X, A, phi - step)) / (2 * step);
    const Eigen::Matrix2d exact = target_metric_excess_angle_derivative(growth, X, A, phi);
    EXPECT_LE((fd - exact).norm(), 1e-9 * exact.norm()) << "epsilon = " << eps << ", profile " << static_cast<int>(profile);
  }
}

}  // namespace
}  // namespace growshell
