// Exact evaluation of Loop elements with extraordinary corners (valence 3..12): the subdivision
// route against the box-spline on regular patches, partition of unity, planes, C1 continuity
// across every interior edge, and the limit position at the extraordinary vertex itself.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/mesh/mesh_topology.hpp"
#include "libshell/subdivision/element_patches.hpp"
#include "libshell/subdivision/limit_surface.hpp"
#include "libshell/subdivision/loop_rules.hpp"
#include "tests/support/polygon_disc.hpp"

namespace growshell {
namespace {

using test_support::polygon_disc;

/// Random smooth-ish bumps plus noise on a planar mesh: a generic curved control net.
Eigen::MatrixX3d curved(const TriangleMesh& mesh, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixX3d X = mesh.vertices;
  for (Eigen::Index v = 0; v < X.rows(); ++v) {
    const double x = X(v, 0), y = X(v, 1);
    X(v, 2) = 0.2 * std::sin(0.7 * x + 0.3) * std::cos(0.5 * y) + 0.05 * x * y;
    for (int c = 0; c < 3; ++c) X(v, c) += noise * u(rng);
  }
  return X;
}

// Points at distance >= 0.03 from the corners: derivatives near an extraordinary corner lose
// precision like eps / d^2 at distance d (the sub-patch's derivatives are scaled by 2^k after k
// steps), so these keep rounding below 1e-12; NearTheCornerPrecisionFollowsItsScaling checks
// closer points.
const std::vector<std::pair<double, double>> kPoints = {
    {1.0 / 3, 1.0 / 3}, {0.1, 0.2}, {0.7, 0.15}, {0.05, 0.9}, {0.0, 0.5},
    {0.5, 0.5},         {0.02, 0.01}, {0.3, 0.0}, {0.6, 0.4}};

TEST(LoopPatch, SubdividingARegularPatchGivesTheBoxSpline) {
  const TriangleMesh mesh = make_disc_mesh({.rings = 5});
  const MeshTopology topology(mesh);
  const ElementPatches patches = build_element_patches(topology);
  const Eigen::MatrixX3d X = curved(mesh, 0.05, 3);
  double worst_position = 0, worst_tangent = 0, worst_second = 0;
  for (std::size_t e = 0; e < patches.patch.size(); e += 7) {
    ASSERT_TRUE(patches.patch[e].is_regular());
    const LoopPatch surrounding = build_surrounding_patch(topology, patches.face[e]);
    for (const auto& [v, w] : kPoints)
      for (int levels : {1, 2, 4}) {
        const LimitSurfacePoint a = evaluate_limit_surface(X, patches.patch[e], v, w);
        const LimitSurfacePoint b = evaluate_limit_surface(
            X, surrounding, evaluate_patch_basis_subdividing(surrounding, v, w, levels));
        worst_position = std::max(worst_position, (a.position - b.position).norm());
        worst_tangent = std::max(worst_tangent, (a.tangents - b.tangents).norm());
        worst_second = std::max(worst_second, (a.second - b.second).norm());
      }
  }
  // Rounding only: coordinates are O(1), the derivatives are scaled by 2^levels.
  EXPECT_LT(worst_position, 1e-13);
  EXPECT_LT(worst_tangent, 1e-12);
  EXPECT_LT(worst_second, 1e-10);
}

class IrregularValence : public ::testing::TestWithParam<int> {};

TEST_P(IrregularValence, BasisIsAPartitionOfUnityAndReproducesPlanes) {
  const int n = GetParam();
  TriangleMesh mesh = polygon_disc(n, 4, 0.25);
  // A tilted plane with an irregular in-plane layout.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    mesh.vertices(v, 0) += u(rng);
    mesh.vertices(v, 1) += u(rng);
    mesh.vertices(v, 2) = 0.3 * mesh.vertices(v, 0) - 0.2 * mesh.vertices(v, 1) + 0.1;
  }
  const Eigen::Vector3d normal = Eigen::Vector3d(-0.3, 0.2, 1.0).normalized();
  const MeshTopology topology(mesh);
  const ElementPatches patches = build_element_patches(topology);
  // The n elements at the centre; for n = 3 also the 3 faces beyond them, whose corners have
  // valence 6 but whose one-rings overlap (they share the centre's neighbours).
  ASSERT_EQ(patches.num_irregular(), n == 3 ? 6 : n);
  double sum_error = 0, plane_error = 0, normal_error = 0, curvature = 0;
  for (const LoopPatch& patch : patches.patch) {
    for (const auto& [v, w] : kPoints) {
      const PatchBasis b = evaluate_patch_basis(patch, v, w);
      sum_error = std::max({sum_error, std::abs(b.value.sum() - 1.0),
                            b.first.colwise().sum().cwiseAbs().maxCoeff(),
                            b.second.colwise().sum().cwiseAbs().maxCoeff()});
      const LimitSurfacePoint p = evaluate_limit_surface(mesh.vertices, patch, b);
      plane_error = std::max(plane_error, std::abs(normal.dot(p.position) - normal.z() * 0.1));
      normal_error = std::max(normal_error, (p.normal - normal).norm());
      curvature = std::max(curvature, p.curvature_tensor.cwiseAbs().maxCoeff());
    }
  }
  EXPECT_LT(sum_error, 1e-11);
  EXPECT_LT(plane_error, 1e-14);
  EXPECT_LT(normal_error, 1e-13);
  EXPECT_LT(curvature, 1e-11);
}

TEST_P(IrregularValence, LimitSurfaceIsC1AcrossEveryInteriorEdge) {
  const int n = GetParam();
  const TriangleMesh mesh = polygon_disc(n, 4, 0.25);
  const Eigen::MatrixX3d X = curved(mesh, 0.02, 11);
  const MeshTopology topology(mesh);
  const ElementPatches patches = build_element_patches(topology);
  std::vector<int> element_of_face(static_cast<std::size_t>(topology.num_faces()), -1);
  for (std::size_t e = 0; e < patches.face.size(); ++e)
    element_of_face[static_cast<std::size_t>(patches.face[e])] = static_cast<int>(e);
  // (v, w) of corner k of an element.
  const auto corner = [](int k) {
    return k == 0 ? Eigen::Vector2d(0, 0) : k == 1 ? Eigen::Vector2d(1, 0) : Eigen::Vector2d(0, 1);
  };
  double position_jump = 0, tangent_jump = 0, normal_jump = 0;
  int edges = 0;
  for (std::size_t e = 0; e < patches.face.size(); ++e) {
    const auto& t = topology.face(patches.face[e]);
    for (int k = 0; k < 3; ++k) {
      const int a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
      const int other = element_of_face[static_cast<std::size_t>(topology.face_with_edge(b, a))];
      if (other < 0) continue;
      const auto& s = topology.face(patches.face[static_cast<std::size_t>(other)]);
      const int ka = static_cast<int>(std::find(s.begin(), s.end(), a) - s.begin());
      const int kb = static_cast<int>(std::find(s.begin(), s.end(), b) - s.begin());
      ++edges;
      for (double tau : {0.1, 0.37, 0.5, 0.81}) {
        const Eigen::Vector2d p = (1 - tau) * corner(k) + tau * corner((k + 1) % 3);
        const Eigen::Vector2d q = (1 - tau) * corner(ka) + tau * corner(kb);
        const LimitSurfacePoint x = evaluate_limit_surface(X, patches.patch[e], p.x(), p.y());
        const LimitSurfacePoint y =
            evaluate_limit_surface(X, patches.patch[static_cast<std::size_t>(other)], q.x(), q.y());
        const Eigen::Vector3d along_x = x.tangents * (corner((k + 1) % 3) - corner(k));
        const Eigen::Vector3d along_y = y.tangents * (corner(kb) - corner(ka));
        position_jump = std::max(position_jump, (x.position - y.position).norm());
        tangent_jump = std::max(tangent_jump, (along_x - along_y).norm());
        normal_jump = std::max(normal_jump, (x.normal - y.normal).norm());
      }
    }
  }
  EXPECT_GT(edges, 60);
  EXPECT_LT(position_jump, 1e-13);
  EXPECT_LT(tangent_jump, 1e-12);
  EXPECT_LT(normal_jump, 1e-11);
}

TEST_P(IrregularValence, ExtraordinaryCornerHasLoopsLimitPosition) {
  const int n = GetParam();
  const TriangleMesh mesh = polygon_disc(n, 3, 0.25);
  const Eigen::MatrixX3d X = curved(mesh, 0.02, 5);
  const MeshTopology topology(mesh);
  const ElementPatches patches = build_element_patches(topology);
  // Element 0 touches the centre (vertex 0) at its corner a.
  const LoopPatch& patch = patches.patch[0];
  ASSERT_EQ(patch.control[static_cast<std::size_t>(patch.corners[0])], 0);
  const double chi = loop_limit_neighbour_weight(n);
  Eigen::Vector3d limit = (1.0 - n * chi) * X.row(0).transpose();
  for (int u : topology.one_ring(0)) limit += chi * X.row(u).transpose();
  EXPECT_LT((evaluate_limit_surface(X, patch, 0.0, 0.0).position - limit).norm(), 1e-14);
  // Points approaching the corner converge to it, like lambda^k at distance 2^-k.
  double previous = 1.0;
  for (int k : {4, 10, 20}) {
    const double d = std::ldexp(1.0, -k);
    const double gap = (evaluate_limit_surface(X, patch, d, d).position - limit).norm();
    EXPECT_LT(gap, 2.0 * std::pow(loop_subdominant_eigenvalue(n), k)) << "distance 2^-" << k;
    EXPECT_LT(gap, previous);
    previous = gap;
  }
}

TEST_P(IrregularValence, NearTheCornerPrecisionFollowsItsScaling) {
  const int n = GetParam();
  const TriangleMesh mesh = polygon_disc(n, 3, 0.25);
  const ElementPatches patches = build_element_patches(MeshTopology(mesh));
  for (double d : {1e-3, 1e-4, 1e-6}) {
    const PatchBasis b = evaluate_patch_basis(patches.patch[0], d, d);
    const double eps = 2.2e-16;
    EXPECT_LT(std::abs(b.value.sum() - 1.0), 100 * eps) << "d = " << d;
    EXPECT_LT(b.first.colwise().sum().cwiseAbs().maxCoeff(), 100 * eps / d) << "d = " << d;
    EXPECT_LT(b.second.colwise().sum().cwiseAbs().maxCoeff(), 100 * eps / (d * d)) << "d = " << d;
  }
}

INSTANTIATE_TEST_SUITE_P(Valences3To12, IrregularValence,
                         ::testing::Values(3, 4, 5, 7, 8, 9, 10, 11, 12));

TEST(LoopPatch, RejectsPointsOutsideTheTriangle) {
  const TriangleMesh mesh = polygon_disc(5, 3, 0.25);
  const ElementPatches patches = build_element_patches(MeshTopology(mesh));
  EXPECT_THROW(evaluate_patch_basis(patches.patch[0], 0.7, 0.5), std::invalid_argument);
  EXPECT_THROW(evaluate_patch_basis(patches.patch[0], -0.1, 0.5), std::invalid_argument);
  EXPECT_THROW(evaluate_patch_basis(patches.patch[0], std::nan(""), 0.5), std::invalid_argument);
}

}  // namespace
}  // namespace growshell
