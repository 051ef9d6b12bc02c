// first_vertex_triangle_crossing and vertex_triangle_crossing_time: passages of a vertex
// through a triangle on a straight path, against closed forms, against a dense scan of the
// path for random motions, and on a folded sheet whose upper layer is pushed through the lower.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "libshell/contact/straight_path_crossing.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "support/sheet_states.hpp"

namespace growshell {
namespace {

using Corners = Eigen::Matrix<double, 4, 3>;

/// Rows p, a, b, c: the unit right triangle in z = 0 and a vertex p.
Corners flat_triangle_with(const Eigen::Vector3d& p) {
  Corners q;
  q << p.transpose(), 0, 0, 0, 1, 0, 0, 0, 1, 0;
  return q;
}

TEST(StraightPathCrossing, AVertexFallingThroughATriangleCrossesWhereItMeetsThePlane) {
  const Corners start = flat_triangle_with({0.2, 0.3, 1.0});
  const Corners end = flat_triangle_with({0.2, 0.3, -3.0});
  const std::optional<double> t = vertex_triangle_crossing_time(start, end);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 0.25, 1e-14);
  // Back up the same line: the same passage, at 1 - 0.25.
  const std::optional<double> back = vertex_triangle_crossing_time(end, start);
  ASSERT_TRUE(back.has_value());
  EXPECT_NEAR(*back, 0.75, 1e-14);
}

TEST(StraightPathCrossing, NoPassageBesideTheTriangleShortOfItOrAlongIt) {
  // Through the plane beside the triangle (x + y > 1).
  EXPECT_FALSE(vertex_triangle_crossing_time(flat_triangle_with({0.6, 0.6, 1.0}),
                                             flat_triangle_with({0.6, 0.6, -1.0})));
  // Towards it but stopping short.
  EXPECT_FALSE(vertex_triangle_crossing_time(flat_triangle_with({0.2, 0.3, 1.0}),
                                             flat_triangle_with({0.2, 0.3, 1e-6})));
  // Parallel to it, above it.
  EXPECT_FALSE(vertex_triangle_crossing_time(flat_triangle_with({0.2, 0.3, 0.1}),
                                             flat_triangle_with({0.7, 0.1, 0.1})));
  // In its plane from the start (a flat sheet: every pair coplanar), sliding beside it.
  EXPECT_FALSE(vertex_triangle_crossing_time(flat_triangle_with({1.0, 1.0, 0.0}),
                                             flat_triangle_with({2.0, 1.5, 0.0})));
}

TEST(StraightPathCrossing, ATriangleSweptThroughAStillVertexCrossesIt) {
  Corners start = flat_triangle_with({0.25, 0.25, 0.0});
  Corners end = start;
  start.block<3, 1>(1, 2).setConstant(-0.5);
  end.block<3, 1>(1, 2).setConstant(1.5);
  const std::optional<double> t = vertex_triangle_crossing_time(start, end);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 0.25, 1e-14);
}

TEST(StraightPathCrossing, TheEarliestPassageOfATiltingTriangleAgreesWithADenseScanOfThePath) {
  // Random straight motions of all four points: the signed volume is a cubic with up to three
  // roots. The reference scans tau on a grid of 20000 intervals for a strict change of side
  // with the vertex inside the triangle at the interpolated root; it can miss a passage
  // between two grid points only by a double crossing in one interval, which a generic motion
  // does not have.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int crossing = 0, clear = 0;
  for (int trial = 0; trial < 400; ++trial) {
    Corners start, end;
    for (int i = 0; i < 4; ++i)
      for (int c = 0; c < 3; ++c) {
        start(i, c) = u(rng);
        end(i, c) = u(rng);
      }
    const auto volume = [&](double tau) {
      const Corners q = start + tau * (end - start);
      const Eigen::Vector3d p = q.row(0), a = q.row(1), b = q.row(2), c = q.row(3);
      return (p - a).dot((b - a).cross(c - a));
    };
    std::optional<double> expected;
    bool ambiguous = false;
    const int grid = 20000;
    for (int k = 0; k < grid && !expected && !ambiguous; ++k) {
      const double t0 = double(k) / grid, t1 = double(k + 1) / grid;
      const double f0 = volume(t0), f1 = volume(t1);
      if (!(f0 * f1 < 0.0)) continue;
      const double root = t0 + (t1 - t0) * f0 / (f0 - f1);
      const Corners q = start + root * (end - start);
      const Eigen::Vector3d p = q.row(0), a = q.row(1), b = q.row(2), c = q.row(3);
      const Eigen::Vector3d n = (b - a).cross(c - a);
      const double least = std::min({(b - p).cross(c - p).dot(n), (c - p).cross(a - p).dot(n),
                                     (a - p).cross(b - p).dot(n)});
      // Far enough inside or outside that the grid's interpolation cannot flip the verdict;
      // a motion that passes within that of an edge is left out.
      const double margin = 1e-4 * n.squaredNorm();
      if (least > margin)
        expected = root;
      else if (least > -margin)
        ambiguous = true;
    }
    if (ambiguous) continue;
    const std::optional<double> got = vertex_triangle_crossing_time(start, end);
    ASSERT_EQ(got.has_value(), expected.has_value()) << "trial " << trial;
    if (got) {
      EXPECT_NEAR(*got, *expected, 1e-6) << "trial " << trial;
      ++crossing;
    } else {
      ++clear;
    }
  }
  // Both outcomes are exercised.
  EXPECT_GT(crossing, 20);
  EXPECT_GT(clear, 20);
}

class FoldedSheetPath : public ::testing::Test {
 protected:
  FoldedSheetPath() : model(make_disc_mesh(mesh_options()), ShellModelSettings{}),
                      proxy(make_contact_proxy(model, 1)) {}
  static DiscMeshOptions mesh_options() {
    DiscMeshOptions mesh;
    mesh.rings = 8;
    return mesh;
  }
  ShellModel model;
  ContactProxy proxy;
};

TEST_F(FoldedSheetPath, PushingTheUpperLayerThroughTheLowerIsACrossing) {
  // Layers 0.08 m apart (fold radius 0.04), wobble 0.01 m: the upper layer (z > 0.06) moved
  // down by 0.16 m meets the lower where it has covered their gap, 0.06 .. 0.1 m of it.
  const Eigen::VectorXd x0 = test_support::folded_sheet(model, 0.0, 0.04, 0.01);
  Eigen::VectorXd x1 = x0;
  for (Eigen::Index v = 0; v < x0.size() / 3; ++v)
    if (x0[3 * v + 2] > 0.06) x1[3 * v + 2] -= 0.16;
  const std::optional<PathCrossing> hit = first_vertex_triangle_crossing(proxy, x0, x1, 0.2);
  ASSERT_TRUE(hit.has_value());
  EXPECT_GT(hit->time, 0.06 / 0.16 - 1e-9);
  EXPECT_LT(hit->time, 0.10 / 0.16 + 1e-9);
  // A quarter of the way down the layers have not met yet.
  const Eigen::VectorXd quarter = x0 + 0.25 * (x1 - x0);
  EXPECT_FALSE(first_vertex_triangle_crossing(proxy, x0, quarter, 0.2).has_value());
}

TEST_F(FoldedSheetPath, ClosingTheFoldOrMovingTheSheetRigidlyCrossesNothing) {
  const Eigen::VectorXd x0 = test_support::folded_sheet(model, 0.0, 0.04, 0.01);
  // The fold closed to layers 0.04 m apart: they approach but do not pass.
  const Eigen::VectorXd closer = test_support::folded_sheet(model, 0.0, 0.02, 0.01);
  EXPECT_FALSE(first_vertex_triangle_crossing(proxy, x0, closer, 0.2).has_value());
  // A rigid translation and a rigid turn about z by 0.3 rad.
  Eigen::VectorXd moved = x0, turned = x0;
  const double c = std::cos(0.3), s = std::sin(0.3);
  for (Eigen::Index v = 0; v < x0.size() / 3; ++v) {
    moved.segment<3>(3 * v) += Eigen::Vector3d(0.3, -0.2, 0.5);
    turned[3 * v] = c * x0[3 * v] - s * x0[3 * v + 1];
    turned[3 * v + 1] = s * x0[3 * v] + c * x0[3 * v + 1];
  }
  EXPECT_FALSE(first_vertex_triangle_crossing(proxy, x0, moved, 0.2).has_value());
  EXPECT_FALSE(first_vertex_triangle_crossing(proxy, x0, turned, 0.2).has_value());
  // No motion, nothing to cross.
  EXPECT_FALSE(first_vertex_triangle_crossing(proxy, x0, x0, 0.2).has_value());
}

TEST_F(FoldedSheetPath, StatesOfTheWrongSizeAndBadExclusionRadiiAreRefused) {
  const Eigen::VectorXd x0 = model.reference_positions();
  EXPECT_THROW(first_vertex_triangle_crossing(proxy, x0, x0.head(x0.size() - 3), 0.2),
               std::invalid_argument);
  EXPECT_THROW(first_vertex_triangle_crossing(proxy, x0, x0, -1.0), std::invalid_argument);
  EXPECT_THROW(first_vertex_triangle_crossing(proxy, x0, x0, std::nan("")),
               std::invalid_argument);
}

}  // namespace
}  // namespace growshell
