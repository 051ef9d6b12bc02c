#pragma once
/// \file
/// Checks that a triangle mesh is a usable growshell control mesh.

#include "libshell/mesh/triangle_mesh.hpp"

namespace growshell {

/// Valences of interior vertices that the Loop element accepts: the range its tests cover
/// (Loop's rules exist for any valence >= 3, but the limit surface degrades as the valence
/// grows and no mesh generator needs more).
inline constexpr int kMinInteriorValence = 3;
inline constexpr int kMaxInteriorValence = 12;

/// Throws MeshError (naming the vertex, face or edge) unless `mesh` is a valid control mesh:
/// - its connectivity is valid (see MeshTopology: indices in range, no repeated vertex in a
///   face, manifold edges and vertices, consistent orientation, no unused vertex);
/// - all coordinates are finite;
/// - no triangle is degenerate: area > 1e-12 * (mean edge length)^2;
/// - no triangle is inverted: for a mesh lying in a plane z = const, every signed area in the
///   xy-plane has the sign of the majority; otherwise no two edge-neighbouring faces have
///   normals more than 90 degrees apart;
/// - every interior vertex has a valence in [kMinInteriorValence, kMaxInteriorValence];
/// - at least one element exists (a face whose three vertices are interior).
void validate_control_mesh(const TriangleMesh& mesh);

}  // namespace growshell
