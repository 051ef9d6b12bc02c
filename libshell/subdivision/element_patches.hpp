#pragma once
/// \file
/// The 12 control points of each regular Loop element.

#include <array>
#include <vector>

#include "libshell/mesh/mesh_topology.hpp"

namespace growshell {

/// Control points of every element of a control mesh.
///
/// An element is a face whose three vertices are interior vertices of valence 6. Its limit
/// surface is a regular box-spline patch of 12 control points, ordered as in Cirak, Ortiz &
/// Schröder (2000), with the element (a, b, c) = nodes (4, 7, 8):
///
///         1   2
///       3   4   5
///     6   7   8   9
///       10  11  12
///
/// `control[e][n - 1]` is the vertex index of node n of element e. On the lattice with
/// e1 = (1, 0), e2 = (1/2, sqrt(3)/2) and node 4 at the origin the nodes sit at
/// 1: e2-e1, 2: e2, 3: -e1, 4: 0, 5: e1, 6: -e1-e2, 7: -e2, 8: e1-e2, 9: 2e1-e2,
/// 10: -2e2, 11: e1-2e2, 12: 2e1-2e2.
struct ElementPatches {
  /// Per element, the vertex indices of nodes 1..12 (array index = node - 1).
  std::vector<std::array<int, 12>> control;
  /// Per element, the index of its face in the control mesh.
  std::vector<int> face;
};

/// Finds all elements of `topology` in increasing face order and gathers their 12 control
/// points. Throws MeshError (naming the face) if the one-rings of an element's vertices
/// disagree about a shared node or the 12 nodes are not distinct (e.g. a tiny closed mesh).
ElementPatches build_element_patches(const MeshTopology& topology);

}  // namespace growshell
