#pragma once
/// \file
/// Graded disc and annulus meshes of concentric rings with the symmetry of the square: a centre
/// vertex (disc) or an inner rim ring (annulus), rings whose radial spacing follows the size
/// field s(r) = clamp(c r, s_min, s_max) (radial_size.hpp), and per-ring vertex counts that stay equal (log-polar region) or double
/// (uniform core). Interior vertices may be irregular (valences 5..7 and the centre's).

#include <limits>
#include <vector>

#include <Eigen/Core>

#include "libshell/mesh/triangle_mesh.hpp"

namespace growshell {

/// Options of make_ring_disc_mesh. Lengths in metres.
struct RingDiscMeshOptions {
  /// Disc radius R (> 0); the last ring lies exactly on the circle of radius R.
  double radius = 1.0;
  /// Inner radius R_i in [0, R): 0 makes a disc; R_i > 0 an annulus whose ring 0 lies exactly
  /// on the circle of radius R_i.
  double inner_radius = 0.0;
  /// c (> 0): element size ~ c r away from the core (log-polar region).
  double size_slope = 0.25;
  /// s_min (> 0): element size in the core r < s_min / c (e.g. h / 2).
  double size_floor = 0.01;
  /// s_max (>= size_floor, may be +infinity): cap on the element size.
  double size_max = std::numeric_limits<double>::infinity();
  /// Number of vertices of ring 1, i.e. the valence of the centre vertex: 4, 8 or 12 (a
  /// multiple of 4 for the quarter turn, within the element's valences 3..12). With the
  /// default 8 every ring has 8 * 2^k vertices. An annulus's rings have center_valence 2^k
  /// vertices too.
  int center_valence = 8;
};

/// The rings of make_ring_disc_mesh; index j = 0..M, ring 0 being the centre vertex of a disc
/// or the inner rim of an annulus.
struct RingDiscRings {
  std::vector<double> radii;      ///< r_j (m): r_0 = R_i (0 for a disc), r_M = R exactly
  std::vector<int> counts;        ///< N_j vertices on ring j (N_0 = 1 for a disc)
  std::vector<int> first_vertex;  ///< index of vertex 0 of ring j (vertices are per ring)
  std::vector<char> half_offset;  ///< vertex i of ring j at angle (i + 1/2) 2 pi / N_j if set,
                                  ///< else at i 2 pi / N_j
};

/// The ring layout of make_ring_disc_mesh:
///  * radii: with u(r) = integral_0^r dr'/s(r') (radial_size_coordinate), M = max(1,
///    round(u(R) - u(R_i))) rings at u(r_j) = u(R_i) + j (u(R) - u(R_i)) / M, so the radial spacing
///    is s(r) times u(R)/M in [1 - 1/(2M), 1 + 1/(2M)]: uniform (s_min) in the core r < s_min/c,
///    geometric (ratio ~ e^c) in the log-polar region, uniform (s_max) beyond s_max/c;
///  * counts: N_1 = center_valence for a disc; an annulus's N_0 = center_valence 2^k with the
///    smallest k for which sqrt(2) N_0 >= 2 pi R_i / s(R_i); then N_j = 2 N_{j-1} if the ideal
///    count 2 pi r_j / s(r_j) exceeds sqrt(2) N_{j-1}, else N_{j-1}, so the tangential spacing 2 pi
///    r_j / N_j stays within [s/sqrt 2, sqrt 2 s] wherever one doubling per ring can keep up (and
///    the ring count is constant, ~2 pi / c rounded to center_valence 2^k, in the log-polar
///    region);
///  * offsets: ring 1 of a disc, ring 0 of an annulus unshifted; a ring with the count of the
///    previous ring is shifted by half a spacing against it; a doubled ring is unshifted (every
///    second vertex radially outside an inner vertex).
/// So every ring has a vertex or an edge midpoint on each half axis. Throws MeshError for
/// invalid options, or when the mesh would exceed 1e6 rings or 1e7 vertices.
RingDiscRings ring_disc_rings(const RingDiscMeshOptions& options);

/// The sheet of make_ring_disc_mesh (no ghost layer): for a disc vertex 0 at the centre, then
/// ring j = 1..M (an annulus: j = 0..M) with vertex i at r_j (cos t, sin t), t = (i + offset_j)
/// 2 pi / N_j. Faces: for a disc the fan (0, ring-1 vertex i, i+1); between two rings of equal
/// count the unique zig-zag strip; at a doubling, per inner edge (a_i, a_{i+1}) with outer vertices
/// b (aligned with a_i), b' (the midpoint direction), b'' (aligned with a_{i+1}) the faces (a_i, b,
/// b'), (a_i, b', a_{i+1}), (a_{i+1}, b', b''). The vertex set and the triangulation are mapped
/// onto themselves exactly (bit for bit: the angles are evaluated in the first octant and
/// reflected) by the mirrors x -> -x and y -> -y and the quarter turn about the centre, and by
/// the rotation through 2 pi / center_valence. Interior valences: 6 between rings of equal
/// count; around a doubling 7 on the inner ring and 5 (aligned) / 6 (midpoint) on the outer
/// ring when rings of equal count follow on both sides, 6 / 7 for consecutive doublings; the
/// centre has valence center_valence. Throws as ring_disc_rings.
TriangleMesh make_ring_disc_sheet(const RingDiscMeshOptions& options);

/// make_ring_disc_sheet with the ghost layer added (add_ghost_layer): the elements are exactly
/// the sheet's faces, which cover the disc of radius R; the sheet vertices keep their indices.
/// A rim vertex of sheet valence k gets valence k + 2 (4 -> 6 after rings of equal count).
TriangleMesh make_ring_disc_mesh(const RingDiscMeshOptions& options);

}  // namespace growshell
