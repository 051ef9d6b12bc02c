#pragma once
/// \file
/// The Loop patch of every element of a control mesh.

#include <vector>

#include "libshell/mesh/mesh_topology.hpp"
#include "libshell/subdivision/loop_patch.hpp"

namespace growshell {

/// The elements of a control mesh and their patches.
///
/// An element is a face whose three vertices are interior vertices of the control mesh (the
/// outermost layer is the ghost layer). A face with three valence-6 corners whose one-rings do
/// not overlap gets the regular 12-node patch, ordered as in Cirak, Ortiz & Schröder (2000), with the element (a, b, c) =
/// nodes (4, 7, 8) in their 1-based numbering:
///
///         1   2
///       3   4   5
///     6   7   8   9
///       10  11  12
///
/// On the lattice with e1 = (1, 0), e2 = (1/2, sqrt(3)/2) and node 4 at the origin the nodes sit
/// at 1: e2-e1, 2: e2, 3: -e1, 4: 0, 5: e1, 6: -e1-e2, 7: -e2, 8: e1-e2, 9: 2e1-e2, 10: -2e2,
/// 11: e1-2e2, 12: 2e1-2e2. Any other element gets the faces around its corners (loop_patch.hpp).
struct ElementPatches {
  /// Per element, its patch; patch[e].control[n - 1] is node n of a regular element.
  std::vector<LoopPatch> patch;
  /// Per element, the index of its face in the control mesh.
  std::vector<int> face;

  /// Number of elements with an extraordinary corner.
  int num_irregular() const;
};

/// Finds all elements of `topology` in increasing face order and builds their patches. Throws
/// MeshError (naming the face and vertex) if the one-ring of a corner misses the next corner.
ElementPatches build_element_patches(const MeshTopology& topology);

/// The patch of face `face` given by the faces around its corners (the representation of an
/// irregular element), whatever the corners' valences: `corners` = (0, 1, 2) are the face's
/// vertices. Throws MeshError if a corner is a boundary vertex of the control mesh.
LoopPatch build_surrounding_patch(const MeshTopology& topology, int face);

}  // namespace growshell
