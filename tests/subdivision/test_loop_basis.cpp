// The regular Loop patch basis: partition of unity, polynomial reproduction, limit masks at
// the corners, and C1 continuity between neighbouring elements of a mesh.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <map>
#include <random>
#include <tuple>

#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/mesh/mesh_topology.hpp"
#include "libshell/subdivision/element_patches.hpp"
#include "libshell/subdivision/loop_basis.hpp"

namespace growshell {
namespace {

// Node positions of the regular patch in a unit equilateral lattice (node 3 at the origin);
// the element triangle is (3, 6, 7).
Eigen::Matrix<double, 12, 2> lattice_nodes() {
  const Eigen::Vector2d e1(1.0, 0.0), e2(0.5, std::sqrt(3.0) / 2.0);
  Eigen::Matrix<double, 12, 2> X;
  const Eigen::Vector2d p[12] = {e2 - e1, e2,          -e1,     Eigen::Vector2d::Zero(),
                                 e1,      -e1 - e2,    -e2,     e1 - e2,
                                 2 * e1 - e2, -2 * e2, e1 - 2 * e2, 2 * e1 - 2 * e2};
  for (int i = 0; i < 12; ++i) X.row(i) = p[i].transpose();
  return X;
}

const double kSamples[][2] = {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}, {0.2, 0.3},
                              {0.5, 0.5}, {0.1, 0.7}, {1.0 / 3, 1.0 / 3}};

TEST(LoopBasis, PartitionOfUnity) {
  for (const auto& s : kSamples) {
    const LoopBasisValues b = evaluate_regular_loop_basis(s[0], s[1]);
    EXPECT_NEAR(b.value.sum(), 1.0, 1e-15);
    EXPECT_NEAR(b.first.col(0).sum(), 0.0, 1e-14);
    EXPECT_NEAR(b.first.col(1).sum(), 0.0, 1e-14);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(b.second.col(k).sum(), 0.0, 1e-13);
    EXPECT_GE(b.value.minCoeff(), -1e-15);  // box splines are non-negative
  }
}

TEST(LoopBasis, ReproducesTheParameterisationOfTheLattice) {
  // x(v, w) = node3 + v (node6 - node3) + w (node7 - node3) for lattice control points.
  const auto X = lattice_nodes();
  for (const auto& s : kSamples) {
    const LoopBasisValues b = evaluate_regular_loop_basis(s[0], s[1]);
    const Eigen::Vector2d x = X.transpose() * b.value;
    const Eigen::Vector2d expected = s[0] * X.row(6).transpose() + s[1] * X.row(7).transpose();
    EXPECT_NEAR((x - expected).norm(), 0.0, 1e-14);
    EXPECT_NEAR((X.transpose() * b.first.col(0) - X.row(6).transpose()).norm(), 0.0, 1e-13);
    EXPECT_NEAR((X.transpose() * b.first.col(1) - X.row(7).transpose()).norm(), 0.0, 1e-13);
    EXPECT_NEAR((X.transpose() * b.second).norm(), 0.0, 1e-13);
  }
}

TEST(LoopBasis, ReproducesQuadraticsUpToAConstant) {
  // Control values sampled from a quadratic q give q + const: the second parametric
  // derivatives of the limit function equal those of q exactly.
  const auto X = lattice_nodes();
  const Eigen::Matrix2d Hq = (Eigen::Matrix2d() << 0.7, -0.3, -0.3, 1.9).finished();
  Eigen::Matrix<double, 12, 1> values;
  for (int i = 0; i < 12; ++i) {
    const Eigen::Vector2d p = X.row(i).transpose();
    values(i) = 0.5 * p.dot(Hq * p) + 0.4 * p.x() - 0.2 * p.y();
  }
  const Eigen::Vector2d d1 = X.row(6).transpose(), d2 = X.row(7).transpose();
  const double expected[3] = {d1.dot(Hq * d1), d2.dot(Hq * d2), d1.dot(Hq * d2)};
  double offset = 0.0;
  for (int k = 0; k < 7; ++k) {
    const LoopBasisValues b = evaluate_regular_loop_basis(kSamples[k][0], kSamples[k][1]);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(values.dot(b.second.col(c)), expected[c], 1e-13);
    const Eigen::Vector2d p = kSamples[k][0] * d1 + kSamples[k][1] * d2;
    const double diff = values.dot(b.value) - (0.5 * p.dot(Hq * p) + 0.4 * p.x() - 0.2 * p.y());
    if (k == 0) offset = diff;
    EXPECT_NEAR(diff, offset, 1e-13);
  }
  // The constant is the lattice's (1/8) l^2 tr(Hq) with unit edge length l.
  EXPECT_NEAR(offset, Hq.trace() / 8.0, 1e-13);
}

TEST(LoopBasis, CornersCarryTheValenceSixLimitMask) {
  const int corner_node[3] = {3, 6, 7};
  const int neighbours[3][6] = {{0, 1, 2, 4, 6, 7}, {2, 3, 5, 7, 9, 10}, {3, 4, 6, 8, 10, 11}};
  const double corners[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  for (int c = 0; c < 3; ++c) {
    const LoopBasisValues b = evaluate_regular_loop_basis(corners[c][0], corners[c][1]);
    EXPECT_NEAR(b.value(corner_node[c]), kRegularLimitCentreWeight, 1e-15);
    for (int k = 0; k < 6; ++k)
      EXPECT_NEAR(b.value(neighbours[c][k]), kRegularLimitNeighbourWeight, 1e-15);
  }
}

TEST(LoopBasis, LimitSurfaceIsC1AcrossElementEdges) {
  // Random control points on a strip mesh: position and both tangent directions agree where
  // two elements meet (the tangents expressed along and across the shared edge).
  StripMeshOptions opts;
  opts.cells_x = 6;
  opts.cells_y = 4;
  TriangleMesh mesh = make_strip_mesh(opts);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) mesh.vertices(v, 2) = u(rng);
  const MeshTopology topology(mesh);
  const ElementPatches patches = build_element_patches(topology);
  std::map<std::pair<int, int>, std::vector<int>> edge_elements;
  for (std::size_t e = 0; e < patches.face.size(); ++e) {
    const auto& f = topology.face(patches.face[e]);
    for (int k = 0; k < 3; ++k)
      edge_elements[{std::min(f[k], f[(k + 1) % 3]), std::max(f[k], f[(k + 1) % 3])}]
          .push_back(static_cast<int>(e));
  }
  // Point at parameter t along edge (p -> q) of element e, and the derivative along the edge
  // and the derivative along (r - p) where r is the element's third corner.
  auto eval = [&](int e, int p, int q, double t) {
    const auto& f = topology.face(patches.face[e]);
    // Corner k of the face is at (v, w) = (0,0), (1,0), (0,1) for f[0], f[1], f[2].
    auto param = [&](int vtx) {
      if (vtx == f[0]) return Eigen::Vector2d(0, 0);
      if (vtx == f[1]) return Eigen::Vector2d(1, 0);
      return Eigen::Vector2d(0, 1);
    };
    const Eigen::Vector2d a = param(p), b = param(q);
    const Eigen::Vector2d s = (1 - t) * a + t * b;
    const LoopBasisValues basis = evaluate_regular_loop_basis(s.x(), s.y());
    Eigen::Matrix<double, 12, 3> X;
    for (int i = 0; i < 12; ++i) X.row(i) = mesh.vertices.row(patches.patch[e].control[i]);
    const Eigen::Vector3d x = X.transpose() * basis.value;
    const Eigen::Matrix<double, 3, 2> A = X.transpose() * basis.first;
    const Eigen::Vector3d along = A * (b - a);
    const Eigen::Vector3d normal = A.col(0).cross(A.col(1)).normalized();
    return std::make_tuple(x, along, normal);
  };
  int checked = 0;
  for (const auto& [edge, elements] : edge_elements) {
    if (elements.size() != 2) continue;
    for (double t : {0.0, 0.3, 0.5, 0.9}) {
      const auto [x0, t0, n0] = eval(elements[0], edge.first, edge.second, t);
      const auto [x1, t1, n1] = eval(elements[1], edge.first, edge.second, t);
      EXPECT_NEAR((x0 - x1).norm(), 0.0, 1e-14);
      EXPECT_NEAR((t0 - t1).norm(), 0.0, 1e-13);
      EXPECT_NEAR((n0 - n1).norm(), 0.0, 1e-12);  // tangent plane continuous: C1 (G1)
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
}

}  // namespace
}  // namespace growshell
