// Fold counting on exact cones with n folds, in any orientation, shallow and deep.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "libshell/analysis/rim_folds.hpp"
#include "libshell/mesh/disc_mesh.hpp"

namespace growshell {
namespace {

/// Control points of the cone X(r, t) = r (cos t cos b, sin t cos b, sin b), b = a cos(n t),
/// rotated by `rotation`: a cone whose generator directions oscillate n times about a great
/// circle with elevation amplitude a (radians).
Eigen::VectorXd oscillating_cone_state(const ShellModel& model, int n, double a,
                                       const Eigen::Matrix3d& rotation) {
  Eigen::VectorXd x = model.reference_positions();
  for (Eigen::Index v = 0; v < x.size() / 3; ++v) {
    const double r = std::hypot(x(3 * v), x(3 * v + 1)), t = std::atan2(x(3 * v + 1), x(3 * v));
    const double b = a * std::cos(n * t);
    x.segment<3>(3 * v) =
        rotation * Eigen::Vector3d(r * std::cos(t) * std::cos(b), r * std::sin(t) * std::cos(b),
                                   r * std::sin(b));
  }
  return x;
}

TEST(RimFolds, CountsTheFoldsOfConesInAnyOrientation) {
  DiscMeshOptions o;
  o.rings = 10;
  ShellModel model(make_disc_mesh(o), ShellModelSettings{});
  const Eigen::Matrix3d tilt =
      Eigen::AngleAxisd(0.9, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  for (int n : {2, 3, 4}) {
    for (double a : {0.05, 0.4, 1.0}) {
      for (const Eigen::Matrix3d& R : {Eigen::Matrix3d(Eigen::Matrix3d::Identity()), tilt}) {
        const RimFoldAnalysis rim =
            analyze_rim_folds(model, oscillating_cone_state(model, n, a, R));
        EXPECT_EQ(rim.folds, n) << "n = " << n << ", amplitude " << a;
        // sin(a cos(n t)) has the n-th Fourier amplitude 2 J_1(a) (Jacobi-Anger); the curve's
        // m = n power also holds nothing else for these n. Sampling on the rim vertices is
        // exact for these smooth periodic functions; the rim points are limit positions, which
        // average neighbouring generators and lose a share of the amplitude growing like n^2
        // (measured on this mesh: 0.51% for n = 2, 2.4% for n = 4), hence 0.003 n^2.
        EXPECT_NEAR(rim.mode_amplitudes(n), 2.0 * std::cyl_bessel_j(1.0, a),
                    0.003 * n * n * 2.0 * std::cyl_bessel_j(1.0, a))
            << "n = " << n << ", a = " << a;
      }
    }
  }
}

TEST(RimFolds, FlatDiscHasNoElevation) {
  DiscMeshOptions o;
  o.rings = 8;
  ShellModel model(make_disc_mesh(o), ShellModelSettings{});
  const RimFoldAnalysis rim = analyze_rim_folds(model, model.reference_positions());
  EXPECT_EQ(rim.folds, 0);
  // The limit positions of the rim vertices are spaced a little unevenly in angle, which
  // shows as small m = 1 +- 6k content of a planar curve.
  EXPECT_NEAR(rim.mode_amplitudes(1), std::sqrt(2.0), 1e-2);  // cos t in x, sin t in y
}

TEST(RimFolds, RejectsTooManyModesForTheRim) {
  DiscMeshOptions o;
  o.rings = 2;
  ShellModel model(make_disc_mesh(o), ShellModelSettings{});
  EXPECT_THROW(analyze_rim_folds(model, model.reference_positions(), 20), std::invalid_argument);
  EXPECT_THROW(analyze_rim_folds(model, model.reference_positions(), 1), std::invalid_argument);
}

}  // namespace
}  // namespace growshell
