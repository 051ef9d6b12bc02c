#pragma once
/// \file
/// The ghost layer of a planar sheet triangulation: one layer of extra control vertices and
/// faces around every boundary loop, so that the sheet's faces become exactly the elements of
/// the Loop control mesh (see triangle_mesh.hpp and docs/subdivision.md).

#include "libshell/mesh/triangle_mesh.hpp"

namespace growshell {

/// Largest gap angle (radians) at a boundary vertex that add_ghost_layer closes with a single
/// face; a larger gap gets an extra ghost vertex and two faces. 2 pi / 3: the closing face's
/// angle at the sheet vertex is then at most 120 degrees, and each of the two faces of a split
/// gap gets more than 60 degrees.
inline constexpr double kGhostGapSplitAngle = 2.0943951023931954923;  // 2 pi / 3

/// Gap angle (radians) at a boundary vertex up to which add_ghost_layer merges the vertex's two
/// ghosts into one (at their mean): 1e-6, i.e. where they coincide (gap 0) or where the two
/// ghost faces overlap (gap < 0, at a reflex boundary vertex).
inline constexpr double kGhostGapMergeAngle = 1e-6;

/// The control mesh whose elements are exactly the faces of `sheet`.
///
/// `sheet` must be a planar (every |z| <= 1e-9 times its xy extent), counter-clockwise (every
/// face of positive signed area seen from +z), edge- and vertex-manifold triangulation in which
/// every vertex belongs to a face; it may have any number of boundary loops (a disc has one,
/// an annulus two). Construction:
///  1. Ghost faces: for every boundary edge a -> b (face (a, b, c) on its left) the ghost
///     vertex g = a + b - c, the point reflection of c through the edge midpoint, and the ghost
///     face (b, a, g), congruent to (a, b, c) by a half turn, so never inverted. A point
///     reflection keeps affine maps exact: a sheet mapped by an affine map gets the same
///     affinely mapped ghost vertices.
///  2. Merging: at a boundary vertex whose gap angle phi (below) is <= kGhostGapMergeAngle
///     or whose two ghosts coincide (to 1e-12 times the sheet's extent) the two ghosts are one
///     ghost vertex, at their mean, and that vertex's fan is closed without a further face.
///     phi = 0 happens at a vertex both of whose boundary faces have their right angle at the
///     far end (the ghosts coincide and do not move); phi < 0 at a reflex vertex whose ghost
///     faces would overlap (e.g. on a coarsely meshed hole), where the merged ghost is no
///     longer a point reflection. Merging is transitive along the boundary.
///  3. Closing faces: at any other boundary vertex v with incoming boundary edge u -> v (ghost g1) and
///     outgoing edge v -> w (ghost g2) the gap between g1 and g2 around v has the angle
///     phi = 2 pi - (sheet angles at v) - (angles of the two ghost faces at v). If
///     phi <= kGhostGapSplitAngle it is closed by the face (v, g1, g2); otherwise by an extra
///     ghost vertex e = 2 v - m, m the mean of all sheet neighbours of v (for a convex corner
///     e lies in the gap), and the faces (v, g1, e), (v, e, g2).
/// Valences: a boundary vertex of sheet valence k gets valence k + 2 (one closing face),
/// k + 3 (split gap) or k + 1 (merged ghosts), so a straight boundary of a regular lattice (k = 4) keeps valence 6 and
/// a sheet corner with one face (k = 2) gets 5; interior sheet vertices keep their valence.
/// Ghost vertices are boundary vertices of the result: edge ghosts of valence 4 (5 for a
/// merged pair), extra ghosts of valence 3.
///
/// Numbering: sheet vertices keep their indices 0..n-1 and sheet faces their rows; then the
/// edge ghosts with their ghost faces (in the order of the sheet faces and, within a face, of
/// its edges (a, b), (b, c), (c, a); a merged pair at its first edge), then the extra ghosts (in sheet vertex order), then the
/// closing faces (in sheet vertex order). The construction uses only the geometry and the
/// connectivity, never the numbering, so it commutes with every isometry of the sheet that
/// maps vertices to vertices and faces to faces (up to rounding in the gap-angle test at
/// exactly kGhostGapSplitAngle).
///
/// Throws MeshError for a sheet that is empty, not planar, not manifold (MeshTopology's
/// errors), has a face that is not counter-clockwise (naming it), has no boundary, or where
/// the boundary is too reflex for the construction: a ghost face inverted after merging, a
/// split gap whose extra ghost lies outside it, or a boundary loop merged into a single ghost
/// (a hole of too few edges), naming the vertex.
TriangleMesh add_ghost_layer(const TriangleMesh& sheet);

}  // namespace growshell
