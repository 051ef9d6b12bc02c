// The distance from a point of the sheet to the limit surface: the exact distance to a
// paraboloid that the Loop surface reproduces, found from any element of the foot's
// neighbourhood; its gradient and Hessian in every control point against central differences,
// on a rough surface, with the foot inside an element, on an edge between two, held on the side
// of a one-element candidate set, and with the point sharing control points with the surface;
// and the errors for bad input.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <algorithm>
#include <functional>
#include <random>
#include <stdexcept>

#include "libshell/contact/limit_surface_distance.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/mesh/mesh_topology.hpp"
#include "libshell/subdivision/closest_limit_point.hpp"
#include "libshell/subdivision/element_neighbourhood.hpp"
#include "libshell/subdivision/limit_surface.hpp"
#include "tests/support/expect_invalid_argument.hpp"
#include "tests/support/paraboloid_foot.hpp"

namespace growshell {
namespace {

using test_support::expect_invalid_argument_containing;

/// A curved strip [0, 1] x [-0.25, 0.25] (16 x 8 cells) on z = a ((x - 0.5)^2 + y^2), a = 1,
/// optionally roughened, with three extra rows of positions after the mesh's vertices that
/// carry the point p = 0.2 P0 + 0.5 P1 + 0.3 P2.
struct CurvedStrip {
  TriangleMesh mesh;
  MeshTopology topology;
  ElementPatches patches;
  std::vector<std::vector<int>> around;
  Eigen::MatrixX3d positions;  // the mesh's control points, then P0, P1, P2
  ControlPointCombination point;
  Eigen::Index mesh_vertices = 0;

  explicit CurvedStrip(double roughness)
      : mesh(make_strip(roughness)), topology(mesh), patches(build_element_patches(topology)),
        around(element_neighbourhoods(topology, patches)) {
    mesh_vertices = mesh.vertices.rows();
    positions.resize(mesh_vertices + 3, 3);
    positions.topRows(mesh_vertices) = mesh.vertices;
    point.vertex = {static_cast<int>(mesh_vertices), static_cast<int>(mesh_vertices + 1),
                    static_cast<int>(mesh_vertices + 2)};
    point.weight = {0.2, 0.5, 0.3};
  }
  static TriangleMesh make_strip(double roughness) {
    StripMeshOptions o;
    o.length = 1.0;
    o.width = 0.5;
    o.cells_x = 16;
    o.cells_y = 8;
    TriangleMesh m = make_strip_mesh(o);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> noise(-1.0, 1.0);
    for (Eigen::Index v = 0; v < m.vertices.rows(); ++v) {
      m.vertices(v, 2) = std::pow(m.vertices(v, 0) - 0.5, 2) + std::pow(m.vertices(v, 1), 2);
      for (int c = 0; c < 3; ++c) m.vertices(v, c) += roughness * noise(rng);
    }
    return m;
  }
  /// Places the point's three rows around `p` (their combination is p).
  void place_point(const Eigen::Vector3d& p) {
    positions.row(mesh_vertices) = (p + Eigen::Vector3d(0.02, -0.01, 0.005)).transpose();
    positions.row(mesh_vertices + 1) = (p + Eigen::Vector3d(-0.01, 0.012, -0.004)).transpose();
    const Eigen::Vector3d rest = (p - 0.2 * positions.row(mesh_vertices).transpose() -
                                  0.5 * positions.row(mesh_vertices + 1).transpose()) /
                                 0.3;
    positions.row(mesh_vertices + 2) = rest.transpose();
  }
  /// Every element, as a candidate list.
  std::vector<int> all_elements() const {
    std::vector<int> all(patches.patch.size());
    for (std::size_t e = 0; e < all.size(); ++e) all[e] = static_cast<int>(e);
    return all;
  }
  /// The element whose corners' (x, y) triangle holds (x, y).
  int element_at(double x, double y) const {
    for (std::size_t e = 0; e < patches.patch.size(); ++e) {
      const LoopPatch& patch = patches.patch[e];
      const auto corner = [&](int k) {
        return Eigen::Vector2d(positions.row(patch.control[static_cast<std::size_t>(patch.corners[static_cast<std::size_t>(k)])]).head<2>());
      };
      Eigen::Matrix2d frame;
      frame << corner(1) - corner(0), corner(2) - corner(0);
      const Eigen::Vector2d vw = frame.inverse() * (Eigen::Vector2d(x, y) - corner(0));
      if (vw.minCoeff() >= 0.0 && vw.sum() <= 1.0) return static_cast<int>(e);
    }
    return -1;
  }
  /// The surface point at parameter (v, w) of element e.
  Eigen::Vector3d surface(int e, double v, double w) const {
    return evaluate_limit_surface(positions, patches.patch[static_cast<std::size_t>(e)], v, w)
        .position;
  }
};

/// Largest |analytic - central difference| of the gradient and of the Hessian, relative to the
/// largest analytic entry, over every coordinate of every vertex the distance depends on, with
/// the candidate set fixed.
struct DistanceFdErrors {
  double gradient = 0.0, hessian = 0.0;
};
DistanceFdErrors distance_fd_errors(const CurvedStrip& s, const ControlPointCombination& point,
                                    const std::vector<int>& candidates) {
  const LimitSurfaceDistance at =
      limit_surface_distance(s.positions, s.patches, point, candidates, true);
  const double step = 1e-6;
  const auto n = static_cast<Eigen::Index>(3 * at.vertices.size());
  Eigen::VectorXd g_fd(n);
  Eigen::MatrixXd h_fd(n, n);
  for (std::size_t j = 0; j < at.vertices.size(); ++j)
    for (int c = 0; c < 3; ++c) {
      Eigen::MatrixX3d plus = s.positions, minus = s.positions;
      plus(at.vertices[j], c) += step;
      minus(at.vertices[j], c) -= step;
      const LimitSurfaceDistance up = limit_surface_distance(plus, s.patches, point, candidates, false);
      const LimitSurfaceDistance down = limit_surface_distance(minus, s.patches, point, candidates, false);
      const auto k = static_cast<Eigen::Index>(3 * j + static_cast<std::size_t>(c));
      g_fd(k) = (up.distance - down.distance) / (2.0 * step);
      // The gradients on the vertex list of `at` (the perturbed runs may have chosen another
      // element, whose vertices are ordered differently).
      Eigen::VectorXd gu = Eigen::VectorXd::Zero(n), gd = Eigen::VectorXd::Zero(n);
      for (std::size_t i = 0; i < at.vertices.size(); ++i)
        for (std::size_t q = 0; q < up.vertices.size(); ++q) {
          if (up.vertices[q] == at.vertices[i])
            gu.segment<3>(static_cast<Eigen::Index>(3 * i)) = up.gradient.segment<3>(static_cast<Eigen::Index>(3 * q));
        }
      for (std::size_t i = 0; i < at.vertices.size(); ++i)
        for (std::size_t q = 0; q < down.vertices.size(); ++q)
          if (down.vertices[q] == at.vertices[i])
            gd.segment<3>(static_cast<Eigen::Index>(3 * i)) = down.gradient.segment<3>(static_cast<Eigen::Index>(3 * q));
      h_fd.col(k) = (gu - gd) / (2.0 * step);
    }
  return {(at.gradient - g_fd).cwiseAbs().maxCoeff() / at.gradient.cwiseAbs().maxCoeff(),
          (at.hessian - h_fd).cwiseAbs().maxCoeff() / at.hessian.cwiseAbs().maxCoeff()};
}

TEST(LimitSurfaceDistance, IsTheExactDistanceToTheReproducedParaboloidFromAnyElementAroundTheFoot) {
  CurvedStrip s(0.0);
  const double shift = s.surface(0, 0.2, 0.3).z() -
                       (std::pow(s.surface(0, 0.2, 0.3).x() - 0.5, 2) + std::pow(s.surface(0, 0.2, 0.3).y(), 2));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> along(0.35, 0.65), across(-0.1, 0.1), height(0.02, 0.08);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::Vector3d p(along(rng), across(rng), 0.0);
    const double side = trial % 2 == 0 ? 1.0 : -1.0;
    p.z() = std::pow(p.x() - 0.5, 2) + std::pow(p.y(), 2) + shift + side * height(rng);
    s.place_point(p);
    const Eigen::Vector3d foot = test_support::paraboloid_foot(p, 1.0, 0.5, shift);
    int foot_element = -1;
    for (std::size_t e = 0; e < s.patches.patch.size() && foot_element < 0; ++e) {
      const LimitSurfaceDistance d =
          limit_surface_distance(s.positions, s.patches, s.point, {static_cast<int>(e)}, false);
      if (d.active == 0 && (d.closest - foot).norm() < 1e-10) foot_element = static_cast<int>(e);
    }
    ASSERT_GE(foot_element, 0) << "trial " << trial;
    for (int other : s.around[static_cast<std::size_t>(foot_element)]) {
      const LimitSurfaceDistance d = limit_surface_distance(
          s.positions, s.patches, s.point, s.around[static_cast<std::size_t>(other)], false);
      EXPECT_NEAR(d.distance, (p - foot).norm(), 1e-13) << "trial " << trial;
      EXPECT_LT((d.closest - foot).norm(), 1e-12) << "trial " << trial;
      EXPECT_EQ(d.active, 0);
      // The gradient with respect to the point's own coordinates is the unit normal direction
      // (p - foot) / d times each weight.
      const Eigen::Vector3d unit = (p - foot).normalized();
      for (int k = 0; k < 3; ++k)
        EXPECT_LT((d.gradient.segment<3>(3 * k) - s.point.weight[static_cast<std::size_t>(k)] * unit).norm(), 1e-11);
    }
  }
}

TEST(LimitSurfaceDistance, GradientAndHessianMatchCentralDifferencesOnARoughSurface) {
  CurvedStrip s(0.004);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> along(0.35, 0.65), across(-0.1, 0.1), height(0.03, 0.08);
  for (int trial = 0; trial < 6; ++trial) {
    Eigen::Vector3d p(along(rng), across(rng), 0.0);
    p.z() = std::pow(p.x() - 0.5, 2) + std::pow(p.y(), 2) + (trial % 2 == 0 ? 1.0 : -1.0) * height(rng);
    s.place_point(p);
    const LimitSurfaceDistance d =
        limit_surface_distance(s.positions, s.patches, s.point, s.all_elements(), true);
    EXPECT_EQ(d.active, 0);
    const std::vector<int> candidates = s.around[static_cast<std::size_t>(d.element)];
    const DistanceFdErrors e = distance_fd_errors(s, s.point, candidates);
    EXPECT_LT(e.gradient, 1e-7) << "trial " << trial;
    EXPECT_LT(e.hessian, 1e-5) << "trial " << trial;
    // The surface's own control points move the distance as much as the point's.
    EXPECT_EQ(d.vertices.size(), 3U + 12U);
  }
}

TEST(LimitSurfaceDistance, DerivativesHoldWhereTheFootCrossesFromOneElementToTheNext) {
  CurvedStrip s(0.004);
  // The point straight above (along the normal) a point of an interior edge of a central
  // element, then moved by 1e-9 m across it: the central differences take the foot into both
  // elements.
  const int centre = s.element_at(0.52, 0.01);
  ASSERT_GE(centre, 0);
  const auto& around = s.around[static_cast<std::size_t>(centre)];
  ASSERT_EQ(around.size(), 13U);
  const LoopPatch& patch = s.patches.patch[static_cast<std::size_t>(centre)];
  const LimitSurfacePoint x = evaluate_limit_surface(s.positions, patch, 0.5, 0.5);
  s.place_point(x.position + 0.05 * x.normal + 1e-9 * x.tangents.col(0).normalized());
  const LimitSurfaceDistance d = limit_surface_distance(s.positions, s.patches, s.point, around, true);
  EXPECT_EQ(d.active, 0);
  // The foot lies within 1e-7 of the edge, in the element or its neighbour across it.
  EXPECT_LT((d.closest - x.position).norm(), 1e-7);
  const DistanceFdErrors e = distance_fd_errors(s, s.point, around);
  EXPECT_LT(e.gradient, 1e-7);
  EXPECT_LT(e.hessian, 1e-5);
}

TEST(LimitSurfaceDistance, AFootHeldOnTheSideOfAOneElementSetHasTheDerivativesOfThatConstrainedMinimum) {
  CurvedStrip s(0.004);
  const int centre = s.element_at(0.52, 0.01);
  ASSERT_GE(centre, 0);
  const LimitSurfacePoint x = evaluate_limit_surface(s.positions, s.patches.patch[static_cast<std::size_t>(centre)], 0.3, 0.3);
  s.place_point(x.position + 0.05 * x.normal + 0.08 * x.tangents.col(0).normalized());
  const LimitSurfaceDistance d = limit_surface_distance(s.positions, s.patches, s.point, {centre}, true);
  EXPECT_NE(d.active, 0);
  const DistanceFdErrors e = distance_fd_errors(s, s.point, {centre});
  EXPECT_LT(e.gradient, 1e-7);
  EXPECT_LT(e.hessian, 1e-5);
}

TEST(LimitSurfaceDistance, APointThatIsAControlPointOfTheSurfaceHasItsWeightsMerged) {
  // A curved surface's control point lies off its limit surface; its distance to the surface
  // depends on it twice, as the point and through the elements around it.
  CurvedStrip s(0.004);
  const int centre = s.element_at(0.52, 0.01);
  ASSERT_GE(centre, 0);
  const LoopPatch& patch = s.patches.patch[static_cast<std::size_t>(centre)];
  const int vertex = patch.control[static_cast<std::size_t>(patch.corners[0])];
  s.positions(vertex, 2) += 0.05;
  const ControlPointCombination point{{vertex}, {1.0}};
  const auto& around = s.around[static_cast<std::size_t>(centre)];
  const LimitSurfaceDistance d = limit_surface_distance(s.positions, s.patches, point, around, true);
  EXPECT_EQ(d.vertices.front(), vertex);
  EXPECT_EQ(std::count(d.vertices.begin(), d.vertices.end(), vertex), 1);
  const DistanceFdErrors e = distance_fd_errors(s, point, around);
  EXPECT_LT(e.gradient, 1e-7);
  EXPECT_LT(e.hessian, 1e-5);
}

TEST(LimitSurfaceDistance, RefusesBadInputByName) {
  CurvedStrip s(0.0);
  s.place_point(Eigen::Vector3d(0.5, 0.0, 0.1));
  expect_invalid_argument_containing(
      [&] { limit_surface_distance(s.positions, s.patches, s.point, {}, false); },
      "no candidate elements");
  expect_invalid_argument_containing(
      [&] { limit_surface_distance(s.positions, s.patches, s.point, {100000}, false); },
      "candidate element 100000");
  expect_invalid_argument_containing(
      [&] { limit_surface_distance(s.positions, s.patches, {{0, 1}, {1.0}}, {0}, false); },
      "2 vertices and 1 weights");
  expect_invalid_argument_containing(
      [&] { limit_surface_distance(s.positions, s.patches, {{-3}, {1.0}}, {0}, false); },
      "point vertex -3");
  Eigen::MatrixX3d bad = s.positions;
  bad(s.patches.patch[0].control[0], 1) = std::nan("");
  expect_invalid_argument_containing(
      [&] { limit_surface_distance(bad, s.patches, s.point, {0}, false); }, "is not finite");
  // A point on the surface: the distance is zero and not differentiable.
  const int centre = s.element_at(0.52, 0.01);
  s.place_point(s.surface(centre, 0.25, 0.25));
  EXPECT_THROW(limit_surface_distance(s.positions, s.patches, s.point,
                                      s.around[static_cast<std::size_t>(centre)], false),
               std::domain_error);
}

}  // namespace
}  // namespace growshell
