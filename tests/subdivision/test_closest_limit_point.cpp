// The closest point on one element's limit surface: against the exact foot point on a
// paraboloid that the Loop surface reproduces, held by the triangle's sides where the foot
// lies outside the element, and from any start in the triangle.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <random>

#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/mesh/mesh_topology.hpp"
#include "libshell/subdivision/closest_limit_point.hpp"
#include "libshell/subdivision/element_patches.hpp"
#include "libshell/subdivision/limit_surface.hpp"
#include "tests/support/paraboloid_foot.hpp"

namespace growshell {
namespace {

constexpr double kCurvature = 1.0;  // z = a ((x - 0.5)^2 + y^2) + shift, a = kCurvature
constexpr double kCentreX = 0.5;

/// A strip [0, 1] x [-0.25, 0.25] whose control points lie on z = a ((x - 0.5)^2 + y^2):
/// the Loop limit of a quadratic is the same quadratic shifted by a constant (every element of
/// the strip is regular), so its limit surface is an exact paraboloid.
struct Paraboloid {
  TriangleMesh mesh;
  ElementPatches patches;
  double shift = 0.0;  // limit z - a rho^2, the same everywhere

  Paraboloid() {
    StripMeshOptions o;
    o.length = 1.0;
    o.width = 0.5;
    o.cells_x = 16;
    o.cells_y = 8;
    mesh = make_strip_mesh(o);
    for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v)
      mesh.vertices(v, 2) = kCurvature * (std::pow(mesh.vertices(v, 0) - kCentreX, 2) +
                                          std::pow(mesh.vertices(v, 1), 2));
    patches = build_element_patches(MeshTopology(mesh));
    const LimitSurfacePoint s = evaluate_limit_surface(mesh.vertices, patches.patch[0], 0.2, 0.3);
    shift = s.position.z() - height_above(s.position);
  }
  double height_above(const Eigen::Vector3d& x) const {
    return kCurvature * (std::pow(x.x() - kCentreX, 2) + std::pow(x.y(), 2));
  }
  /// The exact foot point of p on the paraboloid.
  Eigen::Vector3d foot(const Eigen::Vector3d& p) const {
    return test_support::paraboloid_foot(p, kCurvature, kCentreX, shift);
  }
  /// The element whose limit surface contains the foot (the one whose xy triangle holds it:
  /// x and y are reproduced exactly), and the foot's parameter there.
  int element_of(const Eigen::Vector3d& foot, Eigen::Vector2d& parameter) const {
    for (std::size_t e = 0; e < patches.patch.size(); ++e) {
      const LoopPatch& patch = patches.patch[e];
      const auto corner = [&](int k) {
        return Eigen::Vector2d(mesh.vertices.row(patch.control[patch.corners[k]]).head<2>());
      };
      Eigen::Matrix2d frame;
      frame << corner(1) - corner(0), corner(2) - corner(0);
      const Eigen::Vector2d vw = frame.inverse() * (foot.head<2>() - corner(0));
      if (vw.minCoeff() >= -1e-12 && vw.sum() <= 1.0 + 1e-12) {
        parameter = vw;
        return static_cast<int>(e);
      }
    }
    return -1;
  }
};

TEST(ClosestLimitPoint, TheStripsLimitOfAQuadraticIsThatParaboloidShifted) {
  const Paraboloid s;
  double worst = 0.0;
  for (const LoopPatch& patch : s.patches.patch)
    for (const auto& vw : {Eigen::Vector2d(0.1, 0.1), Eigen::Vector2d(0.6, 0.2),
                           Eigen::Vector2d(0.2, 0.7)}) {
      const LimitSurfacePoint p = evaluate_limit_surface(s.mesh.vertices, patch, vw.x(), vw.y());
      worst = std::max(worst, std::abs(p.position.z() - s.height_above(p.position) - s.shift));
    }
  EXPECT_LT(worst, 1e-14);
  EXPECT_GT(std::abs(s.shift), 1e-3);  // the shift is real, so the test below needs it
}

TEST(ClosestLimitPoint, FindsTheExactFootOnTheParaboloidFromEveryStart) {
  const Paraboloid s;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> along(0.3, 0.7), across(-0.12, 0.12), height(-0.1, 0.1);
  int checked = 0;
  for (int trial = 0; trial < 40; ++trial) {
    Eigen::Vector3d p(along(rng), across(rng), 0.0);
    p.z() = s.height_above(p) + s.shift + height(rng);
    const Eigen::Vector3d foot = s.foot(p);
    Eigen::Vector2d exact_parameter;
    const int e = s.element_of(foot, exact_parameter);
    ASSERT_GE(e, 0);
    for (const auto& start : {Eigen::Vector2d(1.0 / 3.0, 1.0 / 3.0), Eigen::Vector2d(0.0, 0.0),
                              Eigen::Vector2d(0.0, 1.0), Eigen::Vector2d(2.0, -1.0)}) {
      const ClosestLimitPoint c =
          closest_limit_point(s.mesh.vertices, s.patches.patch[static_cast<std::size_t>(e)], p, start);
      ASSERT_TRUE(c.converged) << "trial " << trial;
      EXPECT_LT((c.position - foot).norm(), 1e-12) << "trial " << trial;
      EXPECT_LT((c.parameter - exact_parameter).norm(), 1e-10) << "trial " << trial;
      EXPECT_NEAR(std::sqrt(2.0 * c.half_squared_distance), (p - foot).norm(), 1e-13);
      EXPECT_LE(c.iterations, 12);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 160);
}

TEST(ClosestLimitPoint, AFootOutsideTheElementIsHeldOnTheSideItLeavesBy) {
  const Paraboloid s;
  const Eigen::Vector3d p0(0.5, 0.0, s.shift + 0.05);
  Eigen::Vector2d vw;
  const int e = s.element_of(s.foot(p0), vw);
  ASSERT_GE(e, 0);
  const LoopPatch& patch = s.patches.patch[static_cast<std::size_t>(e)];
  // Move the point far along -x: its foot leaves the element through a side, and the
  // minimiser on the triangle is the foot's nearest point on that side: every point of the
  // side is farther from p, and the gradient along the side vanishes there.
  const Eigen::Vector3d p = p0 + Eigen::Vector3d(-0.2, 0.01, 0.0);
  const ClosestLimitPoint c = closest_limit_point(s.mesh.vertices, patch, p, Eigen::Vector2d(0.3, 0.3));
  ASSERT_TRUE(c.converged);
  EXPECT_NE(c.active, 0);
  const double d = std::sqrt(2.0 * c.half_squared_distance);
  EXPECT_GT(d, (p - s.foot(p)).norm() + 1e-3);
  for (double t = 0.0; t <= 1.0; t += 1.0 / 64.0) {
    for (const Eigen::Vector2d& q : {Eigen::Vector2d(0.0, t), Eigen::Vector2d(t, 0.0),
                                     Eigen::Vector2d(t, 1.0 - t)}) {
      const LimitSurfacePoint x = evaluate_limit_surface(s.mesh.vertices, patch, q.x(), q.y());
      EXPECT_GE((p - x.position).norm(), d - 1e-14);
    }
  }
}

TEST(ClosestLimitPoint, ClampsTheStartIntoTheTriangle) {
  EXPECT_EQ(clamp_to_parameter_triangle(Eigen::Vector2d(0.2, 0.3)), Eigen::Vector2d(0.2, 0.3));
  EXPECT_EQ(clamp_to_parameter_triangle(Eigen::Vector2d(-1.0, -2.0)), Eigen::Vector2d(0.0, 0.0));
  EXPECT_TRUE(clamp_to_parameter_triangle(Eigen::Vector2d(1.0, 1.0)).isApprox(Eigen::Vector2d(0.5, 0.5)));
  EXPECT_TRUE(clamp_to_parameter_triangle(Eigen::Vector2d(-0.5, 0.4)).isApprox(Eigen::Vector2d(0.0, 0.4)));
}

TEST(ClosestLimitPoint, RefusesANonFinitePoint) {
  const Paraboloid s;
  EXPECT_THROW(closest_limit_point(s.mesh.vertices, s.patches.patch[0],
                                   Eigen::Vector3d(0.0, std::nan(""), 0.0), Eigen::Vector2d(0.3, 0.3)),
               std::invalid_argument);
}

}  // namespace
}  // namespace growshell
