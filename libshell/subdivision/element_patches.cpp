#include "libshell/subdivision/element_patches.hpp"

#include <algorithm>
#include <string>

#include "libshell/mesh/mesh_error.hpp"

namespace growshell {

namespace {

bool is_regular_interior(const MeshTopology& topo, int v) {
  return !topo.is_boundary_vertex(v) && topo.valence(v) == 6;
}

// one_ring(v) rotated to start at `first`; the element's face guarantees `first` is in it.
std::array<int, 6> ring_from(const MeshTopology& topo, int v, int first, int face) {
  const auto& ring = topo.one_ring(v);
  const auto it = std::find(ring.begin(), ring.end(), first);
  if (it == ring.end()) {
    throw MeshError("face " + std::to_string(face) + ": vertex " + std::to_string(first) +
                    " is missing from the one-ring of vertex " + std::to_string(v));
  }
  const std::size_t start = static_cast<std::size_t>(it - ring.begin());
  std::array<int, 6> rotated{};
  for (std::size_t k = 0; k < 6; ++k) rotated[k] = ring[(start + k) % 6];
  return rotated;
}

void require_same(int from_first, int from_second, int face, const char* node) {
  if (from_first != from_second) {
    throw MeshError("face " + std::to_string(face) +
                    ": the one-rings of its vertices disagree on " + node + " (vertex " +
                    std::to_string(from_first) + " vs vertex " + std::to_string(from_second) + ")");
  }
}

}  // namespace

ElementPatches build_element_patches(const MeshTopology& topology) {
  ElementPatches patches;
  for (int f = 0; f < topology.num_faces(); ++f) {
    const auto& t = topology.face(f);
    if (!is_regular_interior(topology, t[0]) || !is_regular_interior(topology, t[1]) ||
        !is_regular_interior(topology, t[2])) {
      continue;
    }
    const int a = t[0];
    const int b = t[1];
    const int c = t[2];
    const auto ra = ring_from(topology, a, b, f);  // b, c, n5, n2, n1, n3
    const auto rb = ring_from(topology, b, c, f);  // c, a, n3, n6, n10, n11
    const auto rc = ring_from(topology, c, a, f);  // a, b, n11, n12, n9, n5
    require_same(ra[1], c, f, "node 8");
    require_same(rb[1], a, f, "node 4");
    require_same(rc[1], b, f, "node 7");
    require_same(ra[5], rb[2], f, "node 3");
    require_same(rb[5], rc[2], f, "node 11");
    require_same(rc[5], ra[2], f, "node 5");

    const std::array<int, 12> nodes = {ra[4], ra[3], ra[5], a,     ra[2], rb[3],
                                       b,     c,     rc[4], rb[4], rb[5], rc[3]};
    std::array<int, 12> sorted = nodes;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
      throw MeshError("face " + std::to_string(f) +
                      ": its 12 patch control points are not distinct (the mesh is too small "
                      "around this element)");
    }
    patches.control.push_back(nodes);
    patches.face.push_back(f);
  }
  return patches;
}

}  // namespace growshell
