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

/// Options of make_disc_mesh. Lengths in metres.
struct DiscMeshOptions {
  /// Disc radius R (> 0): radius of the outermost real ring.
  double radius = 1.0;
  /// Number N of real rings around the centre vertex (>= 2).
  int rings = 20;
  /// Grading exponent p (>= 1); p = 1 is uniform, p > 1 refines towards the centre.
  double grading_exponent = 1.0;
  /// Smallest radial spacing when p > 1 (>= 0); ignored when p = 1.
  double min_spacing = 0.0;
  /// Centre of the disc in the xy-plane.
  Eigen::Vector2d center = {0.0, 0.0};
};

/// Disc of concentric hexagonal rings of the triangular lattice: vertex 0 is the centre, ring
/// k = 1..N+1 has 6k vertices, numbered consecutively (ring k starts at 1 + 3k(k-1)); its
/// vertex m sits at angle 2 pi m / (6k) and radius r_k. Ring N+1 is the ghost ring.
///
/// With s = k/N: r_k = R (a s + (1-a) s^p), where a = 1 for p = 1 and
/// a = clamp(min_spacing N / R, 0, 1) for p > 1, so the spacing grows like r^(1-1/p) away
/// from the centre and the first spacing is about min_spacing. Ghost ring radius
/// r_{N+1} = R + (r_N - r_{N-1}). Counts: 1 + 3(N+1)(N+2) vertices, 6(N+1)^2 faces, of which
/// the 6N^2 faces inside ring N are the elements. Throws MeshError for invalid options.
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

/// Returns the index K of the innermost real ring that make_annulus_mesh uses: the K >= 2
/// whose tangential spacing 2 pi R_i / (6K) is closest to the radial spacing
/// dr = (R - R_i) / radial_layers. Throws MeshError for invalid options.
int annulus_first_ring(const AnnulusMeshOptions& options);

/// Annulus cut from the same hexagonal ring lattice as make_disc_mesh: rings K..N with
/// K = annulus_first_ring(options) and N = K + radial_layers, ring K + i at radius R_i + i dr,
/// plus the ghost rings K-1 (radius R_i - dr, or R_i / 2 if that is <= 0) and N+1 (radius
/// R + dr). Vertices are numbered ring by ring from ring K-1 outwards; ring k has 6k vertices,
/// vertex m at angle 2 pi m / (6k). Throws MeshError for invalid options.
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
