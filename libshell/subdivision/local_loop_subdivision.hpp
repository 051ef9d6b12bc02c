#pragma once
/// \file
/// One Loop subdivision step of a small local triangle mesh (the faces around one element), as
/// a linear map from the coarse to the refined control points.
///
/// The exact evaluation of an element with an extraordinary corner (loop_patch.hpp) subdivides
/// the faces around the element until the point of interest lies in a sub-triangle whose three
/// corners have valence 6; that sub-triangle is then a regular box-spline patch. Only the new
/// vertices whose Loop rule sees all the faces it needs can be computed from a local mesh; the
/// others are flagged, and the evaluation never uses them.

#include <Eigen/Core>
#include <array>
#include <vector>

namespace growshell {

/// A triangle mesh in local vertex numbering 0..num_vertices-1: counter-clockwise faces,
/// manifold, each vertex in at least one face. Vertices need not have closed fans.
struct LocalLoopMesh {
  int num_vertices = 0;
  std::vector<std::array<int, 3>> faces;
};

/// The faces around local vertex `v`, counter-clockwise, and its neighbours in the same order.
struct LocalFan {
  /// Neighbours in counter-clockwise order; for a closed fan, neighbours[k] and
  /// neighbours[k + 1 mod n] span a face.
  std::vector<int> neighbours;
  /// True if the faces around v close up (v is interior to the local mesh).
  bool closed = false;
};

/// The fan of `v` in `mesh`. For an open fan the neighbours start at the one whose edge has no
/// face on its clockwise side. Throws std::invalid_argument if v is out of range or its faces
/// do not form one fan.
LocalFan local_fan(const LocalLoopMesh& mesh, int v);

/// One Loop step: `refined` keeps vertex i of the coarse mesh as vertex i (its vertex point) and
/// adds one edge point per coarse edge; each coarse face (a, b, c) becomes (a, e_ab, e_ca),
/// (e_ab, b, e_bc), (e_ca, e_bc, c), (e_bc, e_ca, e_ab), in that order (face 4 f + k). `rule`
/// (refined x coarse) gives each refined point from the coarse points; `computable[i]` is false
/// for a vertex point whose fan is open (or is no single fan) and an edge point of an edge with one face, whose rows
/// of `rule` are zero.
struct LocalSubdivisionStep {
  LocalLoopMesh refined;
  Eigen::MatrixXd rule;
  std::vector<char> computable;
  /// edge_point[f][k]: refined index of the edge point of coarse face f's edge k (k = 0: a-b,
  /// 1: b-c, 2: c-a).
  std::vector<std::array<int, 3>> edge_point;
};

/// Subdivides `mesh` once with Loop's rules (loop_rules.hpp).
LocalSubdivisionStep subdivide_local_mesh(const LocalLoopMesh& mesh);

}  // namespace growshell
