#pragma once
/// \file
/// The elements around each element: those that share a corner with it. A point's closest
/// point on the limit surface near an element lies in this set unless it is more than an
/// element away, so it is the candidate set of a closest-point search started on the element.

#include <vector>

#include "libshell/mesh/mesh_topology.hpp"
#include "libshell/subdivision/element_patches.hpp"

namespace growshell {

/// For each element e of `patches` (built from `topology`), the elements that share at least one
/// corner vertex with e, e itself included, in increasing order. Throws std::invalid_argument if
/// a patch's face is not a face of `topology`.
std::vector<std::vector<int>> element_neighbourhoods(const MeshTopology& topology,
                                                     const ElementPatches& patches);

}  // namespace growshell
