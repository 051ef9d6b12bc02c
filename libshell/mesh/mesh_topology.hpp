#pragma once
/// \file
/// Connectivity of an oriented, manifold triangle mesh: boundary flags, valences and
/// counter-clockwise one-rings.

#include <array>
#include <vector>

#include <Eigen/Core>

#include "libshell/mesh/triangle_mesh.hpp"

namespace growshell {

/// Connectivity of a consistently oriented, edge- and vertex-manifold triangle mesh in which
/// every vertex belongs to at least one face.
///
/// "Counter-clockwise" is the rotation induced by the face orientation: for a face (a, b, c),
/// going counter-clockwise around a visits b, then c.
class MeshTopology {
 public:
  /// Builds the connectivity of `faces` (one row per triangle, vertex indices in
  /// [0, num_vertices)). Throws MeshError naming the item for: an index out of range, a
  /// repeated vertex in a face, an edge shared by more than two faces, two faces traversing
  /// an edge in the same direction, a vertex whose faces do not form a single fan, and a
  /// vertex used by no face.
  MeshTopology(int num_vertices, const Eigen::Ref<const Eigen::MatrixX3i>& faces);

  /// Same as MeshTopology(mesh.vertices.rows(), mesh.faces).
  explicit MeshTopology(const TriangleMesh& mesh);

  /// Number of vertices.
  int num_vertices() const { return static_cast<int>(rings_.size()); }

  /// Number of faces.
  int num_faces() const { return static_cast<int>(faces_.size()); }

  /// The three vertex indices of face f, in the mesh's (counter-clockwise) order.
  /// Throws MeshError if f is not in [0, num_faces()).
  const std::array<int, 3>& face(int f) const;

  /// True if vertex v lies on the mesh boundary (its fan of faces is open).
  bool is_boundary_vertex(int v) const;

  /// Number of edges incident to vertex v (= one_ring(v).size()).
  int valence(int v) const;

  /// Neighbours of v in counter-clockwise order. For an interior vertex the ring is cyclic and
  /// starts at an arbitrary (deterministic) neighbour; for a boundary vertex it starts at the
  /// boundary neighbour whose edge has no face on its clockwise side and ends at the other
  /// boundary neighbour, so that consecutive entries span the faces around v.
  const std::vector<int>& one_ring(int v) const;

  /// The vertex c of the face (a, b, c) that contains the directed edge a -> b, or -1 if no
  /// face contains a -> b (b is not a neighbour of a, or a -> b is a boundary edge traversed
  /// only as b -> a). Throws MeshError if a or b is out of range.
  int opposite_vertex(int a, int b) const;

  /// Index of the face that contains the directed edge a -> b, or -1 if none does.
  /// Throws MeshError if a or b is out of range.
  int face_with_edge(int a, int b) const;

 private:
  void check_vertex(int v, const char* argument) const;
  // Position of b in one_ring(a) if the directed edge a -> b has a face on its left, else -1.
  int ring_slot_with_face(int a, int b) const;

  std::vector<std::array<int, 3>> faces_;
  std::vector<std::vector<int>> rings_;
  // ring_faces_[v][i] is the face containing v -> rings_[v][i] (the face between ring entries
  // i and i+1); the last slot of a boundary vertex has no face and holds -1.
  std::vector<std::vector<int>> ring_faces_;
  std::vector<char> boundary_;
};

}  // namespace growshell
