// elastic_stretches against closed forms: the flat reference under growth (stretches 1 and
// 1/lambda), a uniform in-plane scaling (s and s), and the smoothed growth's weight.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "libshell/analysis/elastic_stretches.hpp"
#include "libshell/mesh/disc_mesh.hpp"

namespace growshell {
namespace {

ShellModel small_model(double smoothing_radius = 0.0) {
  DiscMeshOptions mesh;
  mesh.rings = 4;
  ShellModelSettings settings;
  settings.thickness = constant_thickness(0.02);
  settings.growth.smoothing_radius = smoothing_radius;
  return ShellModel(make_disc_mesh(mesh), settings);
}

TEST(ElasticStretches, FlatReferenceUnderGrowthIsShortByLambdaAlongTheCircles) {
  // The unrelaxed flat sheet has the reference metric, the target is longer by lambda along
  // the circles: stretches 1 (radial) and 1/lambda (circumferential) at every point.
  const ShellModel model = small_model();
  const double phi = 3.0, lambda = 1 + phi / (2 * std::numbers::pi);
  const auto points = elastic_stretches(model, model.reference_positions(), phi, 10.0);
  ASSERT_EQ(static_cast<Eigen::Index>(points.size()),
            model.num_elements() * model.reference().points_per_element());
  for (const PointStretches& p : points) {
    EXPECT_NEAR(p.larger, 1.0, 1e-12);
    EXPECT_NEAR(p.smaller, 1.0 / lambda, 1e-12);
  }
}

TEST(ElasticStretches, UniformScalingWithoutGrowthStretchesBothWaysAlike) {
  const ShellModel model = small_model();
  const double s = 1.3;
  const Eigen::VectorXd x = s * model.reference_positions();
  const auto points = elastic_stretches(model, x, 0.0, 0.5);
  ASSERT_FALSE(points.empty());
  for (const PointStretches& p : points) {
    EXPECT_LE(p.radius, 0.5);
    EXPECT_NEAR(p.smaller, s, 1e-12);
    EXPECT_NEAR(p.larger, s, 1e-12);
  }
  EXPECT_THROW(elastic_stretches(model, x.head(3), 0.0, 0.5), std::invalid_argument);
  EXPECT_THROW(elastic_stretches(model, x, 0.0, -1.0), std::invalid_argument);
}

TEST(ElasticStretches, SmoothedGrowthLeavesTheCentreUngrown) {
  // With smoothing radius eps the circumferential stretch of the flat reference is
  // 1 / (1 + w(r) phi / (2 pi)), w = r^2 / (r^2 + eps^2).
  const double eps = 0.2, phi = 3.0;
  const ShellModel model = small_model(eps);
  for (const PointStretches& p : elastic_stretches(model, model.reference_positions(), phi, 10.0)) {
    const double w = p.radius * p.radius / (p.radius * p.radius + eps * eps);
    EXPECT_NEAR(p.smaller, 1.0 / (1 + w * phi / (2 * std::numbers::pi)), 1e-12);
    EXPECT_NEAR(p.larger, 1.0, 1e-12);
  }
}

}  // namespace
}  // namespace growshell
