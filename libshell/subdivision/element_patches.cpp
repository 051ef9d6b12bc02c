#include "libshell/subdivision/element_patches.hpp"

#include <algorithm>
#include <optional>
#include <string>
#include <unordered_map>

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

// The 12-node patch of face f if its corners' one-rings form the regular configuration.
std::optional<LoopPatch> regular_patch(const MeshTopology& topology, int f) {
  const auto& t = topology.face(f);
  const auto ra = ring_from(topology, t[0], t[1], f);
  const auto rb = ring_from(topology, t[1], t[2], f);
  const auto rc = ring_from(topology, t[2], t[0], f);
  std::array<int, 12> nodes{};
  if (!regular_patch_nodes(ra, rb, rc, nodes)) return std::nullopt;
  LoopPatch patch;
  patch.control.assign(nodes.begin(), nodes.end());
  return patch;
}

}  // namespace

int ElementPatches::num_irregular() const {
  return static_cast<int>(std::count_if(patch.begin(), patch.end(),
                                        [](const LoopPatch& p) { return !p.is_regular(); }));
}

LoopPatch build_surrounding_patch(const MeshTopology& topology, int face) {
  const auto& t = topology.face(face);
  LoopPatch patch;
  std::unordered_map<int, int> local;
  const auto local_index = [&](int v) {
    auto [it, inserted] = local.try_emplace(v, static_cast<int>(patch.control.size()));
    if (inserted) patch.control.push_back(v);
    return it->second;
  };
  for (int v : t) local_index(v);
  patch.corners = {0, 1, 2};
  std::vector<int> faces;
  for (int v : t) {
    if (topology.is_boundary_vertex(v))
      throw MeshError("face " + std::to_string(face) + ": its vertex " + std::to_string(v) +
                      " is on the boundary of the control mesh, so the face is no element");
    for (int u : topology.one_ring(v)) faces.push_back(topology.face_with_edge(v, u));
  }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  for (int f : faces) {
    const auto& g = topology.face(f);
    patch.faces.push_back({local_index(g[0]), local_index(g[1]), local_index(g[2])});
  }
  return patch;
}

ElementPatches build_element_patches(const MeshTopology& topology) {
  ElementPatches patches;
  for (int f = 0; f < topology.num_faces(); ++f) {
    const auto& t = topology.face(f);
    if (topology.is_boundary_vertex(t[0]) || topology.is_boundary_vertex(t[1]) ||
        topology.is_boundary_vertex(t[2]))
      continue;
    const bool regular_corners = is_regular_interior(topology, t[0]) &&
                                 is_regular_interior(topology, t[1]) &&
                                 is_regular_interior(topology, t[2]);
    std::optional<LoopPatch> regular;
    if (regular_corners) regular = regular_patch(topology, f);
    patches.patch.push_back(regular ? std::move(*regular) : build_surrounding_patch(topology, f));
    patches.face.push_back(f);
  }
  return patches;
}

}  // namespace growshell
