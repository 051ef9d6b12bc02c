#include "libshell/contact/contact_gap_constraints.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

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
  vertex_triangle_count_ = pairs.vertex_triangle.rows();
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
    pairs_.push_back(pair);
  }
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

  // ---- stencils: union of the map's columns in the rows of the pair's proxy vertices ----
  dof_begin_.assign(1, 0);
  std::vector<int> stencil;
  for (const Pair& pair : pairs_) {
    stencil.clear();
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
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(map_,
                                                                          3 * pair.vertices(i) + c);
           it; ++it)
        gradient[it.col()] += it.value() * local_gradient(3 * i + c);
}

void ContactGapConstraints::add_pair_hessian(Eigen::Index k, const Matrix12d& local_hessian,
                                             Eigen::SparseMatrix<double>& hessian_upper) const {
  check_pair_index(k, "add_pair_hessian");
  const Eigen::Matrix<double, 12, Eigen::Dynamic> J = pair_map(k);
  const Eigen::MatrixXd block = J.transpose() * (local_hessian * J);
  const std::span<const int> dofs = pair_dofs(k);
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
    // Row k = J_k^T (dc/dy), scattered straight from the map's rows into the stored row
    // (whose columns are pair_dofs(k), sorted), without forming J_k.
    const Vector12d local = g.mollifier * D.gradient + g.gap * D.mollifier_gradient;
    const Pair& pair = pairs_[static_cast<std::size_t>(k)];
    const int* dofs = dofs_.data() + dof_begin_[static_cast<std::size_t>(k)];
    const int* dofs_end = dofs_.data() + dof_begin_[static_cast<std::size_t>(k) + 1];
    double* out = jacobian->valuePtr() + dof_begin_[static_cast<std::size_t>(k)];
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
    // c = m (d - offset): product rule; m = 1 with zero derivatives when not mollified.
    const Vector12d& gd = D.gradient;
    const Vector12d& gm = D.mollifier_gradient;
    const Matrix12d local = w * (g.mollifier * D.hessian + gm * gd.transpose() +
                                 gd * gm.transpose() + g.gap * D.mollifier_hessian);
    add_pair_hessian(k, local, hessian_upper);
  }
}

}  // namespace growshell
