#include "libshell/mesh/ghost_layer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <sstream>
#include <vector>

#include "libshell/mesh/mesh_error.hpp"
#include "libshell/mesh/mesh_topology.hpp"

namespace growshell {

namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Unsigned angle at p of the triangle (p, q, r), in [0, pi].
double angle_at(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
  const Eigen::Vector2d a = q - p;
  const Eigen::Vector2d b = r - p;
  return std::atan2(std::abs(cross2(a, b)), a.dot(b));
}

}  // namespace

TriangleMesh add_ghost_layer(const TriangleMesh& sheet) {
  const Eigen::Index n = sheet.vertices.rows();
  if (n == 0 || sheet.faces.rows() == 0)
    throw MeshError("add_ghost_layer: the sheet has no vertices or no faces");
  if (!sheet.vertices.allFinite())
    throw MeshError("add_ghost_layer: the sheet has a non-finite vertex coordinate");
  const Eigen::Vector2d lo = sheet.vertices.leftCols<2>().colwise().minCoeff();
  const Eigen::Vector2d hi = sheet.vertices.leftCols<2>().colwise().maxCoeff();
  const double extent = (hi - lo).maxCoeff();
  for (Eigen::Index v = 0; v < n; ++v) {
    if (std::abs(sheet.vertices(v, 2)) > 1e-9 * extent) {
      std::ostringstream m;
      m << "add_ghost_layer: sheet vertex " << v << " has z = " << sheet.vertices(v, 2)
        << ", the sheet must be planar (z = 0)";
      throw MeshError(m.str());
    }
  }
  const MeshTopology topo(static_cast<int>(n), sheet.faces);
  const auto xy = [&](int v) -> Eigen::Vector2d { return sheet.vertices.row(v).head<2>(); };
  for (int f = 0; f < topo.num_faces(); ++f) {
    const auto& t = topo.face(f);
    if (!(cross2(xy(t[1]) - xy(t[0]), xy(t[2]) - xy(t[0])) > 0.0)) {
      std::ostringstream m;
      m << "add_ghost_layer: sheet face " << f << " (" << t[0] << ", " << t[1] << ", " << t[2]
        << ") is not counter-clockwise seen from +z (signed area <= 0)";
      throw MeshError(m.str());
    }
  }

  // 1. Ghost vertex and ghost face of every boundary edge a -> b (face on its left).
  struct BoundaryEdge {
    int a, b;
    Eigen::RowVector3d ghost;
  };
  std::vector<BoundaryEdge> edges;
  // out_edge[v]: the boundary edge leaving v; in_edge[v]: the one entering v.
  std::vector<int> out_edge(static_cast<std::size_t>(n), -1);
  std::vector<int> in_edge(static_cast<std::size_t>(n), -1);
  for (int f = 0; f < topo.num_faces(); ++f) {
    const auto& t = topo.face(f);
    for (int k = 0; k < 3; ++k) {
      const int a = t[static_cast<std::size_t>(k)];
      const int b = t[static_cast<std::size_t>((k + 1) % 3)];
      const int c = t[static_cast<std::size_t>((k + 2) % 3)];
      if (topo.face_with_edge(b, a) >= 0) continue;  // interior edge
      out_edge[static_cast<std::size_t>(a)] = static_cast<int>(edges.size());
      in_edge[static_cast<std::size_t>(b)] = static_cast<int>(edges.size());
      edges.push_back({a, b, sheet.vertices.row(a) + sheet.vertices.row(b) - sheet.vertices.row(c)});
    }
  }
  if (edges.empty()) throw MeshError("add_ghost_layer: the sheet has no boundary (closed surface)");
  // Gap angle at boundary vertex v between the ghosts at p1 (of the incoming edge u -> v) and
  // p2 (of the outgoing edge v -> w): 2 pi minus the sheet angles and the two ghost faces' angles.
  const auto gap_at = [&](int v, const Eigen::Vector2d& p1, const Eigen::Vector2d& p2) {
    const std::vector<int>& ring = topo.one_ring(v);  // w (outgoing) ... u (incoming)
    const Eigen::Vector2d p = xy(v);
    double occupied = angle_at(p, xy(ring.back()), p1) + angle_at(p, p2, xy(ring.front()));
    for (std::size_t i = 0; i + 1 < ring.size(); ++i)
      occupied += angle_at(p, xy(ring[i]), xy(ring[i + 1]));
    return 2.0 * std::numbers::pi - occupied;
  };
  const auto raw_xy = [&](int e) -> Eigen::Vector2d {
    return edges[static_cast<std::size_t>(e)].ghost.head<2>().transpose();
  };
  // 2. Where the gap at a boundary vertex is 0 (the two ghosts coincide, e.g. where both
  // boundary faces have their right angle at the far end) or negative (the ghost faces
  // overlap at a reflex vertex), its two ghosts become one, at their mean.
  std::vector<int> root(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e) root[e] = static_cast<int>(e);
  const auto find = [&](int e) {
    while (root[static_cast<std::size_t>(e)] != e) e = root[static_cast<std::size_t>(e)];
    return e;
  };
  const double merge_tolerance = 1e-12 * extent;
  for (int v = 0; v < static_cast<int>(n); ++v) {
    if (!topo.is_boundary_vertex(v)) continue;
    const int in = in_edge[static_cast<std::size_t>(v)];
    const int out = out_edge[static_cast<std::size_t>(v)];
    const bool merge = (raw_xy(in) - raw_xy(out)).norm() <= merge_tolerance ||
                       gap_at(v, raw_xy(in), raw_xy(out)) <= kGhostGapMergeAngle;
    const int e1 = find(in);
    const int e2 = find(out);
    if (merge && e1 != e2) root[static_cast<std::size_t>(std::max(e1, e2))] = std::min(e1, e2);
  }
  std::vector<Eigen::RowVector3d> ghosts;
  std::vector<int> group_size;
  std::vector<int> ghost_of_edge(edges.size(), -1);
  std::vector<std::array<int, 3>> ghost_faces;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto r = static_cast<std::size_t>(find(static_cast<int>(e)));
    if (ghost_of_edge[r] < 0) {
      ghost_of_edge[r] = static_cast<int>(n + static_cast<Eigen::Index>(ghosts.size()));
      ghosts.push_back(Eigen::RowVector3d::Zero());
      group_size.push_back(0);
    }
    ghost_of_edge[e] = ghost_of_edge[r];
    ghosts[static_cast<std::size_t>(ghost_of_edge[e] - n)] += edges[e].ghost;
    ++group_size[static_cast<std::size_t>(ghost_of_edge[e] - n)];
    ghost_faces.push_back({edges[e].b, edges[e].a, ghost_of_edge[e]});
  }
  for (std::size_t g = 0; g < ghosts.size(); ++g)
    if (group_size[g] > 1) ghosts[g] /= static_cast<double>(group_size[g]);
  const auto ghost_xy = [&](int g) -> Eigen::Vector2d {
    return ghosts[static_cast<std::size_t>(g - n)].head<2>().transpose();
  };

  // 3. Close the fan of every boundary vertex between its two ghosts.
  std::vector<std::array<int, 3>> closing_faces;
  for (int v = 0; v < static_cast<int>(n); ++v) {
    if (!topo.is_boundary_vertex(v)) continue;
    const std::vector<int>& ring = topo.one_ring(v);  // w (outgoing) ... u (incoming)
    const int g1 = ghost_of_edge[static_cast<std::size_t>(in_edge[static_cast<std::size_t>(v)])];
    const int g2 = ghost_of_edge[static_cast<std::size_t>(out_edge[static_cast<std::size_t>(v)])];
    if (g1 == g2) continue;  // merged ghosts: the fan is already closed
    const Eigen::Vector2d p = xy(v);
    const double gap = gap_at(v, ghost_xy(g1), ghost_xy(g2));
    const auto fail = [&](const char* why) {
      std::ostringstream m;
      m << "add_ghost_layer: boundary vertex " << v << " at (" << p.x() << ", " << p.y()
        << "): " << why << " (gap angle " << gap * 180.0 / std::numbers::pi << " degrees)";
      throw MeshError(m.str());
    };
    if (!(gap > 0.0)) fail("its ghost faces overlap after merging; the boundary is too reflex there");
    if (gap <= kGhostGapSplitAngle) {
      if (!(cross2(ghost_xy(g1) - p, ghost_xy(g2) - p) > 0.0))
        fail("the closing face (v, g1, g2) would be degenerate");
      closing_faces.push_back({v, g1, g2});
      continue;
    }
    Eigen::RowVector3d mean = Eigen::RowVector3d::Zero();
    for (const int q : ring) mean += sheet.vertices.row(q);
    mean /= static_cast<double>(ring.size());
    const Eigen::RowVector3d e_pos = 2.0 * sheet.vertices.row(v) - mean;
    const Eigen::Vector2d e_xy = e_pos.head<2>().transpose();
    if (!(cross2(ghost_xy(g1) - p, e_xy - p) > 0.0 && cross2(e_xy - p, ghost_xy(g2) - p) > 0.0))
      fail("the extra ghost vertex 2 v - (mean of its neighbours) is outside the gap");
    const int e = static_cast<int>(n + static_cast<Eigen::Index>(ghosts.size()));
    ghosts.push_back(e_pos);
    closing_faces.push_back({v, g1, e});
    closing_faces.push_back({v, e, g2});
  }

  TriangleMesh out;
  out.vertices.resize(n + static_cast<Eigen::Index>(ghosts.size()), 3);
  out.vertices.topRows(n) = sheet.vertices;
  for (std::size_t g = 0; g < ghosts.size(); ++g)
    out.vertices.row(n + static_cast<Eigen::Index>(g)) = ghosts[g];
  const Eigen::Index nf = sheet.faces.rows();
  out.faces.resize(nf + static_cast<Eigen::Index>(ghost_faces.size() + closing_faces.size()), 3);
  out.faces.topRows(nf) = sheet.faces;
  Eigen::Index row = nf;
  for (const auto* list : {&ghost_faces, &closing_faces})
    for (const auto& t : *list) out.faces.row(row++) << t[0], t[1], t[2];
  // Merged ghosts may invert a ghost face or, for a boundary loop of only reflex vertices
  // (a hole of a few edges), close a ghost's fan, which would make ghost faces elements.
  for (Eigen::Index f = nf; f < out.faces.rows(); ++f) {
    const Eigen::Vector2d a = out.vertices.row(out.faces(f, 0)).head<2>();
    const Eigen::Vector2d b = out.vertices.row(out.faces(f, 1)).head<2>();
    const Eigen::Vector2d c = out.vertices.row(out.faces(f, 2)).head<2>();
    if (!(cross2(b - a, c - a) > 0.0)) {
      std::ostringstream m;
      m << "add_ghost_layer: the ghost face (" << out.faces(f, 0) << ", " << out.faces(f, 1)
        << ", " << out.faces(f, 2) << ") at sheet vertex " << out.faces(f, 0)
        << " is inverted: the boundary is too reflex there (refine the sheet near it)";
      throw MeshError(m.str());
    }
  }
  const MeshTopology out_topo(out);
  for (int g = static_cast<int>(n); g < out_topo.num_vertices(); ++g)
    if (!out_topo.is_boundary_vertex(g))
      throw MeshError("add_ghost_layer: ghost vertex " + std::to_string(g) +
                      " closes a boundary loop of reflex vertices (a hole of too few edges)");
  return out;
}

}  // namespace growshell
