// Vertex symmetries of the library's disc and annulus meshes (mirrors about the coordinate
// planes through the z-axis, the half turn about z), their defect on states, and the errors
// for vertex sets without the symmetry.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <stdexcept>
#include <string>

#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/mesh/vertex_symmetry.hpp"

namespace growshell {
namespace {

/// The graded disc (inner_radius 0) or the annulus mesh's vertices.
Eigen::MatrixX3d disc_vertices(double inner_radius) {
  if (inner_radius > 0.0) {
    AnnulusMeshOptions a;
    a.inner_radius = inner_radius;
    a.radial_layers = 8;  // 36 vertices per ring: on both mirror axes
    return make_annulus_mesh(a).vertices;
  }
  DiscMeshOptions o;
  o.rings = 6;
  o.grading_exponent = 3.0;
  o.min_spacing = 0.05;
  return make_disc_mesh(o).vertices;
}

TEST(VertexSymmetry, DiscAndAnnulusMeshesHaveBothMirrorsAndTheHalfTurn) {
  for (const double inner : {0.0, 0.25}) {
    const Eigen::MatrixX3d P = disc_vertices(inner);
    for (const VertexSymmetry& s : {mirror_symmetry(P, 0, 1e-9), mirror_symmetry(P, 1, 1e-9),
                                    half_turn_symmetry(P, 2, 1e-9)}) {
      ASSERT_EQ(static_cast<Eigen::Index>(s.image.size()), P.rows());
      EXPECT_LT(symmetry_defect(P, s), 1e-12);
      // An involution: applied twice every vertex comes back.
      for (std::size_t v = 0; v < s.image.size(); ++v)
        EXPECT_EQ(s.image[static_cast<std::size_t>(s.image[v])], static_cast<int>(v));
    }
    const VertexSymmetry my = mirror_symmetry(P, 1, 1e-9);
    EXPECT_EQ(my.signs, Eigen::Vector3d(1.0, -1.0, 1.0));
    // Vertices on the x-axis are their own images; a vertex off it is not.
    int fixed = 0;
    for (Eigen::Index v = 0; v < P.rows(); ++v) {
      const bool on_axis = std::abs(P(v, 1)) < 1e-12;
      EXPECT_EQ(my.image[static_cast<std::size_t>(v)] == v, on_axis) << "vertex " << v;
      fixed += on_axis;
    }
    EXPECT_GT(fixed, 0);
  }
}

TEST(VertexSymmetry, DefectMeasuresHowFarAStateIsFromTheSymmetry) {
  const Eigen::MatrixX3d P = disc_vertices(0.0);
  const VertexSymmetry my = mirror_symmetry(P, 1, 1e-9);
  // A mirror-symmetric lift z = x^2 - y^2 keeps the symmetry; z += 0.01 y breaks it by
  // 2 * 0.01 * max|y| = 0.02 R.
  Eigen::MatrixX3d Q = P;
  Q.col(2) = P.col(0).array().square() - P.col(1).array().square();
  EXPECT_LT(symmetry_defect(Q, my), 1e-12);
  Q.col(2) += 0.01 * P.col(1);
  EXPECT_NEAR(symmetry_defect(Q, my), 0.02 * P.col(1).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(VertexSymmetry, AVertexSetWithoutTheSymmetryIsNamed) {
  Eigen::MatrixX3d P = disc_vertices(0.0);
  P(7, 1) += 1e-3;  // one vertex moved off its mirror position
  try {
    mirror_symmetry(P, 1, 1e-9);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("vertex"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("does not have this symmetry"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(find_vertex_symmetry(P, Eigen::Vector3d(1.0, 0.5, 1.0), 1e-9),
               std::invalid_argument);
  EXPECT_THROW(mirror_symmetry(P, 3, 1e-9), std::invalid_argument);
  EXPECT_THROW(mirror_symmetry(P, 0, 0.0), std::invalid_argument);
  EXPECT_THROW(symmetry_defect(P.topRows(5), mirror_symmetry(disc_vertices(0.0), 0, 1e-9)),
               std::invalid_argument);
}

TEST(VertexSymmetry, SquareGridSplitAlongOneDiagonalHasTheQuarterTurnOnlyInItsVertices) {
  StripMeshOptions o;
  o.length = 1.0;
  o.width = 1.0;
  o.cells_x = 6;
  o.cells_y = 6;
  TriangleMesh mesh = make_strip_mesh(o);
  mesh.vertices.col(0).array() -= 0.5;  // the grid about the origin
  const LinearVertexSymmetry q = quarter_turn_symmetry(mesh.vertices, 1e-9);
  try {
    check_maps_faces_onto_faces(MeshTopology(mesh), q);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("is not a face"), std::string::npos) << e.what();
  }
}

TEST(VertexSymmetry, QuarterTurnIsAGeneralLinearSymmetry) {
  // The annulus (36 vertices per ring) has the quarter turn, faces included; the hexagonal
  // disc (60-degree symmetry) does not.
  AnnulusMeshOptions a;
  a.inner_radius = 0.25;
  a.radial_layers = 8;
  const TriangleMesh annulus = make_annulus_mesh(a);
  const LinearVertexSymmetry q = quarter_turn_symmetry(annulus.vertices, 1e-9);
  EXPECT_LT(symmetry_defect(annulus.vertices, q), 1e-12);
  EXPECT_NO_THROW(check_maps_faces_onto_faces(MeshTopology(annulus), q));
  // Order 4: q^4 = id, q^2 = the half turn.
  const VertexSymmetry half = half_turn_symmetry(annulus.vertices, 2, 1e-9);
  for (std::size_t v = 0; v < q.image.size(); ++v) {
    const int q2 = q.image[static_cast<std::size_t>(q.image[v])];
    EXPECT_EQ(q2, half.image[v]);
    EXPECT_EQ(q.image[static_cast<std::size_t>(q.image[static_cast<std::size_t>(q2)])],
              static_cast<int>(v));
  }
  // A lift z = 0.01 x lacks the quarter turn: its defect is max 0.01 |x + y| = 0.014 R.
  Eigen::MatrixX3d lifted = annulus.vertices;
  lifted.col(2) = 0.01 * annulus.vertices.col(0);
  EXPECT_GT(symmetry_defect(lifted, q), 0.005);
  try {
    quarter_turn_symmetry(disc_vertices(0.0), 1e-9);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("does not have this symmetry"), std::string::npos)
        << e.what();
  }
  Eigen::Matrix3d not_orthogonal = Eigen::Matrix3d::Identity();
  not_orthogonal(0, 1) = 0.5;
  EXPECT_THROW(find_linear_vertex_symmetry(annulus.vertices, not_orthogonal, 1e-9),
               std::invalid_argument);
}

}  // namespace
}  // namespace growshell
