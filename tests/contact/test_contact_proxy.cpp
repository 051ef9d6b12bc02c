// The contact proxy: exact limit-surface points, a conforming refined mesh with the counted
// sizes, flatness of a flat sheet, and a sag that falls like 1 / n^2.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "libshell/contact/contact_proxy.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/subdivision/limit_surface.hpp"
#include "support/sheet_states.hpp"

namespace growshell {
namespace {

using test_support::map_reference;

/// Applies f to every control point of the reference (vertex-major flat vector).
/// Control points as one row per vertex, for evaluate_limit_surface.
Eigen::MatrixX3d as_rows(const Eigen::VectorXd& x) {
  using RowMajorX3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
  return Eigen::Map<const RowMajorX3>(x.data(), x.size() / 3, 3);
}

/// A smooth, strongly curved state: the unit disc rolled onto a cylinder, with waves.
Eigen::VectorXd curved_state(const ShellModel& model, double roll) {
  return map_reference(model, [roll](const Eigen::Vector3d& X) {
    const double t = X.x() / roll;
    return Eigen::Vector3d(roll * std::sin(t), X.y() + 0.05 * std::sin(3.0 * X.x()),
                           roll * (1.0 - std::cos(t)) + 0.05 * std::cos(2.0 * X.y()));
  });
}

/// Lattice coordinates (i, j) of the three corners of triangle k of an element's n^2
/// triangles, in the order documented on ContactProxy.
std::array<std::array<int, 2>, 3> triangle_lattice(int n, int k) {
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n - i; ++j) {
      if (k-- == 0) return {{{i, j}, {i + 1, j}, {i, j + 1}}};
      if (i + j < n - 1 && k-- == 0) return {{{i + 1, j}, {i + 1, j + 1}, {i, j + 1}}};
    }
  throw std::logic_error("triangle index out of range");
}

TEST(ContactProxy, MapReproducesTheLimitSurfaceAtEveryTriangleCorner) {
  DiscMeshOptions o;
  o.rings = 4;
  const ShellModel model(make_disc_mesh(o), ShellModelSettings{});
  const Eigen::VectorXd x = curved_state(model, 0.4);
  const Eigen::MatrixX3d rows = as_rows(x), reference_rows = as_rows(model.reference_positions());
  for (int n : {1, 2, 3, 5}) {
    const ContactProxy proxy = make_contact_proxy(model, n);
    const Eigen::MatrixX3d y = proxy_positions(proxy, x);
    ASSERT_EQ(y.rows(), proxy.num_vertices());
    // Tolerance 1e-12 m: positions are O(1) m and each is a 12-term sum of O(1) weights, so
    // rounding is ~1e-15; a wrongly shared edge point would be off by O(spacing / n) ~ 0.1 m.
    // Every triangle corner, evaluated in the triangle's own element (so shared corner and edge
    // points are checked against each element that has them).
    double worst = 0.0;
    for (Eigen::Index t = 0; t < proxy.triangles.rows(); ++t) {
      const int e = proxy.triangle_element(t);
      ASSERT_EQ(e, t / (n * n));
      const auto lattice = triangle_lattice(n, static_cast<int>(t % (n * n)));
      for (int c = 0; c < 3; ++c) {
        const double v = static_cast<double>(lattice[c][0]) / n,
                     w = static_cast<double>(lattice[c][1]) / n;
        const auto& control = model.patches().patch[static_cast<std::size_t>(e)];
        const int p = proxy.triangles(t, c);
        worst = std::max(
            worst,
            (y.row(p).transpose() - evaluate_limit_surface(rows, control, v, w).position).norm());
        worst = std::max(worst, (proxy.reference_positions.row(p).transpose() -
                                 evaluate_limit_surface(reference_rows, control, v, w).position)
                                    .norm());
      }
    }
    EXPECT_LT(worst, 1e-12) << "n " << n;
    // The stored (element, parameter) of each vertex names the same point.
    double worst_stored = 0.0;
    for (Eigen::Index p = 0; p < proxy.num_vertices(); ++p) {
      const auto& control =
          model.patches().patch[static_cast<std::size_t>(proxy.vertex_element(p))];
      worst_stored = std::max(
          worst_stored, (y.row(p).transpose() - evaluate_limit_surface(rows, control,
                                                                       proxy.vertex_parameter(p, 0),
                                                                       proxy.vertex_parameter(p, 1))
                                                    .position)
                            .norm());
    }
    EXPECT_LT(worst_stored, 1e-12) << "n " << n;
    // Loop weights are a partition of unity: each row of the map sums to 1 (rounding 1e-15).
    const Eigen::VectorXd row_sums = proxy.map * Eigen::VectorXd::Ones(proxy.map.cols());
    EXPECT_LT((row_sums.array() - 1.0).abs().maxCoeff(), 1e-13) << "n " << n;
    std::cout << "n " << n << ": proxy vertices " << proxy.num_vertices() << ", map nonzeros "
              << proxy.map.nonZeros() << ", worst corner error " << worst << ", stored "
              << worst_stored << "\n";
  }
}

TEST(ContactProxy, IsAConformingMeshWithTheCountedSizes) {
  for (int rings : {2, 5}) {
    DiscMeshOptions o;
    o.rings = rings;
    const ShellModel model(make_disc_mesh(o), ShellModelSettings{});
    // Sheet of an N-ring disc: V = 1 + 3 N (N + 1) vertices, E = 3 N (3 N + 1) edges,
    // F = 6 N^2 elements, 6 N boundary edges.
    const Eigen::Index N = rings, V = 1 + 3 * N * (N + 1), E = 3 * N * (3 * N + 1), F = 6 * N * N;
    for (int n : {1, 2, 3, 4}) {
      const ContactProxy proxy = make_contact_proxy(model, n);
      EXPECT_EQ(proxy.segments_per_edge, n);
      EXPECT_EQ(proxy.num_vertices(), V + E * (n - 1) + F * (n - 1) * (n - 2) / 2)
          << "N " << N << " n " << n;
      EXPECT_EQ(proxy.triangles.rows(), F * n * n);
      // Edges: n per sheet edge plus 3 n (n - 1) / 2 inside each element.
      EXPECT_EQ(proxy.edges.rows(), E * n + F * 3 * n * (n - 1) / 2);
      EXPECT_EQ(proxy.map.rows(), 3 * proxy.num_vertices());
      EXPECT_EQ(proxy.map.cols(), model.dimension());
      EXPECT_EQ(proxy.vertex_element.size(), proxy.num_vertices());
      EXPECT_EQ(proxy.vertex_parameter.rows(), proxy.num_vertices());

      // Conforming and consistently oriented: every directed edge at most once, every
      // undirected edge in one (boundary) or two (interior, opposite directions) triangles.
      std::map<std::pair<int, int>, int> directed;
      std::vector<int> used(static_cast<std::size_t>(proxy.num_vertices()), 0);
      for (Eigen::Index t = 0; t < proxy.triangles.rows(); ++t)
        for (int c = 0; c < 3; ++c) {
          ++directed[{proxy.triangles(t, c), proxy.triangles(t, (c + 1) % 3)}];
          used[static_cast<std::size_t>(proxy.triangles(t, c))] = 1;
        }
      Eigen::Index boundary = 0, interior = 0, bad = 0;
      for (const auto& [edge, count] : directed) {
        if (count != 1) ++bad;
        const bool reverse = directed.count({edge.second, edge.first}) > 0;
        if (reverse) {
          ++interior;
        } else {
          ++boundary;
        }
      }
      EXPECT_EQ(bad, 0);
      EXPECT_EQ(boundary, 6 * N * n);
      EXPECT_EQ(interior / 2 + boundary, proxy.edges.rows());
      EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0);
      // Euler characteristic of a disc.
      EXPECT_EQ(proxy.num_vertices() - proxy.edges.rows() + proxy.triangles.rows(), 1);
      // edges: each triangle side exactly once, (lower, higher), strictly increasing.
      for (Eigen::Index k = 0; k < proxy.edges.rows(); ++k) {
        const int p = proxy.edges(k, 0), q = proxy.edges(k, 1);
        ASSERT_LT(p, q);
        ASSERT_TRUE(directed.count({p, q}) + directed.count({q, p}) > 0);
        if (k > 0) {
          ASSERT_TRUE(std::make_pair(proxy.edges(k - 1, 0), proxy.edges(k - 1, 1)) <
                      std::make_pair(p, q));
        }
      }
    }
  }
}

TEST(ContactProxy, FlatDiscGivesAFlatProxyWithZeroNormalSag) {
  DiscMeshOptions o;
  o.rings = 6;
  const ShellModel model(make_disc_mesh(o), ShellModelSettings{});
  for (int n : {1, 3}) {
    const ContactProxy proxy = make_contact_proxy(model, n);
    const Eigen::MatrixX3d y = proxy_positions(proxy, model.reference_positions());
    // Every control point has z = 0 exactly, so every weighted sum is exactly 0.
    EXPECT_EQ(y.col(2).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ((y - proxy.reference_positions).cwiseAbs().maxCoeff(), 0.0);
    // The proxy's element corners are the sheet's limit points, which ShellModel computes by
    // the Loop limit rule (1/2 and 1/12 weights), an independent path: with n = 1 the two sets
    // coincide (rounding 1e-15).
    if (n == 1) {
      const Eigen::MatrixX3d limit = model.limit_positions(model.reference_positions());
      ASSERT_EQ(limit.rows(), y.rows());
      const std::vector<int>& sheet = model.sheet_vertices();
      double worst = 0.0;
      for (Eigen::Index p = 0; p < y.rows(); ++p) {
        // The corner named by the stored parameter: (0, 0), (1, 0), (0, 1) -> nodes 3, 6, 7.
        const auto& control =
            model.patches().patch[static_cast<std::size_t>(proxy.vertex_element(p))].control;
        const int node = proxy.vertex_parameter(p, 0) == 1.0   ? 6
                         : proxy.vertex_parameter(p, 1) == 1.0 ? 7
                                                               : 3;
        const auto it =
            std::lower_bound(sheet.begin(), sheet.end(), control[static_cast<std::size_t>(node)]);
        ASSERT_TRUE(it != sheet.end() && *it == control[static_cast<std::size_t>(node)]);
        worst = std::max(worst, (y.row(p) - limit.row(it - sheet.begin())).norm());
      }
      EXPECT_LT(worst, 1e-12);
    }
    const ProxySag sag = proxy_sag(model, proxy, model.reference_positions());
    EXPECT_EQ(sag.normal, 0.0);
    // The conformal layout is not an affine lattice, so the limit parameterisation is not
    // affine and the parameter-matched offset is in-plane and non-zero (it is no sag).
    EXPECT_GT(sag.parametric, 0.0);
    std::cout << "flat disc n " << n << ": normal sag " << sag.normal << ", parametric offset "
              << sag.parametric << "\n";
  }
}

TEST(ContactProxy, SagFallsLikeOneOverNSquared) {
  DiscMeshOptions o;
  o.rings = 6;
  const ShellModel model(make_disc_mesh(o), ShellModelSettings{});
  // Rolled onto a cylinder of radius rho = 0.5 (z = rho (1 - cos(x / rho))), no waves: the
  // sag of a chord of length l across the curved direction is l^2 / (8 rho).
  const double rho = 0.5;
  const Eigen::VectorXd x = map_reference(model, [rho](const Eigen::Vector3d& X) {
    return Eigen::Vector3d(rho * std::sin(X.x() / rho), X.y(), rho * (1.0 - std::cos(X.x() / rho)));
  });
  std::vector<double> sag;
  for (int n : {1, 2, 4, 8}) {
    const ContactProxy proxy = make_contact_proxy(model, n);
    const Eigen::MatrixX3d y = proxy_positions(proxy, x);
    double longest = 0.0;
    for (Eigen::Index k = 0; k < proxy.edges.rows(); ++k)
      longest = std::max(longest, (y.row(proxy.edges(k, 0)) - y.row(proxy.edges(k, 1))).norm());
    const ProxySag s = proxy_sag(model, proxy, x);
    sag.push_back(s.normal);
    const double chord = longest * longest / (8.0 * rho);
    std::cout << "cylinder rho 0.5, n " << n << ": normal sag " << s.normal << ", parametric "
              << s.parametric << ", longest edge " << longest << ", l^2 / (8 rho) " << chord
              << "\n";
    // On a cylinder no chord sags more than l^2 / (8 rho); the Loop surface of the rolled
    // control mesh is a cylinder only to O(h^2), hence 10 % slack. And the longest edges of the
    // disc lie along the rim in every direction, so some sag is at least a quarter of it.
    EXPECT_LT(s.normal, 1.1 * chord) << "n " << n;
    EXPECT_GT(s.normal, 0.25 * chord) << "n " << n;
  }
  // Second-order interpolation: halving the sub-edges divides the sag by 4 (+-25 %).
  for (std::size_t k = 0; k + 1 < sag.size(); ++k) {
    EXPECT_GT(sag[k] / sag[k + 1], 3.0) << k;
    EXPECT_LT(sag[k] / sag[k + 1], 5.0) << k;
  }
}

TEST(ContactProxy, TheTriangleAtAParameterHoldsItWithItsWeights) {
  DiscMeshOptions o;
  o.rings = 3;
  const ShellModel model(make_disc_mesh(o), ShellModelSettings{});
  for (int n : {1, 2, 3, 5}) {
    const ContactProxy proxy = make_contact_proxy(model, n);
    const auto elements = static_cast<int>(proxy.triangles.rows() / (n * n));
    for (int e : {0, elements - 1}) {
      for (int a = 0; a <= 20; ++a)
        for (int b = 0; a + b <= 20; ++b) {
          const Eigen::Vector2d vw(a / 20.0, b / 20.0);
          const ProxyTriangleLocation at = proxy_triangle_at(proxy, e, vw);
          ASSERT_GE(at.triangle, e * n * n);
          ASSERT_LT(at.triangle, (e + 1) * n * n);
          EXPECT_GE(at.barycentric.minCoeff(), -1e-15);
          EXPECT_NEAR(at.barycentric.sum(), 1.0, 1e-15);
          // The weights of the triangle's lattice corners give the parameter back.
          const auto corners = triangle_lattice(n, at.triangle - e * n * n);
          Eigen::Vector2d back = Eigen::Vector2d::Zero();
          for (int i = 0; i < 3; ++i)
            back += at.barycentric(i) *
                    Eigen::Vector2d(corners[static_cast<std::size_t>(i)][0],
                                    corners[static_cast<std::size_t>(i)][1]) /
                    n;
          EXPECT_LT((back - vw).norm(), 1e-14) << "n " << n << " (v, w) " << vw.transpose();
        }
    }
    EXPECT_THROW(proxy_triangle_at(proxy, elements, Eigen::Vector2d(0.2, 0.2)),
                 std::invalid_argument);
  }
}

TEST(ContactProxy, RejectsBadInputNamingIt) {
  DiscMeshOptions o;
  o.rings = 3;
  const ShellModel model(make_disc_mesh(o), ShellModelSettings{});
  const auto message = [](auto f) -> std::string {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  for (int n : {0, -2, 1001})
    EXPECT_NE(message([&] { make_contact_proxy(model, n); }).find("segments_per_edge"),
              std::string::npos)
        << n;
  const ContactProxy proxy = make_contact_proxy(model, 2);
  const Eigen::VectorXd& x = model.reference_positions();
  EXPECT_NE(message([&] { proxy_positions(proxy, x.head(x.size() - 3)); }).find("entries"),
            std::string::npos);
  EXPECT_NE(message([&] { proxy_sag(model, proxy, x.head(x.size() - 1)); }).find("dimension"),
            std::string::npos);
  DiscMeshOptions other;
  other.rings = 4;
  const ShellModel other_model(make_disc_mesh(other), ShellModelSettings{});
  EXPECT_NE(message([&] {
              proxy_sag(other_model, proxy, other_model.reference_positions());
            }).find("not made from"),
            std::string::npos);
}

}  // namespace
}  // namespace growshell
