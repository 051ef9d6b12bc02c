// The quarter turn of a vertex set and its triangulation: found on a ring with a multiple of
// four vertices per ring, refused with a reason on the hexagonal disc (60-degree turns only)
// and on a square grid whose cells are all split along the same diagonal.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <string>

#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/mesh/quarter_turn_symmetry.hpp"

namespace growshell {
namespace {

TEST(QuarterTurnSymmetry, RingWithAMultipleOfFourPerRing) {
  AnnulusMeshOptions o;
  o.inner_radius = 0.25;
  o.radial_layers = 8;
  const int m = annulus_vertices_per_ring(o);
  ASSERT_EQ(m % 4, 0);
  const TriangleMesh mesh = make_annulus_mesh(o);
  const QuarterTurnSymmetry s =
      quarter_turn_symmetry(mesh.vertices, MeshTopology(mesh), Eigen::Vector3d::Zero(), 1e-9);
  // Vertex i of ring j (index (j + 1) m + i) goes to vertex i + m / 4 of the same ring.
  for (int v = 0; v < mesh.vertices.rows(); ++v)
    EXPECT_EQ(s.image[static_cast<std::size_t>(v)], (v / m) * m + (v % m + m / 4) % m) << v;
}

TEST(QuarterTurnSymmetry, HexagonalDiscLacksIt) {
  DiscMeshOptions o;
  o.rings = 6;
  const TriangleMesh mesh = make_disc_mesh(o);
  std::string reason;
  EXPECT_FALSE(find_quarter_turn_symmetry(mesh.vertices, MeshTopology(mesh),
                                          Eigen::Vector3d::Zero(), 1e-9, &reason));
  EXPECT_NE(reason.find("has no image"), std::string::npos) << reason;
  EXPECT_THROW(quarter_turn_symmetry(mesh.vertices, MeshTopology(mesh), Eigen::Vector3d::Zero(), 1e-9),
               std::invalid_argument);
}

TEST(QuarterTurnSymmetry, SquareGridSplitAlongOneDiagonalLacksItInItsFaces) {
  StripMeshOptions o;
  o.length = 1.0;
  o.width = 1.0;
  o.cells_x = 6;
  o.cells_y = 6;
  const TriangleMesh mesh = make_strip_mesh(o);
  std::string reason;
  // The vertex set (a square grid about (L/2, 0)) has the quarter turn; its faces do not.
  EXPECT_FALSE(find_quarter_turn_symmetry(mesh.vertices, MeshTopology(mesh),
                                          Eigen::Vector3d(0.5, 0.0, 0.0), 1e-9, &reason));
  EXPECT_NE(reason.find("which is not a face"), std::string::npos) << reason;
}

TEST(QuarterTurnSymmetry, RejectsBadTolerance) {
  DiscMeshOptions o;
  o.rings = 2;
  const TriangleMesh mesh = make_disc_mesh(o);
  EXPECT_THROW(find_quarter_turn_symmetry(mesh.vertices, MeshTopology(mesh), Eigen::Vector3d::Zero(), 0.0),
               std::invalid_argument);
  EXPECT_THROW(find_quarter_turn_symmetry(mesh.vertices.topRows(5), MeshTopology(mesh),
                                          Eigen::Vector3d::Zero(), 1e-9),
               std::invalid_argument);
}

}  // namespace
}  // namespace growshell
