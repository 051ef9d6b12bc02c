#include "libshell/contact/near_contact_pairs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "libshell/contact/edge_edge_distance.hpp"
#include "libshell/contact/point_triangle_distance.hpp"

namespace growshell {
namespace {

/// Exact (unmollified) distances of the pairs at proxy positions y, vertex-triangle pairs first.
/// Computed from the distance primitives directly: building ContactGapConstraints for them
/// (stencils and derivative patterns of every pair) cost 30 s for the 2.1 million candidates
/// of a three-segment proxy within 2 h, where the distances alone take a fraction of that.
Eigen::VectorXd pair_distances(const ContactProxy& proxy, const ContactCandidates& pairs,
                               const Eigen::MatrixX3d& y) {
  const Eigen::Index nvt = pairs.vertex_triangle.rows();
  Eigen::VectorXd d(nvt + pairs.edge_edge.rows());
  for (Eigen::Index k = 0; k < nvt; ++k) {
    const Eigen::Vector3i t = proxy.triangles.row(pairs.vertex_triangle(k, 1)).transpose();
    d(k) = std::sqrt(point_triangle_distance_squared(
        y.row(pairs.vertex_triangle(k, 0)).transpose(), y.row(t(0)).transpose(),
        y.row(t(1)).transpose(), y.row(t(2)).transpose()));
  }
  for (Eigen::Index k = 0; k < pairs.edge_edge.rows(); ++k) {
    const int a = pairs.edge_edge(k, 0), b = pairs.edge_edge(k, 1);
    d(nvt + k) = std::sqrt(edge_edge_distance_squared(
        y.row(proxy.edges(a, 0)).transpose(), y.row(proxy.edges(a, 1)).transpose(),
        y.row(proxy.edges(b, 0)).transpose(), y.row(proxy.edges(b, 1)).transpose()));
  }
  return d;
}

/// Sorted union of two sorted, duplicate-free pair lists.
Eigen::MatrixX2i merge_pairs(const Eigen::MatrixX2i& a, const Eigen::MatrixX2i& b) {
  std::vector<std::pair<int, int>> all;
  for (Eigen::Index i = 0; i < a.rows(); ++i) all.emplace_back(a(i, 0), a(i, 1));
  for (Eigen::Index i = 0; i < b.rows(); ++i) all.emplace_back(b(i, 0), b(i, 1));
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  Eigen::MatrixX2i out(static_cast<Eigen::Index>(all.size()), 2);
  for (std::size_t i = 0; i < all.size(); ++i) out.row(static_cast<Eigen::Index>(i)) << all[i].first, all[i].second;
  return out;
}

}  // namespace

ContactCandidates merge_contact_pairs(const ContactCandidates& a, const ContactCandidates& b) {
  ContactCandidates out;
  out.vertex_triangle = merge_pairs(a.vertex_triangle, b.vertex_triangle);
  out.edge_edge = merge_pairs(a.edge_edge, b.edge_edge);
  return out;
}

double smallest_pair_distance(const ContactProxy& proxy, const ContactCandidates& pairs,
                              const Eigen::Ref<const Eigen::VectorXd>& x) {
  if (pairs.empty()) return std::numeric_limits<double>::infinity();
  return pair_distances(proxy, pairs, proxy_positions(proxy, x)).minCoeff();
}

ContactCandidates near_contact_pairs(const ContactProxy& proxy, const Eigen::Ref<const Eigen::VectorXd>& x,
                                     double distance, double exclusion_radius,
                                     const NearPairSelection& selection) {
  ContactCandidateOptions o;
  o.query_distance = distance;
  o.exclusion_radius = exclusion_radius;
  const Eigen::MatrixX3d y = proxy_positions(proxy, x);
  const ContactCandidates boxes = find_contact_candidates(proxy, y, o);
  if (boxes.empty()) return boxes;
  const Eigen::VectorXd d = pair_distances(proxy, boxes, y);
  std::vector<Eigen::Index> vt, ee;
  const Eigen::Index nvt = boxes.vertex_triangle.rows();
  for (Eigen::Index k = 0; k < d.size(); ++k) {
    if (!(d(k) < distance)) continue;
    if (k < nvt) {
      // Rows are sorted by vertex: a vertex's candidates are consecutive.
      if (selection.nearest_triangle_only && !vt.empty() &&
          boxes.vertex_triangle(vt.back(), 0) == boxes.vertex_triangle(k, 0)) {
        if (d(k) < d(vt.back())) vt.back() = k;
        continue;
      }
      vt.push_back(k);
    } else if (selection.edge_edge_pairs) {
      ee.push_back(k - nvt);
    }
  }
  ContactCandidates out;
  out.pairs_examined = boxes.pairs_examined;
  out.vertex_triangle.resize(static_cast<Eigen::Index>(vt.size()), 2);
  out.edge_edge.resize(static_cast<Eigen::Index>(ee.size()), 2);
  for (std::size_t i = 0; i < vt.size(); ++i)
    out.vertex_triangle.row(static_cast<Eigen::Index>(i)) = boxes.vertex_triangle.row(vt[i]);
  for (std::size_t i = 0; i < ee.size(); ++i)
    out.edge_edge.row(static_cast<Eigen::Index>(i)) = boxes.edge_edge.row(ee[i]);
  return out;
}

}  // namespace growshell
