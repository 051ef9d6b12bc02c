#include "libshell/contact/contact_candidates.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

namespace growshell {
namespace {

/// Grid cell coordinates are packed into 21 bits each of one 64-bit key; the cell size is
/// chosen so that at most 2^20 (+ 2) cells are needed per axis.
constexpr int kKeyBits = 21;
constexpr double kMaxCellsPerAxis = 1048576.0;  // 2^20
/// Relative widening of the query boxes in the hash, so that rounding in the box arithmetic
/// can never make the grid drop a pair that the exact test accepts (extra hits are filtered).
constexpr double kRelativePad = 1e-12;

struct Box {
  Eigen::Vector3d lo, hi;
};

/// Everything the pair tests need, shared by the hash and the brute force so that both apply
/// bit-identical predicates.
class PairTests {
 public:
  PairTests(const ContactProxy& proxy, const Eigen::Ref<const Eigen::MatrixX3d>& positions,
            const ContactCandidateOptions& options)
      : proxy_(proxy),
        d_(options.query_distance),
        r2_(options.exclusion_radius * options.exclusion_radius) {
    const Eigen::Index V = positions.rows();
    vertex_box_.resize(static_cast<std::size_t>(V));
    for (Eigen::Index p = 0; p < V; ++p)
      vertex_box_[static_cast<std::size_t>(p)] = {positions.row(p).transpose(),
                                                  positions.row(p).transpose()};
    triangle_box_.resize(static_cast<std::size_t>(proxy.triangles.rows()));
    for (Eigen::Index t = 0; t < proxy.triangles.rows(); ++t) {
      Box& b = triangle_box_[static_cast<std::size_t>(t)];
      b = vertex_box_[static_cast<std::size_t>(proxy.triangles(t, 0))];
      for (int c = 1; c < 3; ++c)
        grow(b, vertex_box_[static_cast<std::size_t>(proxy.triangles(t, c))]);
    }
    edge_box_.resize(static_cast<std::size_t>(proxy.edges.rows()));
    for (Eigen::Index e = 0; e < proxy.edges.rows(); ++e) {
      Box& b = edge_box_[static_cast<std::size_t>(e)];
      b = vertex_box_[static_cast<std::size_t>(proxy.edges(e, 0))];
      grow(b, vertex_box_[static_cast<std::size_t>(proxy.edges(e, 1))]);
    }
  }

  /// Vertex p and triangle t form a candidate (p not a corner, boxes within d, reference
  /// distance >= r_ex).
  bool vertex_triangle(int p, int t) const {
    const auto tri = proxy_.triangles.row(t);
    if (tri(0) == p || tri(1) == p || tri(2) == p) return false;
    if (!boxes_near(vertex_box_[static_cast<std::size_t>(p)],
                    triangle_box_[static_cast<std::size_t>(t)]))
      return false;
    for (int c = 0; c < 3; ++c)
      if (reference_squared(p, tri(c)) < r2_) return false;
    return true;
  }

  /// Edges a and b form a candidate (no shared vertex, boxes within d, reference distance >= r_ex).
  bool edge_edge(int a, int b) const {
    const int a0 = proxy_.edges(a, 0), a1 = proxy_.edges(a, 1), b0 = proxy_.edges(b, 0),
              b1 = proxy_.edges(b, 1);
    if (a0 == b0 || a0 == b1 || a1 == b0 || a1 == b1) return false;
    if (!boxes_near(edge_box_[static_cast<std::size_t>(a)], edge_box_[static_cast<std::size_t>(b)]))
      return false;
    for (int p : {a0, a1})
      for (int q : {b0, b1})
        if (reference_squared(p, q) < r2_) return false;
    return true;
  }

  const std::vector<Box>& vertex_boxes() const { return vertex_box_; }
  const std::vector<Box>& triangle_boxes() const { return triangle_box_; }
  const std::vector<Box>& edge_boxes() const { return edge_box_; }

 private:
  static void grow(Box& b, const Box& other) {
    b.lo = b.lo.cwiseMin(other.lo);
    b.hi = b.hi.cwiseMax(other.hi);
  }
  bool boxes_near(const Box& a, const Box& b) const {
    for (int c = 0; c < 3; ++c)
      if (a.lo(c) - b.hi(c) > d_ || b.lo(c) - a.hi(c) > d_) return false;
    return true;
  }
  double reference_squared(int p, int q) const {
    return (proxy_.reference_positions.row(p) - proxy_.reference_positions.row(q)).squaredNorm();
  }

  const ContactProxy& proxy_;
  double d_, r2_;
  std::vector<Box> vertex_box_, triangle_box_, edge_box_;
};

void validate(const ContactProxy& proxy, const Eigen::Ref<const Eigen::MatrixX3d>& positions,
              const ContactCandidateOptions& options, const char* caller) {
  const auto check_length = [&](double value, const char* field) {
    if (!std::isfinite(value) || value < 0.0) {
      std::ostringstream msg;
      msg << caller << ": ContactCandidateOptions." << field
          << " must be finite and >= 0 (metres), got " << value;
      throw std::invalid_argument(msg.str());
    }
  };
  check_length(options.query_distance, "query_distance");
  check_length(options.exclusion_radius, "exclusion_radius");
  if (positions.rows() != proxy.num_vertices()) {
    std::ostringstream msg;
    msg << caller << ": positions has " << positions.rows() << " rows, the proxy has "
        << proxy.num_vertices() << " vertices";
    throw std::invalid_argument(msg.str());
  }
  for (Eigen::Index p = 0; p < positions.rows(); ++p)
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(positions(p, c))) {
        std::ostringstream msg;
        msg << caller << ": positions(" << p << ", " << c << ") (proxy vertex " << p
            << ") is not finite";
        throw std::invalid_argument(msg.str());
      }
}

/// Uniform grid over the current boxes with sorted cell keys.
class SpatialHash {
 public:
  SpatialHash(const ContactProxy& proxy, const Eigen::Ref<const Eigen::MatrixX3d>& positions,
              double d) {
    Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
    if (positions.rows() > 0) {
      lo = positions.colwise().minCoeff().transpose();
      hi = positions.colwise().maxCoeff().transpose();
    }
    double mean_edge = 0.0;
    for (Eigen::Index e = 0; e < proxy.edges.rows(); ++e)
      mean_edge += (positions.row(proxy.edges(e, 0)) - positions.row(proxy.edges(e, 1))).norm();
    if (proxy.edges.rows() > 0) mean_edge /= static_cast<double>(proxy.edges.rows());
    const double scale = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
    pad_ = d + kRelativePad * (scale + d) + std::numeric_limits<double>::min();
    origin_ = lo - Eigen::Vector3d::Constant(2.0 * pad_);
    const double extent = (hi - origin_).maxCoeff() + 2.0 * pad_;
    // Why mean edge + d: a stored box then spans at most ~2 cells per axis and a query box
    // (size + 2 d) at most ~3, while a cell holds O(((l + d) / l)^2) surface primitives.
    cell_ = mean_edge + d;
    cell_ = std::max(cell_, extent / kMaxCellsPerAxis);
    if (!(cell_ > 0.0)) cell_ = 1.0;  // every vertex on one point and d = 0
  }

  /// Enters every box into the cells it overlaps, then sorts the (key, id) list.
  void store(const std::vector<Box>& boxes) {
    entries_.clear();
    for (std::size_t k = 0; k < boxes.size(); ++k)
      for_each_cell(boxes[k], 0.0,
                    [&](std::uint64_t key) { entries_.emplace_back(key, static_cast<int>(k)); });
    std::sort(entries_.begin(), entries_.end());
    keys_.clear();
    begin_.clear();
    for (std::size_t k = 0; k < entries_.size(); ++k)
      if (k == 0 || entries_[k].first != entries_[k - 1].first) {
        keys_.push_back(entries_[k].first);
        begin_.push_back(k);
      }
    begin_.push_back(entries_.size());
  }

  /// Ids of the stored boxes sharing a cell with `box` inflated by d (plus rounding pad),
  /// appended to `hits` with repetitions; returns how many were appended.
  std::size_t query(const Box& box, std::vector<int>& hits) const {
    const std::size_t before = hits.size();
    for_each_cell(box, pad_, [&](std::uint64_t key) {
      const auto it = std::lower_bound(keys_.begin(), keys_.end(), key);
      if (it == keys_.end() || *it != key) return;
      const auto cell = static_cast<std::size_t>(it - keys_.begin());
      for (std::size_t k = begin_[cell]; k < begin_[cell + 1]; ++k)
        hits.push_back(entries_[k].second);
    });
    return hits.size() - before;
  }

 private:
  template <class F>
  void for_each_cell(const Box& box, double inflate, F f) const {
    std::array<std::int64_t, 3> first{}, last{};
    for (int c = 0; c < 3; ++c) {
      first[static_cast<std::size_t>(c)] = cell_index(box.lo(c) - inflate, c);
      last[static_cast<std::size_t>(c)] = cell_index(box.hi(c) + inflate, c);
    }
    for (std::int64_t i = first[0]; i <= last[0]; ++i)
      for (std::int64_t j = first[1]; j <= last[1]; ++j)
        for (std::int64_t k = first[2]; k <= last[2]; ++k)
          f((static_cast<std::uint64_t>(i) << (2 * kKeyBits)) |
            (static_cast<std::uint64_t>(j) << kKeyBits) | static_cast<std::uint64_t>(k));
  }
  std::int64_t cell_index(double coordinate, int axis) const {
    // Clamped into the key range; every box lies inside [origin, origin + extent], so the clamp
    // only guards against rounding at the ends.
    const double cell = std::floor((coordinate - origin_(axis)) / cell_);
    return static_cast<std::int64_t>(std::clamp(cell, 0.0, kMaxCellsPerAxis + 2.0));
  }

  Eigen::Vector3d origin_;
  double cell_ = 1.0, pad_ = 0.0;
  std::vector<std::pair<std::uint64_t, int>> entries_;
  std::vector<std::uint64_t> keys_;
  std::vector<std::size_t> begin_;
};

Eigen::MatrixX2i to_matrix(const std::vector<std::array<int, 2>>& pairs) {
  Eigen::MatrixX2i m(static_cast<Eigen::Index>(pairs.size()), 2);
  for (std::size_t k = 0; k < pairs.size(); ++k)
    m.row(static_cast<Eigen::Index>(k)) << pairs[k][0], pairs[k][1];
  return m;
}

/// The spatial-hash search; with stop_at_first it returns as soon as one candidate is found.
ContactCandidates hash_search(const ContactProxy& proxy,
                              const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                              const ContactCandidateOptions& options, bool stop_at_first) {
  const PairTests tests(proxy, positions, options);
  SpatialHash hash(proxy, positions, options.query_distance);
  ContactCandidates result;
  std::vector<std::array<int, 2>> found;
  std::vector<int> hits;

  // Queries visit vertices (edges) in increasing order and their sorted hits in increasing
  // order, so the output comes out sorted and, after the per-query unique, duplicate-free.
  hash.store(tests.triangle_boxes());
  for (int p = 0; p < static_cast<int>(proxy.num_vertices()); ++p) {
    hits.clear();
    result.pairs_examined += static_cast<Eigen::Index>(
        hash.query(tests.vertex_boxes()[static_cast<std::size_t>(p)], hits));
    std::sort(hits.begin(), hits.end());
    hits.erase(std::unique(hits.begin(), hits.end()), hits.end());
    for (int t : hits)
      if (tests.vertex_triangle(p, t)) {
        found.push_back({p, t});
        if (stop_at_first) {
          result.vertex_triangle = to_matrix(found);
          return result;
        }
      }
  }
  result.vertex_triangle = to_matrix(found);

  found.clear();
  hash.store(tests.edge_boxes());
  for (int a = 0; a < static_cast<int>(proxy.edges.rows()); ++a) {
    hits.clear();
    result.pairs_examined += static_cast<Eigen::Index>(
        hash.query(tests.edge_boxes()[static_cast<std::size_t>(a)], hits));
    std::sort(hits.begin(), hits.end());
    hits.erase(std::unique(hits.begin(), hits.end()), hits.end());
    // The box test is symmetric: each unordered pair is kept from its lower edge only.
    for (auto it = std::upper_bound(hits.begin(), hits.end(), a); it != hits.end(); ++it)
      if (tests.edge_edge(a, *it)) {
        found.push_back({a, *it});
        if (stop_at_first) break;
      }
    if (stop_at_first && !found.empty()) break;
  }
  result.edge_edge = to_matrix(found);
  return result;
}

}  // namespace

ContactCandidates find_contact_candidates(const ContactProxy& proxy,
                                          const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                          const ContactCandidateOptions& options) {
  validate(proxy, positions, options, "find_contact_candidates");
  return hash_search(proxy, positions, options, false);
}

ContactCandidates find_contact_candidates_brute_force(
    const ContactProxy& proxy, const Eigen::Ref<const Eigen::MatrixX3d>& positions,
    const ContactCandidateOptions& options) {
  validate(proxy, positions, options, "find_contact_candidates_brute_force");
  const PairTests tests(proxy, positions, options);
  ContactCandidates result;
  std::vector<std::array<int, 2>> found;
  const auto V = static_cast<int>(proxy.num_vertices()),
             T = static_cast<int>(proxy.triangles.rows()), E = static_cast<int>(proxy.edges.rows());
  for (int p = 0; p < V; ++p)
    for (int t = 0; t < T; ++t)
      if (tests.vertex_triangle(p, t)) found.push_back({p, t});
  result.vertex_triangle = to_matrix(found);
  found.clear();
  for (int a = 0; a < E; ++a)
    for (int b = a + 1; b < E; ++b)
      if (tests.edge_edge(a, b)) found.push_back({a, b});
  result.edge_edge = to_matrix(found);
  result.pairs_examined =
      static_cast<Eigen::Index>(V) * T + static_cast<Eigen::Index>(E) * (E - 1) / 2;
  return result;
}

bool has_contact_candidates(const ContactProxy& proxy,
                            const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                            const ContactCandidateOptions& options) {
  validate(proxy, positions, options, "has_contact_candidates");
  return !hash_search(proxy, positions, options, true).empty();
}

}  // namespace growshell
