#include "libshell/subdivision/local_loop_subdivision.hpp"

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "libshell/subdivision/loop_rules.hpp"

namespace growshell {
namespace {

std::pair<int, int> undirected(int a, int b) { return a < b ? std::pair{a, b} : std::pair{b, a}; }

}  // namespace

namespace {

// The fan of v, or nothing if v's faces do not form one fan (e.g. a vertex where the kept faces
// of a small closed mesh meet from two sides).
std::optional<LocalFan> single_fan(const LocalLoopMesh& mesh, int v) {
  // next[p] = q for every face (v, p, q): going counter-clockwise around v, p is followed by q.
  std::map<int, int> next, previous;
  for (const auto& f : mesh.faces)
    for (int k = 0; k < 3; ++k)
      if (f[k] == v) {
        next[f[(k + 1) % 3]] = f[(k + 2) % 3];
        previous[f[(k + 2) % 3]] = f[(k + 1) % 3];
      }
  if (next.empty()) return std::nullopt;
  // Start of an open fan: a neighbour with a face on its counter-clockwise side only.
  int start = next.begin()->first;
  bool closed = true;
  for (const auto& [p, q] : next)
    if (!previous.count(p)) {
      start = p;
      closed = false;
      break;
    }
  LocalFan fan;
  fan.closed = closed;
  int p = start;
  for (;;) {
    fan.neighbours.push_back(p);
    const auto it = next.find(p);
    if (it == next.end()) break;  // open fan: p is the last neighbour
    p = it->second;
    if (p == start) break;
    if (fan.neighbours.size() > next.size() + 1) return std::nullopt;
  }
  const std::size_t faces_seen = closed ? fan.neighbours.size() : fan.neighbours.size() - 1;
  if (faces_seen != next.size()) return std::nullopt;
  return fan;
}

}  // namespace

LocalFan local_fan(const LocalLoopMesh& mesh, int v) {
  if (v < 0 || v >= mesh.num_vertices)
    throw std::invalid_argument("local_fan: vertex " + std::to_string(v) + " out of range");
  std::optional<LocalFan> fan = single_fan(mesh, v);
  if (!fan)
    throw std::invalid_argument("local_fan: the faces around vertex " + std::to_string(v) +
                                " do not form one fan");
  return *fan;
}

LocalSubdivisionStep subdivide_local_mesh(const LocalLoopMesh& mesh) {
  const int n = mesh.num_vertices;
  // Undirected edges in order of first appearance, with the vertices opposite to them.
  std::map<std::pair<int, int>, int> edge_index;
  std::vector<std::pair<int, int>> edges;
  std::vector<std::vector<int>> opposite;
  LocalSubdivisionStep step;
  step.edge_point.resize(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    for (int k = 0; k < 3; ++k) {
      const auto key = undirected(t[k], t[(k + 1) % 3]);
      auto [it, inserted] = edge_index.try_emplace(key, static_cast<int>(edges.size()));
      if (inserted) {
        edges.push_back(key);
        opposite.emplace_back();
      }
      opposite[static_cast<std::size_t>(it->second)].push_back(t[(k + 2) % 3]);
      step.edge_point[f][static_cast<std::size_t>(k)] = n + it->second;
    }
  }
  const int refined_vertices = n + static_cast<int>(edges.size());
  step.rule = Eigen::MatrixXd::Zero(refined_vertices, n);
  step.computable.assign(static_cast<std::size_t>(refined_vertices), 0);
  for (int v = 0; v < n; ++v) {
    const std::optional<LocalFan> fan = single_fan(mesh, v);
    if (!fan || !fan->closed) continue;
    const int valence = static_cast<int>(fan->neighbours.size());
    const double beta = loop_vertex_neighbour_weight(valence);
    step.rule(v, v) = 1.0 - valence * beta;
    for (int u : fan->neighbours) step.rule(v, u) += beta;
    step.computable[static_cast<std::size_t>(v)] = 1;
  }
  for (std::size_t e = 0; e < edges.size(); ++e) {
    if (opposite[e].size() != 2) continue;
    const int row = n + static_cast<int>(e);
    step.rule(row, edges[e].first) += 0.375;
    step.rule(row, edges[e].second) += 0.375;
    step.rule(row, opposite[e][0]) += 0.125;
    step.rule(row, opposite[e][1]) += 0.125;
    step.computable[static_cast<std::size_t>(row)] = 1;
  }
  step.refined.num_vertices = refined_vertices;
  step.refined.faces.reserve(4 * mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    const int ab = step.edge_point[f][0], bc = step.edge_point[f][1], ca = step.edge_point[f][2];
    step.refined.faces.push_back({t[0], ab, ca});
    step.refined.faces.push_back({ab, t[1], bc});
    step.refined.faces.push_back({ca, bc, t[2]});
    step.refined.faces.push_back({bc, ca, ab});
  }
  return step;
}

}  // namespace growshell
