#include "libshell/contact/contact_gap_constraints.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace growshell {

namespace {

[[noreturn]] void throw_invalid(const std::string& message) {
  throw std::invalid_argument("ContactGapConstraints: " + message);
}

std::string describe_pair(ContactPairType type, int first, int second) {
  std::ostringstream s;
  if (type == ContactPairType::VertexTriangle)
    s << "(proxy vertex " << first << ", proxy triangle " << second << ")";
  else
    s << "(proxy edge " << first << ", proxy edge " << second << ")";
  return s.str();
}

/// Mean length (m) of the proxy's reference edges; triangle edges if the edge list is empty.
double mean_reference_edge_length(const ContactProxy& proxy) {
  const Eigen::MatrixX3d& X = proxy.reference_positions;
  const auto length = [&](int a, int b) {
    if (a < 0 || b < 0 || a >= X.rows() || b >= X.rows())
      throw_invalid("proxy edge (" + std::to_string(a) + ", " + std::to_string(b) +
                    ") has a vertex outside [0, " + std::to_string(X.rows()) + ")");
    return (X.row(a) - X.row(b)).norm();
  };
  double sum = 0.0;
  Eigen::Index n = 0;
  for (Eigen::Index e = 0; e < proxy.edges.rows(); ++e, ++n)
    sum += length(proxy.edges(e, 0), proxy.edges(e, 1));
  if (n == 0) {
    for (Eigen::Index t = 0; t < proxy.triangles.rows(); ++t)
      for (int i = 0; i < 3; ++i, ++n)
        sum += length(proxy.triangles(t, i), proxy.triangles(t, (i + 1) % 3));
  }
  return n > 0 ? sum / static_cast<double>(n) : 0.0;
}

/// Throws unless the limit surface fits the proxy and the pairs are vertex-triangle pairs.
void check_limit_surface(const LimitSurfaceContact& limit, const ContactProxy& proxy,
                         const ContactCandidates& pairs) {
  if (pairs.edge_edge.rows() > 0)
    throw_invalid(std::to_string(pairs.edge_edge.rows()) +
                  " edge-edge pairs: on the limit surface only vertex-triangle pairs are "
                  "measured (select no edge-edge pairs)");
  if (proxy.triangle_element.size() != proxy.triangles.rows())
    throw_invalid("the proxy has no element for each triangle (triangle_element)");
  const auto elements = limit.patches.patch.size();
  if (limit.neighbourhoods.size() != elements)
    throw_invalid("the limit surface has " + std::to_string(limit.neighbourhoods.size()) +
                  " neighbourhoods for " + std::to_string(elements) + " elements");
  const Eigen::Index n = proxy.segments_per_edge;
  if (n < 1 || proxy.triangles.rows() != static_cast<Eigen::Index>(elements) * n * n)
    throw_invalid("the proxy has " + std::to_string(proxy.triangles.rows()) + " triangles, not " +
                  std::to_string(n) + "^2 for each of the limit surface's " +
                  std::to_string(elements) + " elements (another model's?)");
  if (proxy.triangle_element.size() > 0 && proxy.triangle_element.minCoeff() < 0)
    throw_invalid("the proxy names a negative element");
  if (proxy.triangle_element.size() > 0 &&
      proxy.triangle_element.maxCoeff() >= static_cast<int>(elements))
    throw_invalid("the proxy names element " + std::to_string(proxy.triangle_element.maxCoeff()) +
                  ", outside the limit surface's " + std::to_string(elements) + " elements");
}

/// The elements around `element` against which proxy vertex p is measured: its neighbourhood
/// less the elements with a proxy vertex within the exclusion radius of p in the reference
/// (`element` itself always stays).
std::vector<int> surface_candidates(const LimitSurfaceContact& limit, const ContactProxy& proxy,
                                    int p, int element) {
  const Eigen::Index n = proxy.segments_per_edge;
  const Eigen::RowVector3d at = proxy.reference_positions.row(p);
  std::vector<int> candidates;
  for (int e : limit.neighbourhoods[static_cast<std::size_t>(element)]) {
    bool near = false;
    for (Eigen::Index row = e * n * n; row < (e + 1) * n * n && !near; ++row)
      for (int i = 0; i < 3; ++i)
        near = near || (proxy.reference_positions.row(proxy.triangles(row, i)) - at).norm() <
                           limit.exclusion_radius;
    if (!near || e == element) candidates.push_back(e);
  }
  return candidates;
}

}  // namespace

const char* to_string(ContactPairType type) {
  switch (type) {
    case ContactPairType::VertexTriangle:
      return "VertexTriangle";
    case ContactPairType::EdgeEdge:
      return "EdgeEdge";
  }
  return "unknown";
}

ContactGapConstraints::ContactGapConstraints(const ContactProxy& proxy,
                                             const ContactCandidates& pairs, double offset,
                                             Eigen::Index dimension, ContactGapOptions options)
    : dimension_(dimension), offset_(offset), options_(options) {
  if (!std::isfinite(offset) || offset < 0.0)
    throw_invalid("offset " + std::to_string(offset) + " must be finite and >= 0");
  const Eigen::Index num_vertices = proxy.reference_positions.rows();
  if (proxy.map.rows() != 3 * num_vertices) {
    std::ostringstream s;
    s << "proxy map has " << proxy.map.rows() << " rows, expected 3 x " << num_vertices
      << " proxy vertices (rows of reference_positions)";
    throw_invalid(s.str());
  }
  if (dimension < proxy.map.cols()) {
    std::ostringstream s;
    s << "dimension " << dimension << " is below the proxy map's " << proxy.map.cols()
      << " columns (the control dofs)";
    throw_invalid(s.str());
  }
  map_ = proxy.map;
  map_.makeCompressed();
  triangles_ = proxy.triangles;
  segments_per_edge_ = proxy.segments_per_edge;
  const LimitSurfaceContact* limit = options_.limit_surface.get();
  if (limit != nullptr) check_limit_surface(*limit, proxy, pairs);

  const double mean_edge = mean_reference_edge_length(proxy);
  const Eigen::Index num_pairs = pairs.size();
  if (num_pairs > 0 && !(mean_edge > 0.0 && std::isfinite(mean_edge)))
    throw_invalid("the proxy's reference edges have no positive mean length");
  distance_floor_ = kContactDistanceFloor * mean_edge;

  // ---- pairs ----
  const Eigen::Index num_triangles = proxy.triangles.rows();
  const Eigen::Index num_edges = proxy.edges.rows();
  const auto check_vertex = [&](int v, const std::string& where) {
    if (v < 0 || v >= num_vertices)
      throw_invalid(where + ": proxy vertex " + std::to_string(v) + " outside [0, " +
                    std::to_string(num_vertices) + ")");
  };
  pairs_.reserve(static_cast<std::size_t>(num_pairs));
  std::unordered_map<int, std::vector<int>> kept_elements;  // limit surface: per proxy vertex
  for (Eigen::Index r = 0; r < pairs.vertex_triangle.rows(); ++r) {
    const int p = pairs.vertex_triangle(r, 0);
    const int t = pairs.vertex_triangle(r, 1);
    const std::string where = "vertex_triangle row " + std::to_string(r);
    check_vertex(p, where);
    if (t < 0 || t >= num_triangles)
      throw_invalid(where + ": proxy triangle " + std::to_string(t) + " outside [0, " +
                    std::to_string(num_triangles) + ")");
    Pair pair;
    pair.type = ContactPairType::VertexTriangle;
    pair.first = p;
    pair.second = t;
    pair.vertices << p, proxy.triangles(t, 0), proxy.triangles(t, 1), proxy.triangles(t, 2);
    for (int i = 1; i < 4; ++i) {
      check_vertex(pair.vertices(i), where + " (corner of triangle " + std::to_string(t) + ")");
      if (pair.vertices(i) == p)
        throw_invalid(where + ": proxy vertex " + std::to_string(p) +
                      " is a corner of proxy triangle " + std::to_string(t));
    }
    if (limit != nullptr) {
      pair.element = proxy.triangle_element(t);
      // A pair of the same vertex whose element shares a corner with this one's measures the
      // same part of the surface: keep the first.
      const std::vector<int>& around =
          limit->neighbourhoods[static_cast<std::size_t>(pair.element)];
      std::vector<int>& kept = kept_elements[p];
      if (std::any_of(kept.begin(), kept.end(),
                      [&](int e) { return std::binary_search(around.begin(), around.end(), e); }))
        continue;
      kept.push_back(pair.element);
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(map_, 3 * p); it; ++it) {
        pair.point.vertex.push_back(static_cast<int>(it.col() / 3));
        pair.point.weight.push_back(it.value());
      }
      pair.candidates = surface_candidates(*limit, proxy, p, pair.element);
    }
    pairs_.push_back(pair);
  }
  vertex_triangle_count_ = static_cast<Eigen::Index>(pairs_.size());
  for (Eigen::Index r = 0; r < pairs.edge_edge.rows(); ++r) {
    const int a = pairs.edge_edge(r, 0);
    const int b = pairs.edge_edge(r, 1);
    const std::string where = "edge_edge row " + std::to_string(r);
    for (int e : {a, b})
      if (e < 0 || e >= num_edges)
        throw_invalid(where + ": proxy edge " + std::to_string(e) + " outside [0, " +
                      std::to_string(num_edges) + ")");
    Pair pair;
    pair.type = ContactPairType::EdgeEdge;
    pair.first = a;
    pair.second = b;
    pair.vertices << proxy.edges(a, 0), proxy.edges(a, 1), proxy.edges(b, 0), proxy.edges(b, 1);
    for (int i = 0; i < 4; ++i) check_vertex(pair.vertices(i), where);
    for (int i = 0; i < 2; ++i)
      for (int j = 2; j < 4; ++j)
        if (pair.vertices(i) == pair.vertices(j))
          throw_invalid(where + ": proxy edges " + std::to_string(a) + " and " + std::to_string(b) +
                        " share proxy vertex " + std::to_string(pair.vertices(i)));
    if (options_.mollify_edge_edge) {
      const Eigen::MatrixX3d& X = proxy.reference_positions;
      const Eigen::Vector3d p0 = X.row(pair.vertices(0)).transpose();
      const Eigen::Vector3d p1 = X.row(pair.vertices(1)).transpose();
      const Eigen::Vector3d q0 = X.row(pair.vertices(2)).transpose();
      const Eigen::Vector3d q1 = X.row(pair.vertices(3)).transpose();
      pair.mollifier_threshold = edge_edge_mollifier_threshold(p0, p1, q0, q1);
      if (!(pair.mollifier_threshold > 0.0))
        throw_invalid(where + ": a rest edge of " +
                      describe_pair(pair.type, pair.first, pair.second) +
                      " has zero length, so its mollifier threshold is zero");
    }
    pairs_.push_back(pair);
  }

  build_patterns();
}

void ContactGapConstraints::build_patterns() {
  const LimitSurfaceContact* limit = options_.limit_surface.get();
  // ---- stencils: union of the map's columns in the rows of the pair's proxy vertices ----
  dof_begin_.assign(1, 0);
  std::vector<int> stencil;
  for (const Pair& pair : pairs_) {
    stencil.clear();
    if (pair.element >= 0) {
      // The proxy vertex's dofs and those of every candidate element.
      for (int v : pair.point.vertex)
        for (int c = 0; c < 3; ++c) stencil.push_back(3 * v + c);
      for (int e : pair.candidates)
        for (int v : limit->patches.patch[static_cast<std::size_t>(e)].control)
          for (int c = 0; c < 3; ++c) stencil.push_back(3 * v + c);
      std::sort(stencil.begin(), stencil.end());
      stencil.erase(std::unique(stencil.begin(), stencil.end()), stencil.end());
      if (!stencil.empty() && stencil.back() >= map_.cols())
        throw_invalid("the limit surface's control points exceed the proxy map's " +
                      std::to_string(map_.cols()) + " columns");
      dofs_.insert(dofs_.end(), stencil.begin(), stencil.end());
      dof_begin_.push_back(static_cast<Eigen::Index>(dofs_.size()));
      continue;
    }
    for (int i = 0; i < 4; ++i)
      for (int c = 0; c < 3; ++c)
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(
                 map_, 3 * pair.vertices(i) + c);
             it; ++it)
          stencil.push_back(static_cast<int>(it.col()));
    std::sort(stencil.begin(), stencil.end());
    stencil.erase(std::unique(stencil.begin(), stencil.end()), stencil.end());
    dofs_.insert(dofs_.end(), stencil.begin(), stencil.end());
    dof_begin_.push_back(static_cast<Eigen::Index>(dofs_.size()));
  }

  // Jacobian pattern: row k = stencil of pair k (already sorted, as row-major storage wants).
  {
    const std::vector<int> outer(dof_begin_.begin(), dof_begin_.end());
    const std::vector<double> zeros(dofs_.size(), 0.0);
    jacobian_pattern_ = Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor>>(
        count(), dimension_, static_cast<Eigen::Index>(dofs_.size()), outer.data(), dofs_.data(),
        zeros.data());
  }

  // Hessian pattern, column by column: rows <= j of every stencil containing j. The inverse
  // index keeps memory at the size of the result (not pairs x stencil^2 triplets).
  {
    std::vector<int> pairs_of_dof_begin(static_cast<std::size_t>(dimension_) + 1, 0);
    for (int dof : dofs_) ++pairs_of_dof_begin[static_cast<std::size_t>(dof) + 1];
    for (std::size_t j = 0; j < static_cast<std::size_t>(dimension_); ++j)
      pairs_of_dof_begin[j + 1] += pairs_of_dof_begin[j];
    std::vector<int> pairs_of_dof(dofs_.size());
    std::vector<int> fill(pairs_of_dof_begin.begin(), pairs_of_dof_begin.end() - 1);
    for (std::size_t k = 0; k < pairs_.size(); ++k)
      for (Eigen::Index i = dof_begin_[k]; i < dof_begin_[k + 1]; ++i)
        pairs_of_dof[static_cast<std::size_t>(
            fill[static_cast<std::size_t>(dofs_[static_cast<std::size_t>(i)])]++)] =
            static_cast<int>(k);

    std::vector<int> outer(1, 0);
    std::vector<int> inner;
    std::vector<int> marker(static_cast<std::size_t>(dimension_), -1);
    std::vector<int> rows;
    for (int j = 0; j < static_cast<int>(dimension_); ++j) {
      rows.clear();
      for (int q = pairs_of_dof_begin[static_cast<std::size_t>(j)];
           q < pairs_of_dof_begin[static_cast<std::size_t>(j) + 1]; ++q) {
        const std::size_t k = static_cast<std::size_t>(pairs_of_dof[static_cast<std::size_t>(q)]);
        for (Eigen::Index i = dof_begin_[k]; i < dof_begin_[k + 1]; ++i) {
          const int r = dofs_[static_cast<std::size_t>(i)];
          if (r > j) break;
          if (marker[static_cast<std::size_t>(r)] != j) {
            marker[static_cast<std::size_t>(r)] = j;
            rows.push_back(r);
          }
        }
      }
      std::sort(rows.begin(), rows.end());
      inner.insert(inner.end(), rows.begin(), rows.end());
      outer.push_back(static_cast<int>(inner.size()));
    }
    const std::vector<double> zeros(inner.size(), 0.0);
    hessian_pattern_ = Eigen::Map<const Eigen::SparseMatrix<double>>(
        dimension_, dimension_, static_cast<Eigen::Index>(inner.size()), outer.data(), inner.data(),
        zeros.data());
  }
}

void ContactGapConstraints::check_pair_index(Eigen::Index k, const char* who) const {
  if (k < 0 || k >= count()) {
    std::ostringstream s;
    s << who << ": pair index " << k << " outside [0, " << count() << ")";
    throw_invalid(s.str());
  }
}

void ContactGapConstraints::check_x(const Eigen::Ref<const Eigen::VectorXd>& x,
                                    const char* who) const {
  if (x.size() != dimension_) {
    std::ostringstream s;
    s << who << ": x has " << x.size() << " entries, expected dimension " << dimension_;
    throw_invalid(s.str());
  }
}

void ContactGapConstraints::check_hessian_structure(
    const Eigen::SparseMatrix<double>& hessian_upper, const char* who) const {
  bool ok = hessian_upper.rows() == dimension_ && hessian_upper.cols() == dimension_ &&
            hessian_upper.isCompressed() && hessian_upper.nonZeros() == hessian_pattern_.nonZeros();
  for (Eigen::Index j = 0; ok && j <= dimension_; ++j)
    ok = hessian_upper.outerIndexPtr()[j] == hessian_pattern_.outerIndexPtr()[j];
  if (!ok) {
    std::ostringstream s;
    s << who << ": the Hessian matrix (" << hessian_upper.rows() << " x " << hessian_upper.cols()
      << ", " << hessian_upper.nonZeros() << " entries) does not carry hessian_pattern() ("
      << dimension_ << " x " << dimension_ << ", " << hessian_pattern_.nonZeros()
      << " entries, compressed)";
    throw_invalid(s.str());
  }
}

ContactPairType ContactGapConstraints::pair_type(Eigen::Index k) const {
  check_pair_index(k, "pair_type");
  return pairs_[static_cast<std::size_t>(k)].type;
}

std::span<const int> ContactGapConstraints::pair_surface_elements(Eigen::Index k) const {
  check_pair_index(k, "pair_surface_elements");
  const std::vector<int>& elements = pairs_[static_cast<std::size_t>(k)].candidates;
  return std::span<const int>(elements.data(), elements.size());
}

std::span<const int> ContactGapConstraints::pair_dofs(Eigen::Index k) const {
  check_pair_index(k, "pair_dofs");
  const auto begin = static_cast<std::size_t>(dof_begin_[static_cast<std::size_t>(k)]);
  const auto end = static_cast<std::size_t>(dof_begin_[static_cast<std::size_t>(k) + 1]);
  return std::span<const int>(dofs_.data() + begin, end - begin);
}

Eigen::Matrix<double, 3, 4> ContactGapConstraints::pair_positions(
    const Eigen::Ref<const Eigen::VectorXd>& x, const Pair& pair) const {
  Eigen::Matrix<double, 3, 4> y;
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c) {
      double sum = 0.0;
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(map_,
                                                                          3 * pair.vertices(i) + c);
           it; ++it)
        sum += it.value() * x[it.col()];
      y(c, i) = sum;
    }
  return y;
}

Eigen::Matrix<double, 12, Eigen::Dynamic> ContactGapConstraints::pair_map(Eigen::Index k) const {
  const Pair& pair = pairs_[static_cast<std::size_t>(k)];
  const int* begin = dofs_.data() + dof_begin_[static_cast<std::size_t>(k)];
  const int* end = dofs_.data() + dof_begin_[static_cast<std::size_t>(k) + 1];
  Eigen::Matrix<double, 12, Eigen::Dynamic> J =
      Eigen::Matrix<double, 12, Eigen::Dynamic>::Zero(12, end - begin);
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(map_,
                                                                          3 * pair.vertices(i) + c);
           it; ++it) {
        const int* where = std::lower_bound(begin, end, static_cast<int>(it.col()));
        J(3 * i + c, where - begin) += it.value();
      }
  return J;
}

ContactPairDistance ContactGapConstraints::compute(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                   Eigen::Index k, bool with_gradient,
                                                   bool with_hessian) const {
  const Pair& pair = pairs_[static_cast<std::size_t>(k)];
  if (pair.element >= 0) return compute_on_limit_surface(x, k, with_gradient, with_hessian);
  const Eigen::Matrix<double, 3, 4> y = pair_positions(x, pair);
  ContactPairDistance out;
  ContactPairGeometry& g = out.geometry;
  g.type = pair.type;
  g.first = pair.first;
  g.second = pair.second;
  g.vertices = pair.vertices;
  with_gradient = with_gradient || with_hessian;
  try {
    ValueGradientHessian<12> squared;
    Eigen::Vector3d fallback_normal = Eigen::Vector3d::Zero();
    if (pair.type == ContactPairType::VertexTriangle) {
      const PointTriangleResult r = point_triangle_closest(y.col(0), y.col(1), y.col(2), y.col(3));
      g.point_triangle_region = r.region;
      g.distance = std::sqrt(r.distance_squared);
      g.closest_point_first = y.col(0);
      g.closest_point_second = r.closest_point;
      g.vertex_weights << 1.0, -r.barycentric(0), -r.barycentric(1), -r.barycentric(2);
      if (with_gradient)
        squared = point_triangle_distance_squared_derivatives(y.col(0), y.col(1), y.col(2),
                                                              y.col(3), r.region);
      fallback_normal = (y.col(2) - y.col(1)).cross(y.col(3) - y.col(1)).normalized();
    } else {
      const EdgeEdgeResult r = edge_edge_closest(y.col(0), y.col(1), y.col(2), y.col(3));
      g.edge_edge_region = r.region;
      g.distance = std::sqrt(r.distance_squared);
      g.closest_point_first = r.closest_point_p;
      g.closest_point_second = r.closest_point_q;
      g.vertex_weights << 1.0 - r.s, r.s, -(1.0 - r.t), -r.t;
      if (with_gradient)
        squared = edge_edge_distance_squared_derivatives(y.col(0), y.col(1), y.col(2), y.col(3),
                                                         r.region);
      const Eigen::Vector3d n = (y.col(1) - y.col(0)).cross(y.col(3) - y.col(2));
      if (n.squaredNorm() > 0.0) fallback_normal = n.normalized();
      if (pair.mollifier_threshold > 0.0) {
        const double eps = pair.mollifier_threshold;
        g.mollifier = edge_edge_mollifier(y.col(0), y.col(1), y.col(2), y.col(3), eps);
        // The mollifier is exactly 1 (with zero derivatives) iff c >= eps_x.
        if (with_gradient && g.mollifier < 1.0)
          out.mollifier_gradient =
              edge_edge_mollifier_gradient(y.col(0), y.col(1), y.col(2), y.col(3), eps);
        if (with_hessian && g.mollifier < 1.0)
          out.mollifier_hessian =
              edge_edge_mollifier_hessian(y.col(0), y.col(1), y.col(2), y.col(3), eps);
      }
    }
    g.gap = g.distance - offset_;
    g.normal = g.distance > distance_floor_
                   ? Eigen::Vector3d((g.closest_point_first - g.closest_point_second) / g.distance)
                   : fallback_normal;
    if (with_gradient) {
      // Chain rule d = sqrt(s); the floor keeps 0/0 out at d = 0 (see the file comment).
      const double d = std::max(g.distance, distance_floor_);
      out.gradient = squared.gradient / (2.0 * d);
      if (with_hessian)
        out.hessian = squared.hessian / (2.0 * d) -
                      squared.gradient * squared.gradient.transpose() / (4.0 * d * d * d);
    }
  } catch (const std::invalid_argument& e) {
    std::ostringstream s;
    s << "contact pair " << k << " " << describe_pair(pair.type, pair.first, pair.second) << ": "
      << e.what();
    throw_invalid(s.str());
  }
  return out;
}

ContactPairDistance ContactGapConstraints::compute_on_limit_surface(
    const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Index k, bool with_gradient,
    bool with_hessian) const {
  const Pair& pair = pairs_[static_cast<std::size_t>(k)];
  const LimitSurfaceContact& limit = *options_.limit_surface;
  ContactPairDistance out;
  ContactPairGeometry& g = out.geometry;
  g.type = pair.type;
  g.first = pair.first;
  LimitSurfaceDistance d;
  try {
    d = limit_surface_distance(control_point_rows(x.head(map_.cols())), limit.patches, pair.point,
                               pair.candidates, with_hessian);
  } catch (const std::exception& e) {
    std::ostringstream s;
    s << "contact pair " << k << " " << describe_pair(pair.type, pair.first, pair.second)
      << " on the limit surface: " << e.what();
    throw_invalid(s.str());
  }
  // The foot's proxy triangle and its weights there: where the contact force acts on the proxy.
  const ProxyTriangleLocation foot =
      proxy_triangle_at(segments_per_edge_, triangles_.rows(), d.element, d.parameter);
  g.second = foot.triangle;
  g.vertices << pair.first, triangles_(foot.triangle, 0), triangles_(foot.triangle, 1),
      triangles_(foot.triangle, 2);
  g.vertex_weights << 1.0, -foot.barycentric(0), -foot.barycentric(1), -foot.barycentric(2);
  g.distance = d.distance;
  g.gap = d.distance - offset_;
  g.closest_point_first = d.point;
  g.closest_point_second = d.closest;
  g.normal = (d.point - d.closest) / d.distance;
  if (!(with_gradient || with_hessian)) return out;
  // From the distance's vertex list to the pair's dofs (sorted, a superset).
  out.on_pair_dofs = true;
  const std::span<const int> dofs = pair_dofs(k);
  std::vector<Eigen::Index> at(3 * d.vertices.size());
  for (std::size_t j = 0; j < d.vertices.size(); ++j)
    for (int c = 0; c < 3; ++c) {
      const int dof = 3 * d.vertices[j] + c;
      at[3 * j + static_cast<std::size_t>(c)] =
          std::lower_bound(dofs.begin(), dofs.end(), dof) - dofs.begin();
    }
  const auto m = static_cast<Eigen::Index>(dofs.size());
  out.dof_gradient = Eigen::VectorXd::Zero(m);
  for (std::size_t a = 0; a < at.size(); ++a)
    out.dof_gradient[at[a]] += d.gradient[static_cast<Eigen::Index>(a)];
  if (with_hessian) {
    out.dof_hessian = Eigen::MatrixXd::Zero(m, m);
    for (std::size_t b = 0; b < at.size(); ++b)
      for (std::size_t a = 0; a < at.size(); ++a)
        out.dof_hessian(at[a], at[b]) +=
            d.hessian(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
  }
  return out;
}

ContactPairGeometry ContactGapConstraints::pair_geometry(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                         Eigen::Index k) const {
  check_pair_index(k, "pair_geometry");
  check_x(x, "pair_geometry");
  return compute(x, k, false, false).geometry;
}

ContactPairDistance ContactGapConstraints::pair_distance(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                         Eigen::Index k, bool with_hessian) const {
  check_pair_index(k, "pair_distance");
  check_x(x, "pair_distance");
  return compute(x, k, true, with_hessian);
}

void ContactGapConstraints::add_pair_gradient(Eigen::Index k, const Vector12d& local_gradient,
                                              Eigen::VectorXd& gradient) const {
  check_pair_index(k, "add_pair_gradient");
  if (gradient.size() != dimension_) {
    std::ostringstream s;
    s << "add_pair_gradient: gradient has " << gradient.size() << " entries, expected "
      << dimension_;
    throw_invalid(s.str());
  }
  const Pair& pair = pairs_[static_cast<std::size_t>(k)];
  if (pair.element >= 0)
    throw std::logic_error("add_pair_gradient: contact pair " + std::to_string(k) +
                           " is measured on the limit surface; its derivatives are in the dofs "
                           "(add_pair_dof_gradient)");
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(map_,
                                                                          3 * pair.vertices(i) + c);
           it; ++it)
        gradient[it.col()] += it.value() * local_gradient(3 * i + c);
}

void ContactGapConstraints::add_pair_dof_gradient(
    Eigen::Index k, const Eigen::Ref<const Eigen::VectorXd>& dof_gradient,
    Eigen::VectorXd& gradient) const {
  check_pair_index(k, "add_pair_dof_gradient");
  const std::span<const int> dofs = pair_dofs(k);
  if (gradient.size() != dimension_ ||
      dof_gradient.size() != static_cast<Eigen::Index>(dofs.size())) {
    std::ostringstream s;
    s << "add_pair_dof_gradient: " << dof_gradient.size() << " entries for the pair's "
      << dofs.size() << " dofs, into a gradient of " << gradient.size() << " (expected "
      << dimension_ << ")";
    throw_invalid(s.str());
  }
  for (std::size_t i = 0; i < dofs.size(); ++i)
    gradient[dofs[i]] += dof_gradient[static_cast<Eigen::Index>(i)];
}

void ContactGapConstraints::add_pair_hessian(Eigen::Index k, const Matrix12d& local_hessian,
                                             Eigen::SparseMatrix<double>& hessian_upper) const {
  check_pair_index(k, "add_pair_hessian");
  if (pairs_[static_cast<std::size_t>(k)].element >= 0)
    throw std::logic_error("add_pair_hessian: contact pair " + std::to_string(k) +
                           " is measured on the limit surface; its derivatives are in the dofs "
                           "(add_pair_dof_hessian)");
  const Eigen::Matrix<double, 12, Eigen::Dynamic> J = pair_map(k);
  add_pair_dof_hessian(k, J.transpose() * (local_hessian * J), hessian_upper);
}

void ContactGapConstraints::add_pair_dof_hessian(Eigen::Index k,
                                                 const Eigen::Ref<const Eigen::MatrixXd>& block,
                                                 Eigen::SparseMatrix<double>& hessian_upper) const {
  check_pair_index(k, "add_pair_dof_hessian");
  const std::span<const int> dofs = pair_dofs(k);
  if (block.rows() != static_cast<Eigen::Index>(dofs.size()) || block.cols() != block.rows()) {
    std::ostringstream s;
    s << "add_pair_dof_hessian: a " << block.rows() << " x " << block.cols()
      << " block for the pair's " << dofs.size() << " dofs";
    throw_invalid(s.str());
  }
  const int* inner = hessian_upper.innerIndexPtr();
  const int* outer = hessian_upper.outerIndexPtr();
  double* values = hessian_upper.valuePtr();
  for (std::size_t j = 0; j < dofs.size(); ++j) {
    const int column = dofs[j];
    const int* it = inner + outer[column];
    const int* end = inner + outer[column + 1];
    // Rows dofs[0..j] are ascending, so the search in the column only moves forward.
    for (std::size_t i = 0; i <= j; ++i) {
      it = std::lower_bound(it, end, dofs[i]);
      if (it == end || *it != dofs[i]) {
        std::ostringstream s;
        s << "add_pair_hessian: entry (" << dofs[i] << ", " << column << ") of contact pair " << k
          << " is not in the Hessian's pattern";
        throw_invalid(s.str());
      }
      values[it - inner] += block(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
    }
  }
}

void ContactGapConstraints::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                                     Eigen::VectorXd& values,
                                     Eigen::SparseMatrix<double, Eigen::RowMajor>* jacobian) {
  check_x(x, "evaluate");
  if (jacobian != nullptr) {
    bool ok = jacobian->rows() == count() && jacobian->cols() == dimension_ &&
              jacobian->isCompressed() &&
              jacobian->nonZeros() == static_cast<Eigen::Index>(dofs_.size());
    for (Eigen::Index k = 0; ok && k <= count(); ++k)
      ok = jacobian->outerIndexPtr()[k] == dof_begin_[static_cast<std::size_t>(k)];
    if (!ok) {
      std::ostringstream s;
      s << "evaluate: the Jacobian matrix (" << jacobian->rows() << " x " << jacobian->cols()
        << ", " << jacobian->nonZeros() << " entries) does not carry jacobian_pattern() ("
        << count() << " x " << dimension_ << ", " << dofs_.size() << " entries, compressed)";
      throw_invalid(s.str());
    }
  }
  values.resize(count());
  for (Eigen::Index k = 0; k < count(); ++k) {
    const ContactPairDistance D = compute(x, k, jacobian != nullptr, false);
    const ContactPairGeometry& g = D.geometry;
    values[k] = g.mollifier * g.gap;
    if (jacobian == nullptr) continue;
    const int* dofs = dofs_.data() + dof_begin_[static_cast<std::size_t>(k)];
    const int* dofs_end = dofs_.data() + dof_begin_[static_cast<std::size_t>(k) + 1];
    double* out = jacobian->valuePtr() + dof_begin_[static_cast<std::size_t>(k)];
    if (D.on_pair_dofs) {
      std::copy(D.dof_gradient.data(), D.dof_gradient.data() + (dofs_end - dofs), out);
      continue;
    }
    // Row k = J_k^T (dc/dy), scattered straight from the map's rows into the stored row
    // (whose columns are pair_dofs(k), sorted), without forming J_k.
    const Vector12d local = g.mollifier * D.gradient + g.gap * D.mollifier_gradient;
    const Pair& pair = pairs_[static_cast<std::size_t>(k)];
    std::fill(out, out + (dofs_end - dofs), 0.0);
    for (int i = 0; i < 4; ++i)
      for (int c = 0; c < 3; ++c)
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(
                 map_, 3 * pair.vertices(i) + c);
             it; ++it)
          out[std::lower_bound(dofs, dofs_end, static_cast<int>(it.col())) - dofs] +=
              it.value() * local(3 * i + c);
  }
}

void ContactGapConstraints::weighted_hessian(const Eigen::Ref<const Eigen::VectorXd>& x,
                                             const Eigen::Ref<const Eigen::VectorXd>& weights,
                                             Eigen::SparseMatrix<double>& hessian_upper) {
  check_x(x, "weighted_hessian");
  if (weights.size() != count()) {
    std::ostringstream s;
    s << "weighted_hessian: weights has " << weights.size() << " entries, expected count() "
      << count();
    throw_invalid(s.str());
  }
  check_hessian_structure(hessian_upper, "weighted_hessian");
  hessian_upper.coeffs().setZero();
  for (Eigen::Index k = 0; k < count(); ++k) {
    const double w = weights[k];
    if (w == 0.0) continue;
    const ContactPairDistance D = compute(x, k, true, true);
    const ContactPairGeometry& g = D.geometry;
    if (D.on_pair_dofs) {
      add_pair_dof_hessian(k, w * D.dof_hessian, hessian_upper);
      continue;
    }
    // c = m (d - offset): product rule; m = 1 with zero derivatives when not mollified.
    const Vector12d& gd = D.gradient;
    const Vector12d& gm = D.mollifier_gradient;
    const Matrix12d local = w * (g.mollifier * D.hessian + gm * gd.transpose() +
                                 gd * gm.transpose() + g.gap * D.mollifier_hessian);
    add_pair_hessian(k, local, hessian_upper);
  }
}

}  // namespace growshell
