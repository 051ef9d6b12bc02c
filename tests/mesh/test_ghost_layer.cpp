// add_ghost_layer on planar sheets with one boundary loop (ring disc, squares with corners) and
// two (annulus): the result is a valid control mesh whose elements are exactly the sheet's
// faces, no ghost face is inverted, the corner rule splits exactly the large gaps, and the
// construction commutes with the sheets' mirrors and quarter turn.
#include "libshell/mesh/ghost_layer.hpp"

#include <algorithm>
#include <functional>
#include <map>
#include <numbers>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/mesh/mesh_error.hpp"
#include "libshell/mesh/mesh_topology.hpp"
#include "libshell/mesh/ring_disc_mesh.hpp"
#include "libshell/mesh/vertex_symmetry.hpp"
#include "tests/support/mesh_checks.hpp"

namespace growshell {
namespace {

using test_support::mesh_error_message;

double signed_area(const TriangleMesh& m, int f) {
  const Eigen::Vector2d a = m.vertices.row(m.faces(f, 0)).head<2>();
  const Eigen::Vector2d b = m.vertices.row(m.faces(f, 1)).head<2>();
  const Eigen::Vector2d c = m.vertices.row(m.faces(f, 2)).head<2>();
  const Eigen::Vector2d u = b - a;
  const Eigen::Vector2d v = c - a;
  return 0.5 * (u.x() * v.y() - u.y() * v.x());
}

/// The square [-1, 1]^2 as an n x n grid (n even), each cell split by the diagonal through the
/// corner nearest to the centre (`towards_center`, the "union jack") or by the other one. Both
/// are symmetric under the mirrors and the quarter turn; without `towards_center` each sheet
/// corner has a single face (a 90 degree corner whose gap needs the split).
TriangleMesh square_sheet(int n, bool towards_center) {
  TriangleMesh m;
  m.vertices.setZero((n + 1) * (n + 1), 3);
  const auto id = [&](int i, int j) { return i + (n + 1) * j; };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      m.vertices.row(id(i, j)) << -1.0 + 2.0 * i / n, -1.0 + 2.0 * j / n, 0.0;
  m.faces.resize(2 * n * n, 3);
  int f = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      // The cell's corner nearest to the centre is at (i or i+1, j or j+1).
      const bool left = i >= n / 2;   // nearest corner on the cell's left (low i) side
      const bool below = j >= n / 2;  // nearest corner on the low j side
      // Diagonal (i,j)-(i+1,j+1) passes through the nearest corner iff left == below.
      const bool main_diagonal = (left == below) == towards_center;
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (main_diagonal) {
        m.faces.row(f++) << a, b, c;
        m.faces.row(f++) << a, c, d;
      } else {
        m.faces.row(f++) << a, b, d;
        m.faces.row(f++) << b, c, d;
      }
    }
  return m;
}

/// The elements (faces with three interior vertices) of make_annulus_mesh, as a sheet with
/// compacted vertex indices: two boundary loops.
TriangleMesh annulus_sheet() {
  AnnulusMeshOptions o;
  o.inner_radius = 0.3;
  o.radial_layers = 6;
  const TriangleMesh full = make_annulus_mesh(o);
  const MeshTopology topo(full);
  std::vector<int> index(static_cast<std::size_t>(full.vertices.rows()), -1);
  std::vector<Eigen::Vector3i> faces;
  int nv = 0;
  for (int f = 0; f < topo.num_faces(); ++f) {
    const auto& t = topo.face(f);
    if (std::any_of(t.begin(), t.end(), [&](int v) { return topo.is_boundary_vertex(v); }))
      continue;
    for (const int v : t)
      if (index[static_cast<std::size_t>(v)] < 0) index[static_cast<std::size_t>(v)] = nv++;
    faces.emplace_back(index[static_cast<std::size_t>(t[0])], index[static_cast<std::size_t>(t[1])],
                       index[static_cast<std::size_t>(t[2])]);
  }
  TriangleMesh sheet;
  sheet.vertices.resize(nv, 3);
  for (int v = 0; v < full.vertices.rows(); ++v)
    if (index[static_cast<std::size_t>(v)] >= 0)
      sheet.vertices.row(index[static_cast<std::size_t>(v)]) = full.vertices.row(v);
  sheet.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    sheet.faces.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  return sheet;
}

TriangleMesh small_ring_disc_sheet() {
  RingDiscMeshOptions o;
  o.size_floor = 0.08;  // 4 core rings with a doubling, then the log-polar rings
  return make_ring_disc_sheet(o);
}

/// How the fans of the sheet's boundary vertices were closed.
struct Closures {
  int split = 0;   ///< gaps closed by an extra ghost and two faces (valence + 3)
  int merged = 0;  ///< coincident ghosts merged (valence + 1)
};

/// The checks every ghosted planar sheet must pass.
Closures expect_valid_ghost_layer(const TriangleMesh& sheet, const TriangleMesh& mesh) {
  const int n = static_cast<int>(sheet.vertices.rows());
  const MeshTopology sheet_topo(sheet);
  const MeshTopology topo(mesh);  // throws for a non-manifold or inconsistently oriented mesh
  Closures closures;
  EXPECT_EQ(mesh.vertices.topRows(n), sheet.vertices);
  EXPECT_EQ(mesh.faces.topRows(sheet.faces.rows()), sheet.faces);
  for (int v = 0; v < n; ++v) {
    EXPECT_FALSE(topo.is_boundary_vertex(v)) << "sheet vertex " << v;
    if (!sheet_topo.is_boundary_vertex(v)) {
      EXPECT_EQ(topo.valence(v), sheet_topo.valence(v)) << "interior vertex " << v;
    } else {
      const int extra = topo.valence(v) - sheet_topo.valence(v);
      EXPECT_TRUE(extra >= 1 && extra <= 3) << "boundary vertex " << v << " gained " << extra;
      closures.split += extra == 3;
      closures.merged += extra == 1;
    }
  }
  for (int v = n; v < topo.num_vertices(); ++v) EXPECT_TRUE(topo.is_boundary_vertex(v));
  int elements = 0;
  for (int f = 0; f < topo.num_faces(); ++f) {
    const auto& t = topo.face(f);
    const bool element =
        std::none_of(t.begin(), t.end(), [&](int v) { return topo.is_boundary_vertex(v); });
    elements += element;
    EXPECT_EQ(element, f < sheet.faces.rows()) << "face " << f;
    EXPECT_GT(signed_area(mesh, f), 0.0) << "face " << f << " is inverted or degenerate";
  }
  EXPECT_EQ(elements, sheet.faces.rows());
  int boundary_edges = 0;
  for (int v = 0; v < n; ++v)
    if (sheet_topo.is_boundary_vertex(v)) ++boundary_edges;  // one outgoing edge per vertex
  // One ghost per boundary edge, one more per split gap, one fewer per merged pair.
  EXPECT_EQ(topo.num_vertices() - n, boundary_edges + closures.split - closures.merged);
  return closures;
}

TEST(GhostLayer, RingDiscSheetBecomesAControlMeshWithTheSheetAsElements) {
  const TriangleMesh sheet = small_ring_disc_sheet();
  const TriangleMesh mesh = add_ghost_layer(sheet);
  const Closures c = expect_valid_ghost_layer(sheet, mesh);
  EXPECT_EQ(c.split + c.merged, 0);
  // A smooth boundary needs no split: one ghost per rim edge, one closing face per rim vertex.
  const int rim = static_cast<int>(ring_disc_rings(RingDiscMeshOptions{.size_floor = 0.08})
                                       .counts.back());
  EXPECT_EQ(mesh.vertices.rows(), sheet.vertices.rows() + rim);
  EXPECT_EQ(mesh.faces.rows(), sheet.faces.rows() + 2 * rim);
}

TEST(GhostLayer, AnnulusSheetWithTwoBoundaryLoops) {
  const TriangleMesh sheet = annulus_sheet();
  const TriangleMesh mesh = add_ghost_layer(sheet);
  const Closures c = expect_valid_ghost_layer(sheet, mesh);
  EXPECT_EQ(c.split + c.merged, 0);
  // Ghosts of the inner loop lie inside the hole, those of the outer loop outside the disc.
  const MeshTopology sheet_topo(sheet);
  int inner = 0;
  int outer = 0;
  for (Eigen::Index g = sheet.vertices.rows(); g < mesh.vertices.rows(); ++g) {
    const double r = mesh.vertices.row(g).norm();
    inner += r < 0.3;
    outer += r > 1.0;
  }
  EXPECT_EQ(inner + outer, mesh.vertices.rows() - sheet.vertices.rows());
  EXPECT_GT(inner, 0);
  EXPECT_EQ(inner, outer);  // both loops have M vertices
}

TEST(GhostLayer, SquareCornersAreSplitOnlyWhereTheGapIsLarge) {
  for (const bool towards_center : {true, false}) {
    SCOPED_TRACE(towards_center ? "union jack" : "corner faces");
    const TriangleMesh sheet = square_sheet(4, towards_center);
    const TriangleMesh mesh = add_ghost_layer(sheet);
    // Union jack: a corner has two faces (45 + 45 degrees) and ghost faces of 90 degrees each,
    // leaving a 90 degree gap: one face. Otherwise a corner has one face (90 degrees) and ghost
    // faces of 45 degrees: a 180 degree gap, split by an extra ghost on the diagonal; and at
    // the midpoint of each side both boundary faces have their right angle at the far end, so
    // both ghosts are the point below the midpoint (gap 0) and are merged.
    const Closures c = expect_valid_ghost_layer(sheet, mesh);
    EXPECT_EQ(c.split, towards_center ? 0 : 4);
    EXPECT_EQ(c.merged, towards_center ? 0 : 4);
    const MeshTopology topo(mesh);
    EXPECT_EQ(topo.valence(0), 5);  // corner (-1, -1): sheet valence 3 + 2, or 2 + 3
    if (!towards_center) {
      const Eigen::Index e = mesh.vertices.rows() - 4;  // extra ghost of corner 0 comes first
      EXPECT_EQ(MeshTopology(sheet).valence(2), 5);
      EXPECT_EQ(topo.valence(2), 6);  // side midpoint (0, -1): merged ghost at (0, -1.5)
      // 2 v - (mean of the neighbours (-0.5, -1) and (-1, -0.5)) = (-1.25, -1.25).
      EXPECT_NEAR(mesh.vertices(e, 0), -1.25, 1e-15);
      EXPECT_NEAR(mesh.vertices(e, 1), -1.25, 1e-15);
    }
  }
}

/// The symmetry `find` of the sheet's vertices extends to the ghosted mesh, maps its faces
/// onto faces, and acts on the sheet vertices as on the sheet.
void expect_equivariant(const TriangleMesh& sheet,
                        const std::function<std::vector<int>(const Eigen::MatrixX3d&)>& find,
                        const std::function<void(const MeshTopology&, const Eigen::MatrixX3d&)>&
                            check_faces) {
  const TriangleMesh mesh = add_ghost_layer(sheet);
  const std::vector<int> sheet_image = find(sheet.vertices);
  check_faces(MeshTopology(sheet), sheet.vertices);
  std::vector<int> image;
  ASSERT_NO_THROW(image = find(mesh.vertices)) << "the ghost vertices lack the symmetry";
  for (std::size_t v = 0; v < sheet_image.size(); ++v) EXPECT_EQ(image[v], sheet_image[v]);
  EXPECT_NO_THROW(check_faces(MeshTopology(mesh), mesh.vertices));
}

TEST(GhostLayer, CommutesWithTheMirrorsAndTheQuarterTurnOfTheSheet) {
  const std::vector<TriangleMesh> sheets = {small_ring_disc_sheet(), square_sheet(4, true),
                                            square_sheet(4, false), square_sheet(6, false)};
  for (std::size_t s = 0; s < sheets.size(); ++s) {
    SCOPED_TRACE("sheet " + std::to_string(s));
    for (const int axis : {0, 1}) {
      expect_equivariant(
          sheets[s],
          [&](const Eigen::MatrixX3d& P) { return mirror_symmetry(P, axis, 1e-12).image; },
          [&](const MeshTopology& t, const Eigen::MatrixX3d& P) {
            check_maps_faces_onto_faces(t, mirror_symmetry(P, axis, 1e-12));
          });
    }
    expect_equivariant(
        sheets[s], [&](const Eigen::MatrixX3d& P) { return quarter_turn_symmetry(P, 1e-12).image; },
        [&](const MeshTopology& t, const Eigen::MatrixX3d& P) {
          check_maps_faces_onto_faces(t, quarter_turn_symmetry(P, 1e-12));
        });
  }
}

/// The L-shaped sheet [0, 2]^2 minus (1, 2)^2 of three unit cells, split by the diagonal
/// (i, j)-(i+1, j+1), except cell (1, 0) if `anti` (split by the other diagonal).
TriangleMesh l_sheet(bool anti) {
  TriangleMesh m;
  m.vertices.resize(8, 3);
  // 0 (0,0) 1 (1,0) 2 (2,0) 3 (0,1) 4 (1,1) 5 (2,1) 6 (0,2) 7 (1,2)
  m.vertices << 0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0, 0, 2, 0, 1, 2, 0;
  m.faces.resize(6, 3);
  m.faces << 0, 1, 4, 0, 4, 3,  // cell (0, 0)
      3, 4, 7, 3, 7, 6,         // cell (0, 1)
      1, 2, 5, 1, 5, 4;         // cell (1, 0)
  if (anti) m.faces.bottomRows(2) << 1, 2, 4, 2, 5, 4;
  return m;
}

TEST(GhostLayer, CoincidentOrOverlappingGhostsAtAReflexCornerAreMerged) {
  // Reflex corner (1, 1) (270 degrees). Main diagonals: both ghost faces have 45 degrees there,
  // the gap is 0 and both ghosts are (2, 2), the missing corner, exactly. Anti-diagonal in
  // cell (1, 0): its ghost face has 90 degrees at (1, 1), the ghost faces would overlap by
  // 45 degrees, and the merged ghost is the mean of (1, 2) and (2, 2).
  for (const bool anti : {false, true}) {
    SCOPED_TRACE(anti ? "overlap" : "coincident");
    const TriangleMesh sheet = l_sheet(anti);
    const TriangleMesh mesh = add_ghost_layer(sheet);
    const Closures c = expect_valid_ghost_layer(sheet, mesh);
    EXPECT_GE(c.merged, 1);
    bool found = false;
    const Eigen::RowVector3d expected(anti ? 1.5 : 2.0, 2.0, 0.0);
    for (Eigen::Index g = sheet.vertices.rows(); g < mesh.vertices.rows(); ++g)
      found = found || mesh.vertices.row(g) == expected;
    EXPECT_TRUE(found);
  }
}

TEST(GhostLayer, RejectsInvalidSheets) {
  EXPECT_CONTAINS(mesh_error_message([] { add_ghost_layer(TriangleMesh{}); }), "no faces");
  TriangleMesh sheet = square_sheet(2, true);
  sheet.faces.row(3) = sheet.faces.row(3).reverse().eval();
  EXPECT_THROW(add_ghost_layer(sheet), MeshError);  // inconsistent orientation (MeshTopology)
  sheet = square_sheet(2, true);
  sheet.faces.col(1).swap(sheet.faces.col(2));  // every face clockwise
  EXPECT_CONTAINS(mesh_error_message([&] { add_ghost_layer(sheet); }),
                  "sheet face 0 (0, 4, 1) is not counter-clockwise");
  sheet = square_sheet(2, true);
  sheet.vertices(4, 2) = 0.1;
  EXPECT_CONTAINS(mesh_error_message([&] { add_ghost_layer(sheet); }),
                  "sheet vertex 4 has z = 0.1");
}

}  // namespace
}  // namespace growshell
