#include "libshell/mesh/mesh_topology.hpp"

#include <algorithm>
#include <string>
#include <tuple>

#include "libshell/mesh/mesh_error.hpp"

namespace growshell {

namespace {

std::string face_name(int f) { return "face " + std::to_string(f); }

std::string edge_name(int a, int b) {
  return "edge (" + std::to_string(a) + ", " + std::to_string(b) + ")";
}

// One face's view from one of its vertices: going counter-clockwise around the vertex the face
// spans from neighbour `from` to neighbour `to`.
struct Wedge {
  int from;
  int to;
  int face;
};

}  // namespace

MeshTopology::MeshTopology(const TriangleMesh& mesh)
    : MeshTopology(static_cast<int>(mesh.vertices.rows()), mesh.faces) {}

MeshTopology::MeshTopology(int num_vertices, const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  if (num_vertices < 0) {
    throw MeshError("number of vertices is " + std::to_string(num_vertices) + "; it must be >= 0");
  }
  const int nf = static_cast<int>(faces.rows());
  faces_.resize(nf);
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int v = faces(f, k);
      if (v < 0 || v >= num_vertices) {
        throw MeshError(face_name(f) + " refers to vertex " + std::to_string(v) +
                        ", outside the valid range [0, " + std::to_string(num_vertices) + ")");
      }
      faces_[f][k] = v;
    }
    const auto& t = faces_[f];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      throw MeshError(face_name(f) + " (" + std::to_string(t[0]) + ", " + std::to_string(t[1]) +
                      ", " + std::to_string(t[2]) + ") repeats a vertex");
    }
  }

  // Edge checks on a sorted list of (min, max, face, forward) so that the errors reported do
  // not depend on hashing; non-manifold edges are reported before orientation conflicts
  // because with three or more faces the orientation question is meaningless.
  std::vector<std::tuple<int, int, int, bool>> edges;
  edges.reserve(3 * static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = faces_[f][k];
      const int b = faces_[f][(k + 1) % 3];
      edges.emplace_back(std::min(a, b), std::max(a, b), f, a < b);
    }
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && std::get<0>(edges[j]) == std::get<0>(edges[i]) &&
           std::get<1>(edges[j]) == std::get<1>(edges[i])) {
      ++j;
    }
    if (j - i > 2) {
      std::string list;
      for (std::size_t k = i; k < j; ++k) {
        list += (k == i ? "" : ", ") + std::to_string(std::get<2>(edges[k]));
      }
      throw MeshError("non-manifold " + edge_name(std::get<0>(edges[i]), std::get<1>(edges[i])) +
                      " is shared by " + std::to_string(j - i) + " faces (" + list +
                      "); at most two are allowed");
    }
    i = j;
  }
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
    const auto& [a0, b0, f0, fw0] = edges[i];
    const auto& [a1, b1, f1, fw1] = edges[i + 1];
    if (a0 == a1 && b0 == b1 && fw0 == fw1) {
      const int from = fw0 ? a0 : b0;
      const int to = fw0 ? b0 : a0;
      throw MeshError("inconsistent orientation: faces " + std::to_string(f0) + " and " +
                      std::to_string(f1) + " both traverse the edge " + std::to_string(from) +
                      " -> " + std::to_string(to) + " in the same direction");
    }
  }

  std::vector<std::vector<Wedge>> wedges(num_vertices);
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      wedges[faces_[f][k]].push_back({faces_[f][(k + 1) % 3], faces_[f][(k + 2) % 3], f});
    }
  }

  rings_.resize(num_vertices);
  ring_faces_.resize(num_vertices);
  boundary_.assign(num_vertices, 0);
  for (int v = 0; v < num_vertices; ++v) {
    const auto& w = wedges[v];
    if (w.empty()) {
      throw MeshError("vertex " + std::to_string(v) + " is not used by any face");
    }
    // A fan start is a neighbour with no face on the clockwise side of its edge, i.e. the
    // `from` of a wedge that is no wedge's `to`.
    int start = -1;
    int num_starts = 0;
    for (const Wedge& x : w) {
      const bool is_end =
          std::any_of(w.begin(), w.end(), [&](const Wedge& y) { return y.to == x.from; });
      if (!is_end) {
        if (num_starts == 0) start = x.from;
        ++num_starts;
      }
    }
    if (num_starts > 1) {
      throw MeshError("vertex " + std::to_string(v) + " is non-manifold: its faces form " +
                      std::to_string(num_starts) + " separate fans");
    }
    const bool open = num_starts == 1;
    if (!open) start = w.front().from;

    auto& ring = rings_[v];
    auto& ring_faces = ring_faces_[v];
    int current = start;
    for (std::size_t step = 0; step < w.size(); ++step) {
      const auto it =
          std::find_if(w.begin(), w.end(), [&](const Wedge& x) { return x.from == current; });
      // Orientation consistency makes every `from` unique, so a missing successor means the
      // chain ended before using all faces: more than one fan.
      if (it == w.end() || (!open && step > 0 && current == start)) break;
      ring.push_back(current);
      ring_faces.push_back(it->face);
      current = it->to;
    }
    if (ring.size() != w.size() || (!open && current != start)) {
      throw MeshError("vertex " + std::to_string(v) +
                      " is non-manifold: its faces do not form a single fan");
    }
    if (open) {
      ring.push_back(current);
      ring_faces.push_back(-1);
      boundary_[v] = 1;
    }
  }
}

void MeshTopology::check_vertex(int v, const char* argument) const {
  if (v < 0 || v >= num_vertices()) {
    throw MeshError(std::string(argument) + " = vertex " + std::to_string(v) +
                    " is outside the valid range [0, " + std::to_string(num_vertices()) + ")");
  }
}

const std::array<int, 3>& MeshTopology::face(int f) const {
  if (f < 0 || f >= num_faces()) {
    throw MeshError(face_name(f) + " is outside the valid range [0, " +
                    std::to_string(num_faces()) + ")");
  }
  return faces_[f];
}

bool MeshTopology::is_boundary_vertex(int v) const {
  check_vertex(v, "v");
  return boundary_[v] != 0;
}

int MeshTopology::valence(int v) const {
  check_vertex(v, "v");
  return static_cast<int>(rings_[v].size());
}

const std::vector<int>& MeshTopology::one_ring(int v) const {
  check_vertex(v, "v");
  return rings_[v];
}

int MeshTopology::ring_slot_with_face(int a, int b) const {
  check_vertex(a, "a");
  check_vertex(b, "b");
  const auto& ring = rings_[a];
  for (std::size_t i = 0; i < ring.size(); ++i) {
    if (ring[i] == b) return ring_faces_[a][i] >= 0 ? static_cast<int>(i) : -1;
  }
  return -1;
}

int MeshTopology::opposite_vertex(int a, int b) const {
  const int i = ring_slot_with_face(a, b);
  if (i < 0) return -1;
  const auto& ring = rings_[a];
  return ring[(static_cast<std::size_t>(i) + 1) % ring.size()];
}

int MeshTopology::face_with_edge(int a, int b) const {
  const int i = ring_slot_with_face(a, b);
  return i < 0 ? -1 : ring_faces_[a][i];
}

}  // namespace growshell
