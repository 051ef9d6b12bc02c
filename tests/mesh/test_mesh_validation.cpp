#include "libshell/mesh/mesh_validation.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/mesh/mesh_error.hpp"
#include "tests/support/expect_contains.hpp"

namespace growshell {
namespace {

std::string validation_message(const TriangleMesh& mesh) {
  try {
    validate_control_mesh(mesh);
  } catch (const MeshError& e) {
    return e.what();
  }
  return "<no MeshError thrown>";
}

// Centre vertex 0 at the origin and n rim vertices 1..n on the unit circle, CCW fan.
TriangleMesh fan(int n) {
  TriangleMesh mesh;
  mesh.vertices.setZero(n + 1, 3);
  mesh.faces.resize(n, 3);
  for (int i = 0; i < n; ++i) {
    const double angle = 2.0 * std::numbers::pi * i / n;
    mesh.vertices.row(i + 1) << std::cos(angle), std::sin(angle), 0.0;
    mesh.faces.row(i) << 0, i + 1, (i + 1) % n + 1;
  }
  return mesh;
}

int find_face(const TriangleMesh& mesh, int a, int b, int c) {
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    if (mesh.faces(f, 0) == a && mesh.faces(f, 1) == b && mesh.faces(f, 2) == c) {
      return static_cast<int>(f);
    }
  }
  return -1;
}

TEST(ValidateControlMesh, AcceptsGeneratedMeshes) {
  EXPECT_NO_THROW(validate_control_mesh(make_disc_mesh({})));
  EXPECT_NO_THROW(validate_control_mesh(
      make_disc_mesh({.rings = 12, .grading_exponent = 3.0, .min_spacing = 0.01})));
  EXPECT_NO_THROW(validate_control_mesh(make_annulus_mesh({})));
  EXPECT_NO_THROW(validate_control_mesh(make_strip_mesh({})));
  // A curved (non-planar) disc has no folds either.
  TriangleMesh dome = make_disc_mesh({.rings = 6});
  for (Eigen::Index v = 0; v < dome.vertices.rows(); ++v) {
    dome.vertices(v, 2) = 0.5 * dome.vertices.row(v).squaredNorm();
  }
  EXPECT_NO_THROW(validate_control_mesh(dome));
}

TEST(ValidateControlMesh, RejectsBadConnectivity) {
  TriangleMesh mesh = fan(6);
  mesh.faces(3, 2) = 9;
  EXPECT_CONTAINS(validation_message(mesh), "face 3 refers to vertex 9");
  mesh = fan(6);
  mesh.faces(2, 1) = 0;
  EXPECT_CONTAINS(validation_message(mesh), "face 2 (0, 0, 4) repeats a vertex");
  mesh = fan(6);
  mesh.vertices.conservativeResize(9, 3);
  mesh.vertices.row(7) << 0.0, 2.0, 1.0;
  mesh.vertices.row(8) << 0.0, 2.0, -1.0;
  mesh.faces.conservativeResize(7, 3);
  mesh.faces.row(6) << 2, 3, 7;  // a second face on edge 2-3, same direction as face 1
  EXPECT_CONTAINS(validation_message(mesh), "faces 1 and 6 both traverse the edge 2 -> 3");
  mesh.faces.conservativeResize(8, 3);
  mesh.faces.row(7) << 3, 2, 8;  // and a third one
  EXPECT_CONTAINS(validation_message(mesh), "non-manifold edge (2, 3) is shared by 3 faces");
  mesh = fan(6);
  mesh.vertices.conservativeResize(9, 3);
  mesh.vertices.row(7) << 2.0, 0.0, 0.0;
  mesh.vertices.row(8) << 2.0, 1.0, 0.0;
  mesh.faces.conservativeResize(7, 3);
  mesh.faces.row(6) << 1, 7, 8;  // touches the fan only at vertex 1
  EXPECT_CONTAINS(validation_message(mesh), "vertex 1 is non-manifold");
  mesh = fan(6);
  mesh.vertices.conservativeResize(8, 3);
  mesh.vertices.row(7) << 5.0, 5.0, 0.0;
  EXPECT_CONTAINS(validation_message(mesh), "vertex 7 is not used by any face");
  EXPECT_CONTAINS(validation_message(TriangleMesh{}), "no faces");
}

TEST(ValidateControlMesh, RejectsNonFiniteCoordinates) {
  TriangleMesh mesh = make_disc_mesh({.rings = 3});
  mesh.vertices(5, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_CONTAINS(validation_message(mesh), "vertex 5 has a non-finite coordinate y");
  mesh = make_disc_mesh({.rings = 3});
  mesh.vertices(11, 2) = std::numeric_limits<double>::infinity();
  EXPECT_CONTAINS(validation_message(mesh), "vertex 11 has a non-finite coordinate z");
}

TEST(ValidateControlMesh, RejectsDegenerateTriangle) {
  const StripMeshOptions options{.length = 1.0, .width = 1.0, .cells_x = 2, .cells_y = 2};
  TriangleMesh mesh = make_strip_mesh(options);
  const int v00 = strip_vertex_index(options, 0, 0);
  const int v10 = strip_vertex_index(options, 1, 0);
  const int v11 = strip_vertex_index(options, 1, 1);
  // Put (1,1) on the line through (0,0) and (1,0): face (v00, v10, v11) gets zero area (its
  // neighbours fold too, but degeneracy is reported first).
  mesh.vertices.row(v11) << 0.75, mesh.vertices(v00, 1), 0.0;
  const int f = find_face(mesh, v00, v10, v11);
  ASSERT_GE(f, 0);
  const std::string message = validation_message(mesh);
  EXPECT_CONTAINS(message, "face " + std::to_string(f) + " (");
  EXPECT_CONTAINS(message, "is degenerate");
}

TEST(ValidateControlMesh, RejectsInvertedTriangleInPlane) {
  // Moving the centre of a hexagon fan to (1.5, 0) beyond rim vertex 1 flips faces 0 (0,1,2)
  // and 5 (0,6,1) (signed areas -0.43 and -1.30) and leaves four positive ones.
  TriangleMesh mesh = fan(6);
  mesh.vertices.row(0) << 1.5, 0.0, 0.0;
  const std::string message = validation_message(mesh);
  EXPECT_CONTAINS(message, "face 0 (0, 1, 2) is inverted");
  // Same with the whole mesh oriented clockwise: the majority defines the orientation.
  mesh.faces.col(1).swap(mesh.faces.col(2));
  EXPECT_CONTAINS(validation_message(mesh), "face 0 (0, 2, 1) is inverted");
}

TEST(ValidateControlMesh, RejectsFoldInCurvedMesh) {
  // Pyramid (centre raised to z = 0.3), then the apex pulled past rim vertex 1: faces 0 and 5
  // turn their normals downwards while their neighbours 1 and 4 still point up.
  TriangleMesh mesh = fan(6);
  mesh.vertices.row(0) << 0.0, 0.0, 0.3;
  EXPECT_CONTAINS(validation_message(mesh), "no element");  // not folded, just too small
  mesh.vertices.row(0) << 1.5, 0.0, 0.3;
  const std::string message = validation_message(mesh);
  EXPECT_CONTAINS(message, "faces 0 and 1 are folded over their shared edge (2, 0)");
}

TEST(ValidateControlMesh, RejectsInteriorValenceAboveTwelve) {
  EXPECT_CONTAINS(validation_message(fan(13)),
                  "interior vertex 0 has valence 13; growshell's Loop elements support interior "
                  "valences 3 to 12");
  // Valences up to 12 pass the valence check (these small fans then have no element).
  EXPECT_CONTAINS(validation_message(fan(12)), "the mesh has no element");
  EXPECT_CONTAINS(validation_message(fan(3)), "the mesh has no element");
}

TEST(ValidateControlMesh, AcceptsIrregularVertexInsideTheSheet) {
  // Split one element of a disc by inserting a vertex at its centroid (valence 3; its
  // neighbours get valence 7): a valid control mesh for the irregular Loop element.
  TriangleMesh mesh = make_disc_mesh({.rings = 4});
  const Eigen::Index f = 0;
  const int a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
  const int centroid = static_cast<int>(mesh.vertices.rows());
  mesh.vertices.conservativeResize(centroid + 1, 3);
  mesh.vertices.row(centroid) =
      (mesh.vertices.row(a) + mesh.vertices.row(b) + mesh.vertices.row(c)) / 3.0;
  const Eigen::Index nf = mesh.faces.rows();
  mesh.faces.row(f) << a, b, centroid;
  mesh.faces.conservativeResize(nf + 2, 3);
  mesh.faces.row(nf) << b, c, centroid;
  mesh.faces.row(nf + 1) << c, a, centroid;
  EXPECT_EQ(validation_message(mesh), "<no MeshError thrown>");
}

TEST(ValidateControlMesh, RejectsMeshWithoutElements) {
  // One hexagon: its centre is regular but every face has two rim (ghost) vertices.
  EXPECT_CONTAINS(validation_message(fan(6)), "the mesh has no element");
}

}  // namespace
}  // namespace growshell
