#pragma once
/// \file
/// Generators of planar control meshes (disc, annulus, strip) with their ghost layer.
///
/// All meshes lie in the plane z = 0, are counter-clockwise seen from +z, and every interior
/// vertex has valence 6. The outermost layer of vertices is the ghost layer (see
/// triangle_mesh.hpp), so the elements cover exactly the nominal region.

#include <vector>

#include <Eigen/Core>

#include "libshell/mesh/triangle_mesh.hpp"

namespace growshell {

/// Where make_disc_mesh places the vertices of the hexagonal ring lattice.
enum class DiscLayout {
  /// The lattice hexagon mapped conformally onto the disc (hexagon_to_disc): a smooth map of
  /// the lattice everywhere except at the six rim corners. The default.
  Conformal,
  /// Ring k on a circle of radius r_k at equal angles: only piecewise smooth, with kinks
  /// along the six spokes through the hexagon corners, which give O(1) curvature errors of
  /// Loop surfaces along the spokes. Kept only to demonstrate that difference.
  EqualAngleRings,
};

/// Options of make_disc_mesh. Lengths in metres.
struct DiscMeshOptions {
  /// Disc radius R (> 0): the real ring N lies on the circle of radius R.
  double radius = 1.0;
  /// Number N of real rings around the centre vertex (>= 2).
  int rings = 20;
  /// Grading exponent p (>= 1); p = 1 is uniform, p > 1 refines towards the centre. With the
  /// conformal layout only odd integers (p = 1, 3, ...) give a smooth map; p = 3 is the
  /// smooth graded choice (see make_disc_mesh).
  double grading_exponent = 1.0;
  /// Smallest spacing when p > 1 (>= 0); ignored when p = 1.
  double min_spacing = 0.0;
  /// Centre of the disc in the xy-plane.
  Eigen::Vector2d center = {0.0, 0.0};
  /// Vertex placement; EqualAngleRings only for comparisons.
  DiscLayout layout = DiscLayout::Conformal;
};

/// Disc meshed by the triangular lattice inside a regular hexagon. Vertex 0 is the centre;
/// ring k = 1..N+1 (the hexagon of lattice points at hexagonal distance k) has 6k vertices,
/// numbered consecutively from 1 + 3k(k-1) counter-clockwise; its vertex m = s k + j
/// (side s = 0..5, j = 0..k-1) is the lattice point xi = k c_s + j (c_{s+1} - c_s) with
/// c_s = exp(i s pi/3). Ring N+1 is the ghost ring. Counts: 1 + 3(N+1)(N+2) vertices,
/// 6(N+1)^2 faces, of which the 6N^2 faces inside ring N are the elements. The mesh is
/// invariant under rotation by 60 degrees about the centre (vertex m of ring k goes to
/// vertex m + k) and under reflection in the x-axis.
///
/// Conformal layout (default): w = hexagon_to_disc(xi / N) puts ring N exactly on the unit
/// circle; ghost vertices get the Schwarz-reflected (analytically continued) map, except the
/// six ghost corners and their twelve ghost neighbours, where that continuation folds over
/// (it would put both neighbours of a ghost corner on the same point). Those continue a
/// lattice line through ring N linearly instead: the ghost corner is 2 c_s - w(ring N-1
/// corner), the point reflection through the ring-N corner, and the ghost vertex next to it
/// on side s is 2 w(ring N, j = 1) - w(ring N-1, j = 1) (mirror-symmetric on the other side).
/// Then
///   X = center + R w sigma(|w|) / |w|,  sigma(rho) = a rho + (1 - a) rho^p,
/// with a = 1 for p = 1 and a = clamp(min_spacing N / R, 0, 1) for p > 1. Ring radii are not
/// constant per ring, but the real ring N lies exactly on |X - center| = R and every real
/// vertex inside it. Since hexagon_to_disc is conformal with derivative 1/C = 1.11 at the
/// centre (C = 6 Gamma(5/6) / (Gamma(1/6) Gamma(2/3)) = 0.899), the elements are
/// near-equilateral (p = 1: edge ratio <= 1.22, angles >= 48 degrees) with edges of
/// 1.11 R / N at the centre growing to 2^(1/3) R / (C N) = 1.40 R / N at the rim between the
/// corners. The exception are the elements at the six rim corners, where the map behaves
/// like (z - c_s)^(3/2): they shrink like N^(-3/2) and tend to right isosceles triangles
/// (edge ratio sqrt 2), and Loop surfaces over the few elements around each corner keep
/// O(1) curvature errors under refinement (see tests/subdivision). With grading the spacing
/// near the centre is about min_spacing / C. The map X(xi) is smooth (analytic in xi away
/// from the rim corners) only when sigma(rho)/rho = a + (1 - a) rho^(p-1) is a polynomial in
/// |w|^2, i.e. for odd integer p (p = 3 is the smooth graded choice); other p leave a weak
/// singularity at the centre vertex only.
///
/// EqualAngleRings layout: vertex m of ring k at angle 2 pi m / (6k) and radius
/// r_k = R sigma(k/N) (r_{N+1} = R + r_N - r_{N-1}); piecewise smooth only.
///
/// Throws MeshError for invalid options.
TriangleMesh make_disc_mesh(const DiscMeshOptions& options);

/// Options of make_annulus_mesh. Lengths in metres.
struct AnnulusMeshOptions {
  /// Inner radius R_i, in (0, outer_radius).
  double inner_radius = 0.25;
  /// Outer radius R (> inner_radius).
  double outer_radius = 1.0;
  /// Number of element layers between the inner and outer real rings (>= 1).
  int radial_layers = 16;
  /// Centre of the annulus in the xy-plane.
  Eigen::Vector2d center = {0.0, 0.0};
};

/// Number M of vertices per ring of make_annulus_mesh: max(6, round(2 pi / dl)) with the
/// logarithmic radial step dl = ln(R / R_i) / radial_layers, so that the grid cells are
/// nearly square. Throws MeshError for invalid options (also when M would exceed 1e6).
int annulus_vertices_per_ring(const AnnulusMeshOptions& options);

/// Annulus as a periodic log-polar grid, the image of a uniform grid under the conformal map
/// (u, theta) -> R_i exp(u + i theta): smooth, with element size proportional to the radius.
/// Ring j = -1..radial_layers+1 lies at radius R_i exp(j dl) (ring 0 exactly at R_i, ring
/// radial_layers exactly at R); rings -1 and radial_layers+1 are the ghost rings. Vertex i of
/// ring j, at angle 2 pi i / M (M = annulus_vertices_per_ring), has index (j + 1) M + i. Each
/// grid cell (j..j+1, i..i+1) is split by its diagonal from (j, i) to (j+1, i+1) into the
/// counter-clockwise triangles ((j,i), (j+1,i), (j+1,i+1)) and ((j,i), (j+1,i+1), (j,i+1)),
/// so every interior vertex has valence 6. Counts: M (radial_layers + 3) vertices,
/// 2 M (radial_layers + 2) faces, of which 2 M radial_layers are elements. Throws MeshError
/// for invalid options.
TriangleMesh make_annulus_mesh(const AnnulusMeshOptions& options);

/// Options of make_strip_mesh. Lengths in metres.
struct StripMeshOptions {
  /// Length L along x (> 0).
  double length = 1.0;
  /// Width W along y (> 0).
  double width = 0.2;
  /// Number of grid cells along x (>= 1).
  int cells_x = 20;
  /// Number of grid cells along y (>= 1).
  int cells_y = 4;
};

/// Rectangular strip: grid vertex (i, j), i = -1..cells_x+1, j = -1..cells_y+1, at
/// (i L / cells_x, j W / cells_y - W/2, 0) with index strip_vertex_index(options, i, j). Each
/// grid square is split along its diagonal from (i, j) to (i+1, j+1). The rows and columns
/// i = -1, cells_x+1 and j = -1, cells_y+1 are the ghost layer, so the elements
/// (2 cells_x cells_y of them) cover exactly [0, L] x [-W/2, W/2]. Throws MeshError for
/// invalid options.
TriangleMesh make_strip_mesh(const StripMeshOptions& options);

/// Index of strip vertex (i, j): (i + 1) + (j + 1) (cells_x + 3). Throws MeshError if
/// i is outside [-1, cells_x + 1] or j outside [-1, cells_y + 1].
int strip_vertex_index(const StripMeshOptions& options, int i, int j);

/// Indices of the strip vertices in grid column i (x = i L / cells_x), ordered by j = -1 ..
/// cells_y + 1; e.g. i = 0 and i = cells_x are the real end rows, i = -1 and cells_x + 1
/// the ghost end rows. Throws MeshError if i is outside [-1, cells_x + 1].
std::vector<int> strip_vertices_with_x_index(const StripMeshOptions& options, int i);

}  // namespace growshell
