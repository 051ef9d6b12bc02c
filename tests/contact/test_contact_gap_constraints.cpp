// Contact gap constraints: values against independent computations (a point over a triangle,
// crossing and nearly parallel edges with the mollifier, two stacked flat layers, sampled
// brute force), Jacobian and weighted Hessian against central differences on a folded disc,
// patterns against the union of stencils and against every nonzero of a finite-difference
// Jacobian and Hessian, zero distance, empty input, bad input.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "libshell/contact/contact_gap_constraints.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "support/dense_symmetric.hpp"
#include "support/sheet_states.hpp"
#include "tests/support/expect_invalid_argument.hpp"
#include "tests/support/folded_disc_scene.hpp"
#include "tests/support/identity_proxy.hpp"

namespace growshell {
namespace {

using test_support::dense_symmetric;
using test_support::folded_sheet;

using test_support::expect_invalid_argument_containing;
using test_support::flatten;
using test_support::FoldedDiscScene;
using test_support::identity_proxy;

/// The offset of the gap constraints on the folded disc (FoldedDiscScene).
constexpr double kFoldedDiscOffset = 0.1;

/// Pair indices whose region and mollifier branch are the same at x - step, x and x + step,
/// so that central differences see one smooth function.
std::vector<char> stable_pairs(const ContactGapConstraints& c, const Eigen::VectorXd& x,
                               const Eigen::VectorXd& step) {
  std::vector<char> stable(static_cast<std::size_t>(c.count()), 1);
  for (Eigen::Index k = 0; k < c.count(); ++k) {
    const ContactPairGeometry g0 = c.pair_geometry(x, k);
    for (const Eigen::VectorXd& xs : {Eigen::VectorXd(x + step), Eigen::VectorXd(x - step)}) {
      const ContactPairGeometry g = c.pair_geometry(xs, k);
      if (g.point_triangle_region != g0.point_triangle_region ||
          g.edge_edge_region != g0.edge_edge_region || (g.mollifier < 1.0) != (g0.mollifier < 1.0))
        stable[static_cast<std::size_t>(k)] = 0;
    }
  }
  return stable;
}

// ---- exact values on hand-made primitives --------------------------------------------------

TEST(ContactGapConstraints, PointOverTriangleMatchesTheClosedForm) {
  // Triangle (0,0,0), (1,0,0), (0,1,0) in z = 0 and points over its face, beside edge ab, beside
  // vertex a and under the face; distances 0.5, 0.5, 0.5 and 0.25 by Pythagoras.
  Eigen::MatrixX3d points(7, 3);
  points << 0, 0, 0, 1, 0, 0, 0, 1, 0,  //
      0.2, 0.3, 0.5,                    // Face, closest (0.2, 0.3, 0)
      0.5, -0.4, 0.3,                   // EdgeAB, closest (0.5, 0, 0)
      -0.3, -0.4, 0.0,                  // VertexA
      0.2, 0.3, -0.25;                  // Face from below
  Eigen::MatrixX3i triangles(1, 3);
  triangles << 0, 1, 2;
  Eigen::MatrixX2i edges(3, 2);
  edges << 0, 1, 0, 2, 1, 2;
  const ContactProxy proxy = identity_proxy(points, triangles, edges);
  ContactCandidates pairs;
  pairs.vertex_triangle.resize(4, 2);
  pairs.vertex_triangle << 3, 0, 4, 0, 5, 0, 6, 0;
  const double offset = 0.1;
  ContactGapConstraints c(proxy, pairs, offset, 21);
  ASSERT_EQ(c.count(), 4);

  const Eigen::VectorXd x = flatten(points);
  Eigen::VectorXd values;
  Eigen::SparseMatrix<double, Eigen::RowMajor> J = c.jacobian_pattern();
  c.evaluate(x, values, &J);
  const Eigen::Vector4d expected(0.5 - offset, 0.5 - offset, 0.5 - offset, 0.25 - offset);
  // Closed forms in binary-exact-ish data: agreement to a few ulps of the 0.5 m distances.
  EXPECT_LT((values - expected).cwiseAbs().maxCoeff(), 1e-15);

  // Gradient = weights (x) unit normal: d/dp = n, d/d(a, b, c) = -beta n.
  const Eigen::MatrixXd Jd = Eigen::MatrixXd(J);
  const std::vector<Eigen::Vector3d> normals = {{0, 0, 1},
                                                Eigen::Vector3d(0, -0.4, 0.3) / 0.5,
                                                Eigen::Vector3d(-0.3, -0.4, 0) / 0.5,
                                                {0, 0, -1}};
  const std::vector<Eigen::Vector3d> beta = {
      {0.5, 0.2, 0.3}, {0.5, 0.5, 0}, {1, 0, 0}, {0.5, 0.2, 0.3}};
  for (int k = 0; k < 4; ++k) {
    Eigen::VectorXd row = Eigen::VectorXd::Zero(21);
    row.segment<3>(3 * (3 + k)) = normals[k];
    for (int i = 0; i < 3; ++i) row.segment<3>(3 * i) = -beta[k](i) * normals[k];
    EXPECT_LT((Jd.row(k).transpose() - row).cwiseAbs().maxCoeff(), 1e-14) << "pair " << k;
    const ContactPairGeometry g = c.pair_geometry(x, k);
    EXPECT_LT((g.normal - normals[k]).norm(), 1e-15) << "pair " << k;
    EXPECT_LT((g.vertex_weights - Eigen::Vector4d(1, -beta[k](0), -beta[k](1), -beta[k](2)))
                  .cwiseAbs()
                  .maxCoeff(),
              1e-15);
    EXPECT_EQ((g.closest_point_first - points.row(3 + k).transpose()).norm(), 0.0);
    EXPECT_NEAR(g.distance, expected(k) + offset, 1e-15);
    EXPECT_EQ(g.mollifier, 1.0);
  }
  // Unknowns beyond the proxy's columns (e.g. a load parameter) change nothing.
  ContactGapConstraints wider(proxy, pairs, offset, 23);
  Eigen::VectorXd x_wider = Eigen::VectorXd::Zero(23), values_wider;
  x_wider.head(21) = x;
  x_wider.tail(2).setConstant(5.0);
  Eigen::SparseMatrix<double, Eigen::RowMajor> J_wider = wider.jacobian_pattern();
  wider.evaluate(x_wider, values_wider, &J_wider);
  EXPECT_EQ(values_wider, values);
  EXPECT_EQ(Eigen::MatrixXd(J_wider).leftCols(21), Jd);
  EXPECT_EQ(Eigen::MatrixXd(J_wider).rightCols(2).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(c.pair_geometry(x, 0).point_triangle_region, PointTriangleRegion::Face);
  EXPECT_EQ(c.pair_geometry(x, 1).point_triangle_region, PointTriangleRegion::EdgeAB);
  EXPECT_EQ(c.pair_geometry(x, 2).point_triangle_region, PointTriangleRegion::VertexA);
  EXPECT_EQ(c.pair_geometry(x, 3).point_triangle_region, PointTriangleRegion::Face);
}

TEST(ContactGapConstraints, CrossingAndNearlyParallelEdgesWithTheMollifier) {
  // Edge P along x at height 0.3 over edge Q through the origin at angle alpha in z = 0: the
  // lines are 0.3 apart and the closest points are the midpoints. |e0 x e1|^2 = 16 sin^2 alpha
  // and the mollifier threshold is 1e-3 |e0|^2 |e1|^2 = 16e-3, so m = (2 - r) r with
  // r = sin^2(alpha) / 1e-3 (m = 1 for r >= 1).
  for (const double alpha : {std::numbers::pi / 2, 0.2, 0.01}) {
    Eigen::MatrixX3d points(4, 3);
    points << -1, 0, 0.3, 1, 0, 0.3, -std::cos(alpha), -std::sin(alpha), 0, std::cos(alpha),
        std::sin(alpha), 0;
    Eigen::MatrixX2i edges(2, 2);
    edges << 0, 1, 2, 3;
    const ContactProxy proxy = identity_proxy(points, Eigen::MatrixX3i(0, 3), edges);
    ContactCandidates pairs;
    pairs.edge_edge.resize(1, 2);
    pairs.edge_edge << 0, 1;
    const double offset = 0.5;
    const double r = std::pow(std::sin(alpha), 2) / 1e-3;
    const double m = r < 1.0 ? (2.0 - r) * r : 1.0;
    for (const bool mollify : {true, false}) {
      ContactGapConstraints c(proxy, pairs, offset, 12, ContactGapOptions{mollify});
      Eigen::VectorXd values;
      c.evaluate(flatten(points), values, nullptr);
      const double expected = (mollify ? m : 1.0) * (0.3 - offset);
      EXPECT_NEAR(values[0], expected, 1e-14) << "alpha " << alpha << " mollify " << mollify;
      const ContactPairGeometry g = c.pair_geometry(flatten(points), 0);
      EXPECT_EQ(g.edge_edge_region, EdgeEdgeRegion::EdgeEdge);
      EXPECT_NEAR(g.distance, 0.3, 1e-15);
      EXPECT_LT((g.normal - Eigen::Vector3d(0, 0, 1)).norm(), 1e-14);
      EXPECT_LT((g.vertex_weights - Eigen::Vector4d(0.5, 0.5, -0.5, -0.5)).norm(), 1e-14);
      EXPECT_NEAR(g.mollifier, mollify ? m : 1.0, 1e-15);
    }
  }
}

// ---- values on a folded sheet --------------------------------------------------------------

TEST(ContactGapConstraints, StackedFlatLayersHaveTheirSeparationAsDistance) {
  // Without wobble both layers are exactly flat (z = 0 and z = 2 rho) wherever the whole
  // support of a proxy vertex lies in one leg. A vertex whose xy-projection falls inside a
  // triangle of the other layer is exactly 2 rho from it, and so are two edges whose
  // projections cross; no pair of the two layers is closer.
  const FoldedDiscScene scene(0.0, 2);
  const double D = 2.0 * FoldedDiscScene::kRho;
  ContactGapConstraints c(scene.proxy, scene.pairs, kFoldedDiscOffset, scene.model.dimension());
  Eigen::VectorXd values;
  c.evaluate(scene.x, values, nullptr);
  const Eigen::MatrixX3d y = proxy_positions(scene.proxy, scene.x);
  const auto layer = [&](int v) {  // 0 lower, 1 upper, -1 not on a flat layer
    if (y(v, 2) == 0.0) return 0;
    if (std::abs(y(v, 2) - D) < 1e-14) return 1;
    return -1;
  };
  const auto cross2 = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() * b.y() - a.y() * b.x();
  };
  int exact_vt = 0, exact_ee = 0, flat_pairs = 0;
  for (Eigen::Index k = 0; k < c.count(); ++k) {
    const ContactPairGeometry g = c.pair_geometry(scene.x, k);
    const Eigen::Vector4i v = g.vertices;
    // Layers of the first primitive (the vertex, or the first edge) and of the second.
    const bool vt = g.type == ContactPairType::VertexTriangle;
    const int l0 = layer(v(0));
    const int l1 = layer(v(vt ? 1 : 2));
    bool flat = l0 >= 0 && l1 >= 0 && l0 != l1;
    if (vt)
      flat = flat && layer(v(2)) == l1 && layer(v(3)) == l1;
    else
      flat = flat && layer(v(1)) == l0 && layer(v(3)) == l1;
    if (!flat) continue;
    ++flat_pairs;
    EXPECT_GE(g.gap, D - kFoldedDiscOffset - 1e-14) << "pair " << k;
    const auto xy = [&](int i) { return Eigen::Vector2d(y(v(i), 0), y(v(i), 1)); };
    bool overlapping = false;
    if (g.type == ContactPairType::VertexTriangle) {
      // Inside with a margin: all three signed areas of the same sign, none tiny.
      const double s0 = cross2(xy(2) - xy(1), xy(0) - xy(1));
      const double s1 = cross2(xy(3) - xy(2), xy(0) - xy(2));
      const double s2 = cross2(xy(1) - xy(3), xy(0) - xy(3));
      overlapping =
          (s0 > 1e-9 && s1 > 1e-9 && s2 > 1e-9) || (s0 < -1e-9 && s1 < -1e-9 && s2 < -1e-9);
      exact_vt += overlapping;
    } else {
      const double a = cross2(xy(1) - xy(0), xy(2) - xy(0));
      const double b = cross2(xy(1) - xy(0), xy(3) - xy(0));
      const double cc = cross2(xy(3) - xy(2), xy(0) - xy(2));
      const double d = cross2(xy(3) - xy(2), xy(1) - xy(2));
      overlapping = a * b < -1e-18 && cc * d < -1e-18;
      exact_ee += overlapping;
    }
    if (overlapping) {
      // z-coordinates of the upper layer carry one rounding of the map's weights (~1e-17 m).
      EXPECT_NEAR(g.gap, D - kFoldedDiscOffset, 1e-14) << "pair " << k;
      EXPECT_EQ(values[k], g.mollifier * g.gap) << "pair " << k;
      EXPECT_LT(std::abs(std::abs(g.normal.z()) - 1.0), 1e-12) << "pair " << k;
    }
  }
  std::cout << "[ stacked  ] " << c.count() << " pairs, " << flat_pairs
            << " between the flat layers, exact checks: " << exact_vt << " vertex-triangle, "
            << exact_ee << " edge-edge\n";
  EXPECT_GT(exact_vt, 20);
  EXPECT_GT(exact_ee, 20);
}

/// Smallest distance between samples of the two primitives of a pair on a barycentric grid
/// of `n` steps per edge, and the covering radius of the sampling (every point of each
/// primitive is within it of a sample).
std::pair<double, double> sampled_distance(const Eigen::Matrix<double, 3, 4>& y,
                                           bool vertex_triangle, int n) {
  std::vector<Eigen::Vector3d> first, second;
  double cover = 0.0;
  if (vertex_triangle) {
    first.push_back(y.col(0));
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j)
        second.push_back(y.col(1) + (y.col(2) - y.col(1)) * i / double(n) +
                         (y.col(3) - y.col(1)) * j / double(n));
    const double longest = std::max(
        {(y.col(2) - y.col(1)).norm(), (y.col(3) - y.col(2)).norm(), (y.col(1) - y.col(3)).norm()});
    cover = longest / n;  // a point of a sub-triangle is within its longest edge of a corner
  } else {
    for (int i = 0; i <= n; ++i) {
      first.push_back(y.col(0) + (y.col(1) - y.col(0)) * i / double(n));
      second.push_back(y.col(2) + (y.col(3) - y.col(2)) * i / double(n));
    }
    cover = 0.5 * ((y.col(1) - y.col(0)).norm() + (y.col(3) - y.col(2)).norm()) / n;
  }
  double best = std::numeric_limits<double>::infinity();
  for (const auto& a : first)
    for (const auto& b : second) best = std::min(best, (a - b).squaredNorm());
  return {std::sqrt(best), cover};
}

TEST(ContactGapConstraints, DistancesMatchSampledBruteForceOnAFoldedDisc) {
  const FoldedDiscScene scene(0.02, 2);
  ContactGapConstraints c(scene.proxy, scene.pairs, kFoldedDiscOffset, scene.model.dimension());
  Eigen::VectorXd values;
  c.evaluate(scene.x, values, nullptr);
  const Eigen::MatrixX3d y = proxy_positions(scene.proxy, scene.x);
  double worst_excess = 0.0, worst_ratio = 0.0;
  for (Eigen::Index k = 0; k < c.count(); ++k) {
    const ContactPairGeometry g = c.pair_geometry(scene.x, k);
    Eigen::Matrix<double, 3, 4> corners;
    for (int i = 0; i < 4; ++i) corners.col(i) = y.row(g.vertices(i)).transpose();
    const auto [sampled, cover] =
        sampled_distance(corners, g.type == ContactPairType::VertexTriangle, 48);
    // The reported distance is a minimum over the continuum, so no sample may beat it (up to
    // rounding), and sampling overestimates it by at most the covering radii.
    worst_excess = std::max(worst_excess, g.distance - sampled);
    worst_ratio = std::max(worst_ratio, (sampled - g.distance) / cover);
    EXPECT_LE(g.distance, sampled + 1e-14) << "pair " << k;
    EXPECT_LE(sampled - g.distance, cover) << "pair " << k;
    // The closest points realise the distance, their difference is sum w_i y_i, the normal is
    // their unit direction.
    EXPECT_NEAR((g.closest_point_first - g.closest_point_second).norm(), g.distance, 1e-14);
    EXPECT_LT(
        (corners * g.vertex_weights - (g.closest_point_first - g.closest_point_second)).norm(),
        1e-14);
    EXPECT_LT((g.normal * g.distance - (g.closest_point_first - g.closest_point_second)).norm(),
              1e-14);
    const double expected = (c.pair_type(k) == ContactPairType::EdgeEdge ? g.mollifier : 1.0) *
                            (g.distance - kFoldedDiscOffset);
    EXPECT_EQ(values[k], expected);
  }
  std::cout << "[ sampled  ] " << c.count() << " pairs; largest (reported - sampled) "
            << worst_excess << " m, largest (sampled - reported) / covering radius " << worst_ratio
            << "\n";
}

// ---- derivatives ---------------------------------------------------------------------------

TEST(ContactGapConstraints, JacobianAndWeightedHessianMatchCentralDifferences) {
  const FoldedDiscScene scene(0.02, 1);
  const Eigen::Index n = scene.model.dimension();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (const bool mollify : {true, false}) {
    ContactGapConstraints c(scene.proxy, scene.pairs, kFoldedDiscOffset, n,
                            ContactGapOptions{mollify});
    const Eigen::Index m = c.count();
    // Enough of every kind for the test to mean something.
    int regions_seen = 0, mollified = 0;
    std::set<int> pt, ee;
    for (Eigen::Index k = 0; k < m; ++k) {
      const ContactPairGeometry g = c.pair_geometry(scene.x, k);
      if (g.type == ContactPairType::VertexTriangle)
        pt.insert(static_cast<int>(g.point_triangle_region));
      else
        ee.insert(static_cast<int>(g.edge_edge_region));
      mollified += g.mollifier < 1.0;
    }
    regions_seen = static_cast<int>(pt.size() + ee.size());
    std::cout << "[ FD       ] mollify " << mollify << ": " << c.vertex_triangle_count()
              << " vertex-triangle + " << m - c.vertex_triangle_count() << " edge-edge pairs, "
              << pt.size() << " point-triangle and " << ee.size() << " edge-edge regions, "
              << mollified << " mollified\n";
    ASSERT_GT(c.vertex_triangle_count(), 50);
    ASSERT_GT(m - c.vertex_triangle_count(), 50);
    EXPECT_GE(regions_seen, 6);
    if (mollify) {
      EXPECT_GT(mollified, 0);
    }

    const double h = 1e-7;  // metres; |x| ~ 1, distances ~ 0.1
    double worst_jacobian = 0.0, worst_hessian = 0.0;
    int unstable = 0;
    Eigen::SparseMatrix<double, Eigen::RowMajor> J = c.jacobian_pattern();
    Eigen::SparseMatrix<double, Eigen::RowMajor> Jp = J, Jm = J;
    Eigen::SparseMatrix<double> H = c.hessian_pattern();
    for (int trial = 0; trial < 3; ++trial) {
      Eigen::VectorXd v(n);
      for (Eigen::Index i = 0; i < n; ++i) v[i] = U(rng);
      const std::vector<char> stable = stable_pairs(c, scene.x, h * v);
      Eigen::VectorXd w(m);
      for (Eigen::Index k = 0; k < m; ++k) {
        w[k] = stable[static_cast<std::size_t>(k)] ? U(rng) : 0.0;
        unstable += !stable[static_cast<std::size_t>(k)];
      }
      Eigen::VectorXd values, vp, vm;
      c.evaluate(scene.x, values, &J);
      c.evaluate(scene.x + h * v, vp, &Jp);
      c.evaluate(scene.x - h * v, vm, &Jm);
      const Eigen::VectorXd fd = (vp - vm) / (2.0 * h);
      const Eigen::VectorXd Jv = J * v;
      for (Eigen::Index k = 0; k < m; ++k) {
        if (!stable[static_cast<std::size_t>(k)]) continue;
        const double err = std::abs(fd[k] - Jv[k]) / (1.0 + std::abs(Jv[k]));
        worst_jacobian = std::max(worst_jacobian, err);
      }
      c.weighted_hessian(scene.x, w, H);
      const Eigen::VectorXd fd_h =
          (Eigen::VectorXd(Jp.transpose() * w) - Eigen::VectorXd(Jm.transpose() * w)) / (2.0 * h);
      const Eigen::VectorXd Hv = dense_symmetric(H) * v;
      worst_hessian = std::max(
          worst_hessian, (fd_h - Hv).cwiseAbs().maxCoeff() / (1.0 + Hv.cwiseAbs().maxCoeff()));
    }
    std::cout << "[ FD       ] mollify " << mollify << ": relative error Jacobian "
              << worst_jacobian << ", weighted Hessian " << worst_hessian << ", " << unstable
              << " pair-trials skipped (region change within the step)\n";
    // Central differences, h = 1e-7 m. The truncation error h^2 |c'''| |v|^3 / 6 dominates:
    // the third derivatives of nearly parallel edge-edge distances grow like 1 / (l sin)^2
    // (l ~ 0.25 m, sin down to ~0.01). Measured: up to 7e-7 (Jacobian) with h = 1e-6, and
    // 1.6e-8 (Jacobian), 1.5e-9 (Hessian) with h = 1e-7, the h^2 scaling of a correct
    // derivative; rounding is ~1e-16 * 0.2 m / h = 2e-10. Bounds: about 50x the measured.
    EXPECT_LT(worst_jacobian, 1e-6);
    EXPECT_LT(worst_hessian, 1e-7);
    EXPECT_LT(unstable, 3 * m / 100);
  }
}

TEST(ContactGapConstraints, DistanceGradientIsTheWeightedNormal) {
  // Away from zero distance, d(distance)/d y_i = vertex_weights(i) * normal (the closest
  // points move tangentially to first order); pair_distance computes it from the primitives'
  // squared-distance gradient instead.
  const FoldedDiscScene scene(0.02, 2);
  ContactGapConstraints c(scene.proxy, scene.pairs, kFoldedDiscOffset, scene.model.dimension());
  double worst = 0.0;
  for (Eigen::Index k = 0; k < c.count(); ++k) {
    const ContactPairDistance D = c.pair_distance(scene.x, k, false);
    Vector12d expected;
    for (int i = 0; i < 4; ++i)
      expected.segment<3>(3 * i) = D.geometry.vertex_weights(i) * D.geometry.normal;
    worst = std::max(worst, (D.gradient - expected).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, 1e-12);
}

// ---- patterns ------------------------------------------------------------------------------

TEST(ContactGapConstraints, PatternsAreTheStencilsAndHoldEveryNonzero) {
  const FoldedDiscScene scene(0.02, 1);
  const Eigen::Index n = scene.model.dimension();
  // Every 10th candidate of each kind keeps the n finite-difference evaluations below fast.
  const auto every_tenth = [](const Eigen::MatrixX2i& rows) {
    Eigen::MatrixX2i out((rows.rows() + 9) / 10, 2);
    for (Eigen::Index r = 0; r < out.rows(); ++r) out.row(r) = rows.row(10 * r);
    return out;
  };
  ContactCandidates subset;
  subset.vertex_triangle = every_tenth(scene.pairs.vertex_triangle);
  subset.edge_edge = every_tenth(scene.pairs.edge_edge);
  ContactGapConstraints c(scene.proxy, subset, kFoldedDiscOffset, n);
  const Eigen::Index m = c.count();

  // Stencils computed independently by scanning the columns of the (column-major) map.
  std::vector<std::set<int>> stencil(static_cast<std::size_t>(m));
  {
    std::vector<std::vector<int>> columns_of_vertex(
        static_cast<std::size_t>(scene.proxy.num_vertices()));
    for (Eigen::Index j = 0; j < scene.proxy.map.outerSize(); ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(scene.proxy.map, j); it; ++it)
        columns_of_vertex[static_cast<std::size_t>(it.row() / 3)].push_back(static_cast<int>(j));
    for (Eigen::Index k = 0; k < m; ++k) {
      const Eigen::Vector4i v = c.pair_geometry(scene.x, k).vertices;
      for (int i = 0; i < 4; ++i)
        for (int col : columns_of_vertex[static_cast<std::size_t>(v(i))])
          stencil[static_cast<std::size_t>(k)].insert(col);
    }
  }
  const Eigen::SparseMatrix<double, Eigen::RowMajor> Jpattern = c.jacobian_pattern();
  std::set<std::pair<int, int>> hessian_expected;
  for (Eigen::Index k = 0; k < m; ++k) {
    const auto& s = stencil[static_cast<std::size_t>(k)];
    const auto dofs = c.pair_dofs(k);
    ASSERT_EQ(std::vector<int>(dofs.begin(), dofs.end()), std::vector<int>(s.begin(), s.end()))
        << "pair " << k;
    std::vector<int> row;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(Jpattern, k); it; ++it)
      row.push_back(static_cast<int>(it.col()));
    ASSERT_EQ(row, std::vector<int>(s.begin(), s.end())) << "Jacobian row " << k;
    for (int a : s)
      for (int b : s)
        if (a <= b) hessian_expected.insert({a, b});
  }
  const Eigen::SparseMatrix<double> Hpattern = c.hessian_pattern();
  std::set<std::pair<int, int>> hessian_actual;
  for (Eigen::Index j = 0; j < Hpattern.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(Hpattern, j); it; ++it)
      hessian_actual.insert({static_cast<int>(it.row()), static_cast<int>(j)});
  EXPECT_EQ(hessian_actual, hessian_expected);

  // Every nonzero of the true derivatives is in the patterns: central differences of c and of
  // J^T w along every coordinate direction, entries above 1e-6 of the largest must be stored.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Eigen::VectorXd w(m);
  for (Eigen::Index k = 0; k < m; ++k) w[k] = U(rng);
  Eigen::SparseMatrix<double, Eigen::RowMajor> Jp = Jpattern, Jm = Jpattern;
  Eigen::MatrixXd fd_jacobian(m, n), fd_hessian(n, n);
  const double h = 1e-6;
  for (Eigen::Index j = 0; j < n; ++j) {
    Eigen::VectorXd xp = scene.x, xm = scene.x, vp, vm;
    xp[j] += h;
    xm[j] -= h;
    c.evaluate(xp, vp, &Jp);
    c.evaluate(xm, vm, &Jm);
    fd_jacobian.col(j) = (vp - vm) / (2.0 * h);
    fd_hessian.col(j) =
        (Eigen::VectorXd(Jp.transpose() * w) - Eigen::VectorXd(Jm.transpose() * w)) / (2.0 * h);
  }
  const double jacobian_scale = fd_jacobian.cwiseAbs().maxCoeff();
  const double hessian_scale = fd_hessian.cwiseAbs().maxCoeff();
  int outside = 0, checked_j = 0, checked_h = 0;
  for (Eigen::Index k = 0; k < m; ++k)
    for (Eigen::Index j = 0; j < n; ++j)
      if (std::abs(fd_jacobian(k, j)) > 1e-6 * jacobian_scale) {
        ++checked_j;
        if (!stencil[static_cast<std::size_t>(k)].count(static_cast<int>(j))) ++outside;
      }
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = 0; i <= j; ++i)
      if (std::abs(fd_hessian(i, j)) > 1e-6 * hessian_scale) {
        ++checked_h;
        if (!hessian_expected.count({static_cast<int>(i), static_cast<int>(j)})) ++outside;
      }
  std::cout << "[ pattern  ] " << checked_j << " Jacobian and " << checked_h
            << " Hessian nonzeros (finite differences) checked, " << Jpattern.nonZeros() << " and "
            << Hpattern.nonZeros() << " in the patterns\n";
  EXPECT_EQ(outside, 0);
  EXPECT_GT(checked_h, 1000);
}

// ---- zero distance, empty input, bad input -------------------------------------------------

TEST(ContactGapConstraints, ZeroDistanceGivesFiniteDerivatives) {
  // A point in the plane of a triangle: d = 0 exactly, value -offset, gradient zero (grad s = 0
  // there), Hessian finite; the normal falls back to the triangle's. A point 1e-6 m above it
  // (far above the floor) has the unit normal as gradient.
  Eigen::MatrixX3d points(5, 3);
  points << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.2, 0.3, 0.0, 0.2, 0.3, 1e-6;
  Eigen::MatrixX3i triangles(1, 3);
  triangles << 0, 1, 2;
  Eigen::MatrixX2i edges(3, 2);
  edges << 0, 1, 0, 2, 1, 2;
  const ContactProxy proxy = identity_proxy(points, triangles, edges);
  ContactCandidates pairs;
  pairs.vertex_triangle.resize(2, 2);
  pairs.vertex_triangle << 3, 0, 4, 0;
  ContactGapConstraints c(proxy, pairs, 0.1, 15);
  EXPECT_NEAR(c.distance_floor(), 1e-9 * (2.0 + std::sqrt(2.0)) / 3.0, 1e-24);
  const Eigen::VectorXd x = flatten(points);
  Eigen::VectorXd values;
  Eigen::SparseMatrix<double, Eigen::RowMajor> J = c.jacobian_pattern();
  c.evaluate(x, values, &J);
  EXPECT_EQ(values[0], -0.1);
  EXPECT_NEAR(values[1], 1e-6 - 0.1, 1e-17);
  const Eigen::MatrixXd Jd = Eigen::MatrixXd(J);
  EXPECT_TRUE(Jd.allFinite());
  EXPECT_EQ(Jd.row(0).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LT((Jd.row(1).segment<3>(12) - Eigen::RowVector3d(0, 0, 1)).norm(), 1e-12);
  Eigen::SparseMatrix<double> H = c.hessian_pattern();
  c.weighted_hessian(x, Eigen::Vector2d(1.0, 1.0), H);
  EXPECT_TRUE(Eigen::MatrixXd(H).allFinite());
  EXPECT_LT((c.pair_geometry(x, 0).normal - Eigen::Vector3d(0, 0, 1)).norm(), 1e-15);
}

TEST(ContactGapConstraints, InterpenetratedFoldedDiscStaysFinite) {
  // The upper layer pressed into the lower one (fold radius 0, wobble-free): the mid-surfaces
  // coincide and many pairs have distance exactly 0.
  const FoldedDiscScene scene(0.02, 1);
  const Eigen::VectorXd x = folded_sheet(scene.model, 0.0, 0.0, 0.0);
  ContactCandidateOptions options;
  options.query_distance = 0.05;
  options.exclusion_radius = 0.2;
  const ContactCandidates pairs =
      find_contact_candidates(scene.proxy, proxy_positions(scene.proxy, x), options);
  for (const bool mollify : {true, false}) {
    ContactGapConstraints c(scene.proxy, pairs, kFoldedDiscOffset, scene.model.dimension(),
                            ContactGapOptions{mollify});
    Eigen::VectorXd values;
    Eigen::SparseMatrix<double, Eigen::RowMajor> J = c.jacobian_pattern();
    c.evaluate(x, values, &J);
    int zero = 0;
    for (Eigen::Index k = 0; k < c.count(); ++k) {
      const ContactPairGeometry g = c.pair_geometry(x, k);
      if (g.distance == 0.0) {
        ++zero;
        EXPECT_EQ(values[k], -g.mollifier * kFoldedDiscOffset);
        if (g.type == ContactPairType::VertexTriangle) {
          EXPECT_NEAR(g.normal.norm(), 1.0, 1e-14);
        }
      }
    }
    EXPECT_GT(zero, 20);
    EXPECT_TRUE(values.allFinite());
    EXPECT_TRUE(
        Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(J.valuePtr(), J.nonZeros())).allFinite());
    Eigen::SparseMatrix<double> H = c.hessian_pattern();
    c.weighted_hessian(x, Eigen::VectorXd::Ones(c.count()), H);
    EXPECT_TRUE(
        Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(H.valuePtr(), H.nonZeros())).allFinite());
  }
}

TEST(ContactGapConstraints, NoPairsGiveEmptyConstraints) {
  const FoldedDiscScene scene(0.02, 1);
  const Eigen::Index n = scene.model.dimension();
  ContactGapConstraints c(scene.proxy, ContactCandidates{}, 0.1, n + 2);  // 2 extra unknowns
  EXPECT_EQ(c.count(), 0);
  EXPECT_EQ(c.dimension(), n + 2);
  EXPECT_EQ(c.jacobian_pattern().rows(), 0);
  EXPECT_EQ(c.jacobian_pattern().cols(), n + 2);
  EXPECT_EQ(c.hessian_pattern().nonZeros(), 0);
  Eigen::VectorXd values(3);
  Eigen::SparseMatrix<double, Eigen::RowMajor> J = c.jacobian_pattern();
  const Eigen::VectorXd x = Eigen::VectorXd::Zero(n + 2);
  c.evaluate(x, values, &J);
  EXPECT_EQ(values.size(), 0);
  Eigen::SparseMatrix<double> H = c.hessian_pattern();
  c.weighted_hessian(x, Eigen::VectorXd(0), H);
}

TEST(ContactGapConstraints, RejectsBadInputNamingIt) {
  Eigen::MatrixX3d points(5, 3);
  points << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.2, 0.3, 0.5, 0.3, 0.3, 0.5;
  Eigen::MatrixX3i triangles(1, 3);
  triangles << 0, 1, 2;
  Eigen::MatrixX2i edges(4, 2);
  edges << 0, 1, 0, 2, 1, 2, 3, 4;
  const ContactProxy proxy = identity_proxy(points, triangles, edges);
  ContactCandidates good;
  good.vertex_triangle.resize(1, 2);
  good.vertex_triangle << 3, 0;
  expect_invalid_argument_containing([&] { ContactGapConstraints(proxy, good, -0.1, 15); },
                                     "offset");
  expect_invalid_argument_containing([&] { ContactGapConstraints(proxy, good, std::nan(""), 15); },
                                     "offset");
  expect_invalid_argument_containing([&] { ContactGapConstraints(proxy, good, 0.1, 14); },
                                     "dimension 14");
  ContactCandidates bad = good;
  bad.vertex_triangle << 7, 0;
  expect_invalid_argument_containing([&] { ContactGapConstraints(proxy, bad, 0.1, 15); },
                                     "proxy vertex 7");
  bad.vertex_triangle << 3, 1;
  expect_invalid_argument_containing([&] { ContactGapConstraints(proxy, bad, 0.1, 15); },
                                     "proxy triangle 1");
  bad.vertex_triangle << 1, 0;
  expect_invalid_argument_containing([&] { ContactGapConstraints(proxy, bad, 0.1, 15); },
                                     "is a corner");
  ContactCandidates ee;
  ee.edge_edge.resize(1, 2);
  ee.edge_edge << 0, 1;  // share vertex 0
  expect_invalid_argument_containing([&] { ContactGapConstraints(proxy, ee, 0.1, 15); },
                                     "share proxy vertex 0");
  ee.edge_edge << 2, 9;
  expect_invalid_argument_containing([&] { ContactGapConstraints(proxy, ee, 0.1, 15); },
                                     "proxy edge 9");

  ContactGapConstraints c(proxy, good, 0.1, 15);
  Eigen::VectorXd values;
  expect_invalid_argument_containing(
      [&] { c.evaluate(Eigen::VectorXd::Zero(14), values, nullptr); }, "x has 14 entries");
  Eigen::SparseMatrix<double, Eigen::RowMajor> wrong(1, 15);
  expect_invalid_argument_containing([&] { c.evaluate(flatten(points), values, &wrong); },
                                     "jacobian_pattern");
  Eigen::SparseMatrix<double> wrong_h(15, 15);
  expect_invalid_argument_containing(
      [&] { c.weighted_hessian(flatten(points), Eigen::VectorXd::Ones(1), wrong_h); },
      "hessian_pattern");
  Eigen::SparseMatrix<double> H = c.hessian_pattern();
  expect_invalid_argument_containing(
      [&] { c.weighted_hessian(flatten(points), Eigen::VectorXd::Ones(2), H); },
      "weights has 2 entries");
  expect_invalid_argument_containing([&] { c.pair_geometry(flatten(points), 1); }, "pair index 1");
  // A triangle collapsed onto a segment at x: the primitive's error, prefixed with the pair.
  Eigen::MatrixX3d collapsed = points;
  collapsed.row(2) << 2, 0, 0;
  expect_invalid_argument_containing([&] { c.evaluate(flatten(collapsed), values, nullptr); },
                                     "contact pair 0 (proxy vertex 3, proxy triangle 0)");
}

}  // namespace
}  // namespace growshell
