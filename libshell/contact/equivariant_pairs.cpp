#include "libshell/contact/equivariant_pairs.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "libshell/mesh/vertex_symmetry.hpp"

namespace growshell {
namespace {

std::array<int, 3> sorted_corners(int a, int b, int c) {
  std::array<int, 3> k{a, b, c};
  std::sort(k.begin(), k.end());
  return k;
}

}  // namespace

std::vector<ProxySymmetry> proxy_symmetry_group(const ContactProxy& proxy,
                                                const std::vector<Eigen::Vector3d>& signs,
                                                double tolerance) {
  if (signs.size() > 16)
    throw std::invalid_argument("proxy_symmetry_group: at most 16 generators, got " +
                                std::to_string(signs.size()));
  const Eigen::Index nt = proxy.triangles.rows();
  std::map<std::array<int, 3>, int> triangle_of;
  for (Eigen::Index t = 0; t < nt; ++t)
    triangle_of[sorted_corners(proxy.triangles(t, 0), proxy.triangles(t, 1),
                               proxy.triangles(t, 2))] = static_cast<int>(t);
  // Diagonal sign matrices commute and square to one: the group is the set of products of
  // subsets of the generators, the empty product (the identity) first.
  std::vector<Eigen::Vector3d> elements;
  for (unsigned subset = 0; subset < (1u << signs.size()); ++subset) {
    Eigen::Vector3d product = Eigen::Vector3d::Ones();
    for (std::size_t k = 0; k < signs.size(); ++k)
      if (subset & (1u << k)) product = product.cwiseProduct(signs[k]);
    if (std::find(elements.begin(), elements.end(), product) == elements.end())
      elements.push_back(product);
  }
  std::vector<ProxySymmetry> group;
  for (const Eigen::Vector3d& s : elements) {
    ProxySymmetry g;
    g.vertex_image = find_vertex_symmetry(proxy.reference_positions, s, tolerance).image;
    g.triangle_image.resize(static_cast<std::size_t>(nt));
    for (Eigen::Index t = 0; t < nt; ++t) {
      const auto image = triangle_of.find(
          sorted_corners(g.vertex_image[static_cast<std::size_t>(proxy.triangles(t, 0))],
                         g.vertex_image[static_cast<std::size_t>(proxy.triangles(t, 1))],
                         g.vertex_image[static_cast<std::size_t>(proxy.triangles(t, 2))]));
      if (image == triangle_of.end())
        throw std::invalid_argument("proxy_symmetry_group: the image of proxy triangle " +
                                    std::to_string(t) + " is no proxy triangle");
      g.triangle_image[static_cast<std::size_t>(t)] = image->second;
    }
    group.push_back(std::move(g));
  }
  return group;
}

ContactCandidates equivariant_nearest_pairs(const ContactCandidates& nearest,
                                            const std::vector<ProxySymmetry>& group) {
  if (group.empty()) return nearest;
  const std::size_t nv = group.front().vertex_image.size();
  const std::size_t nt = group.front().triangle_image.size();
  std::vector<int> triangle_of(nv, -1);
  for (Eigen::Index k = 0; k < nearest.vertex_triangle.rows(); ++k) {
    const int v = nearest.vertex_triangle(k, 0), t = nearest.vertex_triangle(k, 1);
    if (v < 0 || static_cast<std::size_t>(v) >= nv || t < 0 || static_cast<std::size_t>(t) >= nt)
      throw std::invalid_argument("equivariant_nearest_pairs: pair (" + std::to_string(v) + ", " +
                                  std::to_string(t) + ") is outside the symmetries' maps");
    if (triangle_of[static_cast<std::size_t>(v)] >= 0)
      throw std::invalid_argument("equivariant_nearest_pairs: proxy vertex " + std::to_string(v) +
                                  " has more than one pair");
    triangle_of[static_cast<std::size_t>(v)] = t;
  }
  std::vector<int> chosen(nv, -1);
  std::vector<bool> decided(nv, false);
  for (std::size_t v = 0; v < nv; ++v) {
    const int t = triangle_of[v];
    if (t < 0 || decided[v]) continue;
    // v is its orbit's member of lowest index with a pair; the group's first element is the
    // identity, so v keeps its own, and so does a member reached twice (first image wins).
    for (const ProxySymmetry& g : group) {
      const auto w = static_cast<std::size_t>(g.vertex_image[v]);
      if (decided[w]) continue;
      chosen[w] = g.triangle_image[static_cast<std::size_t>(t)];
      decided[w] = true;
    }
  }
  std::vector<std::pair<int, int>> rows;
  for (std::size_t v = 0; v < nv; ++v)
    if (chosen[v] >= 0) rows.emplace_back(static_cast<int>(v), chosen[v]);
  ContactCandidates out;
  out.pairs_examined = nearest.pairs_examined;
  out.edge_edge = nearest.edge_edge;
  out.vertex_triangle.resize(static_cast<Eigen::Index>(rows.size()), 2);
  for (std::size_t i = 0; i < rows.size(); ++i)
    out.vertex_triangle.row(static_cast<Eigen::Index>(i)) << rows[i].first, rows[i].second;
  return out;
}

}  // namespace growshell
