#include "libshell/contact/contact_proxy.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "libshell/subdivision/closest_limit_point.hpp"
#include "libshell/subdivision/loop_basis.hpp"
#include "libshell/subdivision/loop_patch.hpp"

namespace growshell {
namespace {

/// Largest accepted segments_per_edge: (n + 1)(n + 2) / 2 lattice points per element and
/// 3 * proxy vertices must stay far below the int range for realistic sheets.
constexpr int kMaxSegmentsPerEdge = 1000;

/// Index of lattice point (i, j), i + j <= n, in the order i outer, j inner.
int lattice_index(int n, int i, int j) { return i * (n + 1) - i * (i - 1) / 2 + j; }

int lattice_size(int n) { return (n + 1) * (n + 2) / 2; }

/// The element corners in the parameterisation of loop_basis.hpp.
struct Corners {
  int a, b, c;  // at (v, w) = (0, 0), (1, 0), (0, 1)
};

Corners element_corners(const LoopPatch& patch) {
  const auto corner = [&](int k) {
    return patch.control[static_cast<std::size_t>(patch.corners[static_cast<std::size_t>(k)])];
  };
  return {corner(0), corner(1), corner(2)};
}

void check_segments(int segments_per_edge) {
  if (segments_per_edge < 1 || segments_per_edge > kMaxSegmentsPerEdge) {
    std::ostringstream msg;
    msg << "make_contact_proxy: segments_per_edge must be in [1, " << kMaxSegmentsPerEdge
        << "], got " << segments_per_edge;
    throw std::invalid_argument(msg.str());
  }
}

}  // namespace

ContactProxy make_contact_proxy(const ShellModel& model, int segments_per_edge) {
  check_segments(segments_per_edge);
  const int n = segments_per_edge;
  const int num_mesh_vertices = static_cast<int>(model.dimension() / 3);
  const auto num_elements = static_cast<int>(model.num_elements());

  // Basis weights of every lattice point are the same for all regular elements; an element
  // with an extraordinary corner has its own.
  const int lattice = lattice_size(n);
  std::vector<Eigen::VectorXd> regular_weights(static_cast<std::size_t>(lattice));
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n - i; ++j)
      regular_weights[static_cast<std::size_t>(lattice_index(n, i, j))] =
          evaluate_regular_loop_basis(static_cast<double>(i) / n, static_cast<double>(j) / n).value;
  std::vector<Eigen::VectorXd> irregular_weights(static_cast<std::size_t>(lattice));

  ContactProxy proxy;
  proxy.segments_per_edge = n;
  std::vector<int> vertex_proxy(static_cast<std::size_t>(num_mesh_vertices), -1);
  // Per mesh edge (lower, higher vertex): the proxy indices of its n - 1 inner points,
  // counted in steps from the lower vertex. Only looked up, never iterated: deterministic.
  std::unordered_map<std::uint64_t, std::vector<int>> edge_proxy;
  std::vector<int> element_of;
  std::vector<std::pair<double, double>> parameter_of;
  std::vector<Eigen::Triplet<double>> triplets;
  const auto expected = static_cast<std::size_t>(num_elements) * static_cast<std::size_t>(n) *
                            static_cast<std::size_t>(n) / 2 +
                        static_cast<std::size_t>(num_elements);
  element_of.reserve(expected);
  parameter_of.reserve(expected);
  triplets.reserve(36 * expected);
  proxy.triangles.resize(static_cast<Eigen::Index>(num_elements) * n * n, 3);
  proxy.triangle_element.resize(proxy.triangles.rows());

  std::vector<int> local(static_cast<std::size_t>(lattice));
  Eigen::Index triangle = 0;
  for (int e = 0; e < num_elements; ++e) {
    const LoopPatch& patch = model.patches().patch[static_cast<std::size_t>(e)];
    const auto& control = patch.control;
    const Corners k = element_corners(patch);
    if (!patch.is_regular())
      for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n - i; ++j)
          irregular_weights[static_cast<std::size_t>(lattice_index(n, i, j))] =
              evaluate_patch_basis(patch, static_cast<double>(i) / n, static_cast<double>(j) / n)
                  .value;
    const auto& weights = patch.is_regular() ? regular_weights : irregular_weights;
    // The slot of an edge point reached s steps from corner p along the edge p-q.
    const auto edge_slot = [&](int p, int q, int s) -> int& {
      const auto lo = static_cast<std::uint64_t>(std::min(p, q)),
                 hi = static_cast<std::uint64_t>(std::max(p, q));
      auto& slots = edge_proxy[lo * static_cast<std::uint64_t>(num_mesh_vertices) + hi];
      if (slots.empty()) slots.assign(static_cast<std::size_t>(n - 1), -1);
      return slots[static_cast<std::size_t>((p < q ? s : n - s) - 1)];
    };
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; j <= n - i; ++j) {
        int fresh = -1;
        int* shared = &fresh;
        if (i == 0 && j == 0)
          shared = &vertex_proxy[static_cast<std::size_t>(k.a)];
        else if (i == n)
          shared = &vertex_proxy[static_cast<std::size_t>(k.b)];
        else if (j == n)
          shared = &vertex_proxy[static_cast<std::size_t>(k.c)];
        else if (j == 0)
          shared = &edge_slot(k.a, k.b, i);
        else if (i == 0)
          shared = &edge_slot(k.a, k.c, j);
        else if (i + j == n)
          shared = &edge_slot(k.b, k.c, n - i);
        if (*shared < 0) {
          const int p = static_cast<int>(element_of.size());
          *shared = p;
          element_of.push_back(e);
          parameter_of.emplace_back(static_cast<double>(i) / n, static_cast<double>(j) / n);
          const auto& N = weights[static_cast<std::size_t>(lattice_index(n, i, j))];
          for (int node = 0; node < patch.size(); ++node) {
            // Some basis functions vanish exactly on the element's boundary (e.g. at corners);
            // dropping them keeps the map's pattern as small as the surface's true support.
            if (N(node) == 0.0) continue;
            for (int c = 0; c < 3; ++c)
              triplets.emplace_back(3 * p + c, 3 * control[static_cast<std::size_t>(node)] + c,
                                    N(node));
          }
        }
        local[static_cast<std::size_t>(lattice_index(n, i, j))] = *shared;
      }
    }
    const auto at = [&](int i, int j) {
      return local[static_cast<std::size_t>(lattice_index(n, i, j))];
    };
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n - i; ++j) {
        proxy.triangles.row(triangle) << at(i, j), at(i + 1, j), at(i, j + 1);
        proxy.triangle_element(triangle++) = e;
        if (i + j < n - 1) {
          proxy.triangles.row(triangle) << at(i + 1, j), at(i + 1, j + 1), at(i, j + 1);
          proxy.triangle_element(triangle++) = e;
        }
      }
    }
  }

  const auto num_proxy = static_cast<Eigen::Index>(element_of.size());
  proxy.map.resize(3 * num_proxy, model.dimension());
  proxy.map.setFromTriplets(triplets.begin(), triplets.end());
  proxy.map.makeCompressed();
  proxy.vertex_element = Eigen::Map<const Eigen::VectorXi>(element_of.data(), num_proxy);
  proxy.vertex_parameter.resize(num_proxy, 2);
  for (Eigen::Index p = 0; p < num_proxy; ++p)
    proxy.vertex_parameter.row(p) << parameter_of[static_cast<std::size_t>(p)].first,
        parameter_of[static_cast<std::size_t>(p)].second;

  std::vector<std::pair<int, int>> edges;
  edges.reserve(3 * static_cast<std::size_t>(proxy.triangles.rows()));
  for (Eigen::Index t = 0; t < proxy.triangles.rows(); ++t)
    for (int c = 0; c < 3; ++c) {
      const int p = proxy.triangles(t, c), q = proxy.triangles(t, (c + 1) % 3);
      edges.emplace_back(std::min(p, q), std::max(p, q));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  proxy.edges.resize(static_cast<Eigen::Index>(edges.size()), 2);
  for (std::size_t k = 0; k < edges.size(); ++k)
    proxy.edges.row(static_cast<Eigen::Index>(k)) << edges[k].first, edges[k].second;

  proxy.reference_positions = proxy_positions(proxy, model.reference_positions());
  return proxy;
}

Eigen::MatrixX3d proxy_positions(const ContactProxy& proxy,
                                 const Eigen::Ref<const Eigen::VectorXd>& x) {
  if (x.size() != proxy.map.cols()) {
    std::ostringstream msg;
    msg << "proxy_positions: x has " << x.size() << " entries, the proxy map expects "
        << proxy.map.cols();
    throw std::invalid_argument(msg.str());
  }
  const Eigen::VectorXd y = proxy.map * x;
  using RowMajorX3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
  return Eigen::Map<const RowMajorX3>(y.data(), y.size() / 3, 3);
}

ProxySag proxy_sag(const ShellModel& model, const ContactProxy& proxy,
                   const Eigen::Ref<const Eigen::VectorXd>& x) {
  if (x.size() != model.dimension()) {
    std::ostringstream msg;
    msg << "proxy_sag: x has " << x.size() << " entries, the model has dimension "
        << model.dimension();
    throw std::invalid_argument(msg.str());
  }
  const int n = proxy.segments_per_edge;
  if (proxy.map.cols() != model.dimension() || n < 1 ||
      proxy.triangles.rows() != model.num_elements() * static_cast<Eigen::Index>(n) * n) {
    std::ostringstream msg;
    msg << "proxy_sag: the proxy (" << proxy.map.cols() << " columns, " << proxy.triangles.rows()
        << " triangles, segments_per_edge " << n << ") was not made from this model (dimension "
        << model.dimension() << ", " << model.num_elements() << " elements)";
    throw std::invalid_argument(msg.str());
  }
  // Check points: every sub-edge midpoint and sub-triangle centroid. The offset y - x there is
  // X^T (mean of N(corners) - N(check)): one weight vector per check point, shared by all
  // regular elements (an element with an extraordinary corner has its own), like the tangents
  // X^T dN/dv, X^T dN/dw.
  struct CheckWeights {
    std::vector<Eigen::VectorXd> offset;
    std::vector<Eigen::MatrixX2d> first;
  };
  const auto check_weights = [n](const LoopPatch& patch) {
    CheckWeights w;
    const auto N = [&](double i, double j) { return evaluate_patch_basis(patch, i / n, j / n).value; };
    const auto add = [&](double i, double j, const Eigen::VectorXd& interpolated) {
      const PatchBasis b = evaluate_patch_basis(patch, i / n, j / n);
      w.offset.push_back(interpolated - b.value);
      w.first.push_back(b.first);
    };
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n - i; ++j) {
        const Eigen::VectorXd a = N(i, j), b = N(i + 1, j), c = N(i, j + 1);
        add(i + 0.5, j, 0.5 * (a + b));
        add(i, j + 0.5, 0.5 * (a + c));
        add(i + 0.5, j + 0.5, 0.5 * (b + c));
        add(i + 1.0 / 3.0, j + 1.0 / 3.0, (a + b + c) / 3.0);
        if (i + j < n - 1) add(i + 2.0 / 3.0, j + 2.0 / 3.0, (b + N(i + 1, j + 1) + c) / 3.0);
      }
    }
    return w;
  };
  LoopPatch regular;
  regular.control.assign(12, 0);
  const CheckWeights regular_weights = check_weights(regular);

  ProxySag sag;
  for (Eigen::Index e = 0; e < model.num_elements(); ++e) {
    const LoopPatch& patch = model.patches().patch[static_cast<std::size_t>(e)];
    const CheckWeights irregular_weights = patch.is_regular() ? CheckWeights{} : check_weights(patch);
    const CheckWeights& w = patch.is_regular() ? regular_weights : irregular_weights;
    Eigen::MatrixX3d X(patch.size(), 3);
    for (int node = 0; node < patch.size(); ++node)
      X.row(node) = x.segment<3>(3 * patch.control[static_cast<std::size_t>(node)]).transpose();
    for (std::size_t k = 0; k < w.offset.size(); ++k) {
      const Eigen::Vector3d delta = X.transpose() * w.offset[k];
      const Eigen::Matrix<double, 3, 2> tangents = X.transpose() * w.first[k];
      const Eigen::Vector3d normal = tangents.col(0).cross(tangents.col(1)).normalized();
      sag.normal = std::max(sag.normal, std::abs(normal.dot(delta)));
      sag.parametric = std::max(sag.parametric, delta.norm());
    }
  }
  return sag;
}

ProxyTriangleLocation proxy_triangle_at(const ContactProxy& proxy, int element,
                                        const Eigen::Ref<const Eigen::Vector2d>& parameter) {
  return proxy_triangle_at(proxy.segments_per_edge, proxy.triangles.rows(), element, parameter);
}

ProxyTriangleLocation proxy_triangle_at(int segments_per_edge, Eigen::Index triangles, int element,
                                        const Eigen::Ref<const Eigen::Vector2d>& parameter) {
  const int n = segments_per_edge;
  const Eigen::Index elements = n > 0 ? triangles / (static_cast<Eigen::Index>(n) * n) : 0;
  if (element < 0 || element >= elements)
    throw std::invalid_argument("proxy_triangle_at: element " + std::to_string(element) +
                                " is outside the proxy's " + std::to_string(elements) +
                                " elements");
  if (!parameter.allFinite())
    throw std::invalid_argument("proxy_triangle_at: the parameter is not finite");
  const Eigen::Vector2d vw = clamp_to_parameter_triangle(parameter);
  // Lattice coordinates: the point lies in cell (i, j), at (fs, ft) within it.
  const double s = n * vw.x();
  const double t = n * vw.y();
  const int i = std::min(static_cast<int>(std::floor(s)), n - 1);
  const int j = std::max(0, std::min(static_cast<int>(std::floor(t)), n - 1 - i));
  const double fs = s - i;
  const double ft = t - j;
  // Rows of the element's triangles before cell (i, j)'s "up" triangle (the order of
  // make_contact_proxy: i outer, j inner, each "up" triangle followed by its "down" one if
  // i + j < n - 1).
  int row = 0;
  for (int a = 0; a <= i; ++a)
    for (int b = 0; b <= n - 1 - a; ++b) {
      if (a == i && b == j) break;
      row += a + b < n - 1 ? 2 : 1;
    }
  ProxyTriangleLocation out;
  const Eigen::Index first = static_cast<Eigen::Index>(element) * n * n;
  // A cell on the diagonal (i + j = n - 1) has its "up" triangle only; a point there with
  // fs + ft above 1 by rounding lies on that triangle's far side.
  if (fs + ft <= 1.0 || i + j == n - 1) {
    out.triangle = static_cast<int>(first + row);
    out.barycentric << std::max(0.0, 1.0 - fs - ft), fs, ft;
    out.barycentric /= out.barycentric.sum();
  } else {
    out.triangle = static_cast<int>(first + row + 1);
    out.barycentric << 1.0 - ft, fs + ft - 1.0, 1.0 - fs;
  }
  return out;
}

}  // namespace growshell
