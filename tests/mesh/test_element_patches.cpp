#include "libshell/subdivision/element_patches.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/mesh/mesh_error.hpp"

namespace growshell {
namespace {

// Node n (index n-1) of the regular patch in lattice coordinates (alpha, beta) relative to
// node 4, i.e. position = alpha e1 + beta e2 with e1 = (1,0), e2 = (1/2, sqrt(3)/2).
constexpr int kLayout[12][2] = {{-1, 1}, {0, 1},  {-1, 0}, {0, 0},  {1, 0},  {-1, -1},
                                {0, -1}, {1, -1}, {2, -1}, {0, -2}, {1, -2}, {2, -2}};

// Checks that every element's control points are the affine image of the layout: with the
// element's own edge vectors E1 = x8 - x7 (image of e1) and E2 = x4 - x7 (image of e2),
// x_n = x4 + alpha_n E1 + beta_n E2. Returns the largest deviation relative to |E1|.
double max_layout_deviation(const TriangleMesh& mesh, const ElementPatches& patches) {
  double worst = 0.0;
  for (std::size_t e = 0; e < patches.patch.size(); ++e) {
    const auto& p = patches.patch[e].control;
    auto x = [&](int node) -> Eigen::Vector3d {
      return mesh.vertices.row(p[node - 1]).transpose();
    };
    const Eigen::Vector3d E1 = x(8) - x(7);
    const Eigen::Vector3d E2 = x(4) - x(7);
    for (int n = 1; n <= 12; ++n) {
      const Eigen::Vector3d expected = x(4) + kLayout[n - 1][0] * E1 + kLayout[n - 1][1] * E2;
      worst = std::max(worst, (x(n) - expected).norm() / E1.norm());
    }
  }
  return worst;
}

// Checks that the element list is exactly the faces with three interior valence-6 vertices,
// in increasing order, and that nodes 4, 7, 8 are that face's (a, b, c).
void expect_elements_are_regular_interior_faces(const MeshTopology& topo,
                                                const ElementPatches& patches) {
  ASSERT_EQ(patches.patch.size(), patches.face.size());
  std::size_t e = 0;
  for (int f = 0; f < topo.num_faces(); ++f) {
    const auto& t = topo.face(f);
    const bool element = std::all_of(t.begin(), t.end(), [&](int v) {
      return !topo.is_boundary_vertex(v) && topo.valence(v) == 6;
    });
    if (!element) continue;
    ASSERT_LT(e, patches.face.size());
    EXPECT_EQ(patches.face[e], f);
    EXPECT_EQ(patches.patch[e].control[3], t[0]);
    EXPECT_EQ(patches.patch[e].control[6], t[1]);
    EXPECT_EQ(patches.patch[e].control[7], t[2]);
    ++e;
  }
  EXPECT_EQ(e, patches.face.size());
}

TEST(ElementPatches, EquilateralLatticeFromStripTopology) {
  // Strip connectivity with grid vertex (i, j) moved to -(i e1 + j (e2 - e1)): both triangles
  // of every grid square become unit equilateral triangles, and the second triangle of each
  // square, (v00, v11, v01) -> (0, -e2, e1 - e2), has exactly the layout's orientation.
  const StripMeshOptions options{.length = 1.0, .width = 1.0, .cells_x = 6, .cells_y = 5};
  TriangleMesh mesh = make_strip_mesh(options);
  const Eigen::Vector3d e1(1.0, 0.0, 0.0);
  const Eigen::Vector3d e2(0.5, std::sqrt(3.0) / 2.0, 0.0);
  for (int j = -1; j <= 6; ++j) {
    for (int i = -1; i <= 7; ++i) {
      mesh.vertices.row(strip_vertex_index(options, i, j)) =
          (-(i * e1 + j * (e2 - e1))).transpose();
    }
  }
  const MeshTopology topo(mesh);
  const ElementPatches patches = build_element_patches(topo);
  EXPECT_EQ(patches.patch.size(), 2u * 6 * 5);
  expect_elements_are_regular_interior_faces(topo, patches);
  // Coordinates are small integer combinations of e1, e2: exact up to a few ulps.
  EXPECT_LT(max_layout_deviation(mesh, patches), 1e-14);
  // The element edges really are unit lattice vectors at 60 degrees.
  for (const auto& [p, faces, corners] : patches.patch) {
    const Eigen::Vector3d E1 = mesh.vertices.row(p[7]) - mesh.vertices.row(p[6]);
    const Eigen::Vector3d E2 = mesh.vertices.row(p[3]) - mesh.vertices.row(p[6]);
    EXPECT_NEAR(E1.norm(), 1.0, 1e-14);
    EXPECT_NEAR(E2.norm(), 1.0, 1e-14);
    EXPECT_NEAR(E1.dot(E2), 0.5, 1e-14);
  }
  // Elements in the layout's own orientation (E1 = e1): the node offsets from node 4 are the
  // listed lattice points themselves.
  std::size_t num_aligned = 0;
  for (const auto& [p, faces, corners] : patches.patch) {
    const Eigen::Vector3d x4 = mesh.vertices.row(p[3]).transpose();
    const Eigen::Vector3d E1 = mesh.vertices.row(p[7]) - mesh.vertices.row(p[6]);
    if ((E1 - e1).norm() > 1e-12) continue;
    ++num_aligned;
    for (int n = 1; n <= 12; ++n) {
      const Eigen::Vector3d expected = x4 + kLayout[n - 1][0] * e1 + kLayout[n - 1][1] * e2;
      EXPECT_LT((mesh.vertices.row(p[n - 1]).transpose() - expected).norm(), 1e-14) << "node " << n;
    }
  }
  EXPECT_EQ(num_aligned, 6u * 5);
}

TEST(ElementPatches, StripIsAffineImageOfLattice) {
  const StripMeshOptions options{.length = 2.0, .width = 0.3, .cells_x = 10, .cells_y = 3};
  const TriangleMesh mesh = make_strip_mesh(options);
  const MeshTopology topo(mesh);
  const ElementPatches patches = build_element_patches(topo);
  EXPECT_EQ(patches.patch.size(), 2u * 10 * 3);
  expect_elements_are_regular_interior_faces(topo, patches);
  // Grid coordinates i L / n, j W / m - W/2 carry rounding of ~1 ulp of L = 2.
  EXPECT_LT(max_layout_deviation(mesh, patches), 1e-13);
}

TEST(ElementPatches, DiscTopologyOnTrueLattice) {
  // The disc's ring k, side s, entry j moved to the lattice point k c_s + j (c_{s+1} - c_s),
  // c_s the unit hexagon corners: the disc connectivity is the triangular lattice.
  const int n = 5;
  TriangleMesh mesh = make_disc_mesh({.rings = n});
  auto corner = [](int s) {
    const double angle = std::numbers::pi / 3.0 * s;
    return Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.0);
  };
  mesh.vertices.row(0).setZero();
  for (int k = 1; k <= n + 1; ++k) {
    for (int s = 0; s < 6; ++s) {
      for (int j = 0; j < k; ++j) {
        mesh.vertices.row(1 + 3 * k * (k - 1) + s * k + j) =
            (k * corner(s) + j * (corner(s + 1) - corner(s))).transpose();
      }
    }
  }
  const MeshTopology topo(mesh);
  const ElementPatches patches = build_element_patches(topo);
  EXPECT_EQ(patches.patch.size(), 6u * n * n);
  expect_elements_are_regular_interior_faces(topo, patches);
  // Lattice points of norm <= 6 built from cos/sin of multiples of 60 degrees.
  EXPECT_LT(max_layout_deviation(mesh, patches), 1e-14);
}

// n x n periodic grid (a torus), every square split along the same diagonal: all vertices
// interior with valence 6.
Eigen::MatrixX3i torus_faces(int n) {
  Eigen::MatrixX3i faces(2 * n * n, 3);
  auto v = [n](int i, int j) { return ((i + n) % n) + n * ((j + n) % n); };
  int f = 0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      faces.row(f++) << v(i, j), v(i + 1, j), v(i + 1, j + 1);
      faces.row(f++) << v(i, j), v(i + 1, j + 1), v(i, j + 1);
    }
  }
  return faces;
}

TEST(ElementPatches, ClosedTorus) {
  const MeshTopology large(64, torus_faces(8));
  const ElementPatches patches = build_element_patches(large);
  EXPECT_EQ(patches.patch.size(), 128u);
  for (const auto& patch : patches.patch) {
    auto sorted = patch.control;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end());
  }
  EXPECT_EQ(patches.num_irregular(), 0);
  // A 3 x 3 torus has only 9 vertices: the one-rings of a face's corners overlap, so no face is
  // a 12-node box-spline patch although every vertex has valence 6; each gets the faces around
  // its corners, which the subdivision evaluation separates after one step.
  const MeshTopology tiny(9, torus_faces(3));
  const ElementPatches tiny_patches = build_element_patches(tiny);
  ASSERT_EQ(tiny_patches.patch.size(), 18u);
  EXPECT_EQ(tiny_patches.num_irregular(), 18);
  for (const LoopPatch& patch : tiny_patches.patch) {
    EXPECT_EQ(patch.size(), 9);
    const PatchBasis b = evaluate_patch_basis(patch, 0.2, 0.3);
    EXPECT_NEAR(b.value.sum(), 1.0, 1e-14);
  }
}

TEST(ElementPatches, NoElementsOnSingleHexagon) {
  Eigen::MatrixX3i faces(6, 3);
  for (int i = 0; i < 6; ++i) faces.row(i) << 0, i + 1, (i + 1) % 6 + 1;
  const ElementPatches patches = build_element_patches(MeshTopology(7, faces));
  EXPECT_TRUE(patches.patch.empty());
  EXPECT_TRUE(patches.face.empty());
}

}  // namespace
}  // namespace growshell
