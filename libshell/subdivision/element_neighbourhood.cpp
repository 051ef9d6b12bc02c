#include "libshell/subdivision/element_neighbourhood.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace growshell {

std::vector<std::vector<int>> element_neighbourhoods(const MeshTopology& topology,
                                                     const ElementPatches& patches) {
  const int elements = static_cast<int>(patches.face.size());
  std::vector<std::vector<int>> at_vertex(static_cast<std::size_t>(topology.num_vertices()));
  for (int e = 0; e < elements; ++e) {
    const int face = patches.face[static_cast<std::size_t>(e)];
    if (face < 0 || face >= topology.num_faces())
      throw std::invalid_argument("element_neighbourhoods: element " + std::to_string(e) +
                                  " names face " + std::to_string(face) + ", outside the " +
                                  std::to_string(topology.num_faces()) + " faces of the mesh");
    for (int v : topology.face(face)) at_vertex[static_cast<std::size_t>(v)].push_back(e);
  }
  std::vector<std::vector<int>> around(static_cast<std::size_t>(elements));
  for (int e = 0; e < elements; ++e) {
    std::vector<int>& set = around[static_cast<std::size_t>(e)];
    for (int v : topology.face(patches.face[static_cast<std::size_t>(e)]))
      for (int other : at_vertex[static_cast<std::size_t>(v)]) set.push_back(other);
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
  }
  return around;
}

}  // namespace growshell
