// ReferenceQuadrature::vertex_areas: the lumped reference area of every control vertex is
// positive (every vertex of a ghosted mesh supports an element), they add up to the reference
// area, and their first moment is the integral of the limit position (the limit surface of a
// planar control mesh is sum_i N_i X_i, so both sides are the same quadrature: equal to
// rounding), on regular and irregular (rings) meshes.
#include "libshell/assembly/reference_quadrature.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <string>

#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/mesh/mesh_topology.hpp"
#include "libshell/mesh/ring_disc_mesh.hpp"
#include "libshell/subdivision/element_patches.hpp"

namespace growshell {
namespace {

void expect_consistent_vertex_areas(const TriangleMesh& mesh, int degree) {
  const MeshTopology topology(mesh);
  const ElementPatches patches = build_element_patches(topology);
  const ReferenceQuadrature q(mesh.vertices, patches, degree, constant_thickness(0.01));
  const Eigen::VectorXd& m = q.vertex_areas();
  ASSERT_EQ(m.size(), mesh.vertices.rows());
  EXPECT_GT(m.minCoeff(), 0.0);
  // Sums of O(1e4) positive terms of O(1e-4): rounding of a few 1e-16 relative.
  EXPECT_NEAR(m.sum() / q.reference_area(), 1.0, 1e-13);
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  const int per = q.points_per_element();
  for (Eigen::Index i = 0; i < q.size(); ++i)
    moment += q.rule()[static_cast<std::size_t>(i % per)].weight *
              q.tangents(i).col(0).cross(q.tangents(i).col(1)).norm() * q.position(i);
  const Eigen::Vector3d lumped = mesh.vertices.transpose() * m;
  EXPECT_LT((lumped - moment).norm(), 1e-13 * q.reference_area());
  EXPECT_GT(moment.norm(), 0.1);  // the meshes below are off-centre: the check has content
}

TEST(ReferenceQuadrature, VertexAreasArePositiveAndIntegrateTheLimitSurface) {
  DiscMeshOptions lattice;
  lattice.rings = 8;
  lattice.center = {0.3, -0.2};
  SCOPED_TRACE("lattice disc");
  expect_consistent_vertex_areas(make_disc_mesh(lattice), 2);
  RingDiscMeshOptions rings;
  rings.size_slope = 0.25;
  rings.size_floor = 0.05;
  TriangleMesh ring_mesh = make_ring_disc_mesh(rings);
  ring_mesh.vertices.col(0).array() += 0.3;
  SCOPED_TRACE("rings disc (extraordinary vertices)");
  expect_consistent_vertex_areas(ring_mesh, 4);
}

}  // namespace
}  // namespace growshell
