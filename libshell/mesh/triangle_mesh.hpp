#pragma once
/// \file
/// Plain triangle mesh: vertex positions and counter-clockwise triangles.
///
/// In growshell a TriangleMesh is the *control mesh* of a Loop subdivision surface.
/// Convention (see docs/subdivision.md): the outermost layer of the control mesh is a
/// ghost layer. Elements are exactly the triangles whose three vertices are interior
/// vertices (any valence 3..12); every other triangle only supplies control points.

#include <Eigen/Core>

namespace growshell {

/// Vertex positions (one row per vertex, metres) and triangles (one row per triangle,
/// vertex indices, counter-clockwise seen from +z for planar meshes).
struct TriangleMesh {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
};

}  // namespace growshell
