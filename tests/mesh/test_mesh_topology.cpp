#include "libshell/mesh/mesh_topology.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/mesh/mesh_error.hpp"
#include "tests/support/mesh_checks.hpp"

namespace growshell {
namespace {

using test_support::mesh_error_message;

Eigen::MatrixX3i faces_of(std::initializer_list<std::array<int, 3>> list) {
  Eigen::MatrixX3i faces(static_cast<Eigen::Index>(list.size()), 3);
  Eigen::Index f = 0;
  for (const auto& t : list) faces.row(f++) << t[0], t[1], t[2];
  return faces;
}

// Hexagon fan: centre 0, rim 1..6 counter-clockwise.
Eigen::MatrixX3i hexagon_fan() {
  return faces_of({{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {0, 5, 6}, {0, 6, 1}});
}

double cross_z(const TriangleMesh& mesh, int v, int a, int b) {
  const Eigen::Vector2d da = (mesh.vertices.row(a) - mesh.vertices.row(v)).head<2>();
  const Eigen::Vector2d db = (mesh.vertices.row(b) - mesh.vertices.row(v)).head<2>();
  return da.x() * db.y() - da.y() * db.x();
}

// Checks the one-rings of a planar CCW mesh geometrically: consecutive neighbours turn
// counter-clockwise by less than pi, and around an interior vertex the turns add up to 2 pi.
void expect_ccw_rings(const TriangleMesh& mesh) {
  const MeshTopology topo(mesh);
  for (int v = 0; v < topo.num_vertices(); ++v) {
    const auto& ring = topo.one_ring(v);
    const bool closed = !topo.is_boundary_vertex(v);
    const std::size_t turns = closed ? ring.size() : ring.size() - 1;
    double total_angle = 0.0;
    for (std::size_t i = 0; i < turns; ++i) {
      const int a = ring[i];
      const int b = ring[(i + 1) % ring.size()];
      const double cz = cross_z(mesh, v, a, b);
      ASSERT_GT(cz, 0.0) << "vertex " << v << ", ring entries " << i << ", " << i + 1;
      const Eigen::Vector2d da = (mesh.vertices.row(a) - mesh.vertices.row(v)).head<2>();
      const Eigen::Vector2d db = (mesh.vertices.row(b) - mesh.vertices.row(v)).head<2>();
      total_angle += std::atan2(cz, da.dot(db));
    }
    // Sum of ~6 atan2 results, each accurate to a few ulps.
    if (closed) {
      EXPECT_NEAR(total_angle, 2.0 * std::numbers::pi, 1e-12) << "vertex " << v;
    }
  }
}

TEST(MeshTopology, SingleTriangleIsAllBoundary) {
  const MeshTopology topo(3, faces_of({{0, 1, 2}}));
  EXPECT_EQ(topo.num_vertices(), 3);
  EXPECT_EQ(topo.num_faces(), 1);
  for (int v = 0; v < 3; ++v) {
    EXPECT_TRUE(topo.is_boundary_vertex(v));
    EXPECT_EQ(topo.valence(v), 2);
  }
  EXPECT_EQ(topo.one_ring(0), (std::vector<int>{1, 2}));
  EXPECT_EQ(topo.one_ring(1), (std::vector<int>{2, 0}));
  EXPECT_EQ(topo.one_ring(2), (std::vector<int>{0, 1}));
  EXPECT_EQ(topo.opposite_vertex(0, 1), 2);
  EXPECT_EQ(topo.opposite_vertex(1, 2), 0);
  EXPECT_EQ(topo.opposite_vertex(2, 0), 1);
  EXPECT_EQ(topo.opposite_vertex(1, 0), -1);
  EXPECT_EQ(topo.face_with_edge(2, 0), 0);
  EXPECT_EQ(topo.face_with_edge(0, 2), -1);
}

TEST(MeshTopology, HexagonFanRings) {
  const MeshTopology topo(7, hexagon_fan());
  EXPECT_FALSE(topo.is_boundary_vertex(0));
  EXPECT_EQ(topo.valence(0), 6);
  EXPECT_EQ(topo.one_ring(0), (std::vector<int>{1, 2, 3, 4, 5, 6}));
  // Rim vertex 1: edge 1-2 has its face on the counter-clockwise side only, so the fan starts
  // there and ends at 6.
  EXPECT_TRUE(topo.is_boundary_vertex(1));
  EXPECT_EQ(topo.one_ring(1), (std::vector<int>{2, 0, 6}));
  EXPECT_EQ(topo.one_ring(6), (std::vector<int>{1, 0, 5}));
  EXPECT_EQ(topo.opposite_vertex(0, 6), 1);
  EXPECT_EQ(topo.opposite_vertex(6, 0), 5);
  EXPECT_EQ(topo.opposite_vertex(1, 6), -1);  // boundary edge, traversed only as 6 -> 1
  EXPECT_EQ(topo.opposite_vertex(1, 4), -1);  // not neighbours
  EXPECT_EQ(topo.face_with_edge(6, 0), 4);
}

TEST(MeshTopology, OppositeVertexMatchesEveryFace) {
  const TriangleMesh mesh = make_disc_mesh({.radius = 1.0, .rings = 4});
  const MeshTopology topo(mesh);
  for (int f = 0; f < topo.num_faces(); ++f) {
    const auto& t = topo.face(f);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(topo.opposite_vertex(t[k], t[(k + 1) % 3]), t[(k + 2) % 3]);
      EXPECT_EQ(topo.face_with_edge(t[k], t[(k + 1) % 3]), f);
    }
  }
}

TEST(MeshTopology, OneRingsAreCounterClockwiseOnLatticeMeshes) {
  expect_ccw_rings(make_disc_mesh({.radius = 1.0, .rings = 5}));
  expect_ccw_rings(
      make_disc_mesh({.radius = 2.0, .rings = 8, .grading_exponent = 2.0, .min_spacing = 0.05}));
  expect_ccw_rings(
      make_annulus_mesh({.inner_radius = 0.3, .outer_radius = 1.0, .radial_layers = 5}));
  expect_ccw_rings(make_strip_mesh({.length = 2.0, .width = 0.3, .cells_x = 7, .cells_y = 3}));
}

TEST(MeshTopology, RejectsBadConnectivity) {
  EXPECT_CONTAINS(mesh_error_message([] {
                    MeshTopology(3, faces_of({{0, 1, 3}}));
                  }),
                  "face 0 refers to vertex 3");
  EXPECT_CONTAINS(mesh_error_message([] { MeshTopology(3, faces_of({{0, 1, -1}})); }), "vertex -1");
  EXPECT_CONTAINS(mesh_error_message([] {
                    MeshTopology(4, faces_of({{0, 1, 2}, {2, 3, 3}}));
                  }),
                  "face 1 (2, 3, 3) repeats a vertex");
  const std::string non_manifold = mesh_error_message([] {
    MeshTopology(5, faces_of({{0, 1, 2}, {1, 0, 3}, {4, 0, 1}}));
  });
  EXPECT_CONTAINS(non_manifold, "non-manifold edge (0, 1)");
  EXPECT_CONTAINS(non_manifold, "3 faces (0, 1, 2)");
  EXPECT_CONTAINS(mesh_error_message([] {
                    MeshTopology(4, faces_of({{0, 1, 2}, {3, 1, 2}}));
                  }),
                  "faces 0 and 1 both traverse the edge 1 -> 2");
  // Bow tie: two triangles touching only at vertex 2.
  EXPECT_CONTAINS(mesh_error_message([] {
                    MeshTopology(5, faces_of({{0, 1, 2}, {2, 3, 4}}));
                  }),
                  "vertex 2 is non-manifold");
  // Two closed fans around vertex 0 (two hexagon fans glued at their centre).
  EXPECT_CONTAINS(
      mesh_error_message([] {
        MeshTopology(7,
                     faces_of({{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {0, 4, 5}, {0, 5, 6}, {0, 6, 4}}));
      }),
      "vertex 0 is non-manifold");
  EXPECT_CONTAINS(mesh_error_message([] {
                    MeshTopology(4, faces_of({{0, 1, 2}}));
                  }),
                  "vertex 3 is not used by any face");
  const MeshTopology topo(3, faces_of({{0, 1, 2}}));
  EXPECT_CONTAINS(mesh_error_message([&] { topo.one_ring(3); }), "vertex 3");
  EXPECT_CONTAINS(mesh_error_message([&] { topo.opposite_vertex(0, 7); }), "vertex 7");
}

}  // namespace
}  // namespace growshell
