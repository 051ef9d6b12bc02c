#include "libshell/mesh/disc_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "libshell/mesh/mesh_error.hpp"
#include "libshell/mesh/mesh_topology.hpp"
#include "libshell/mesh/mesh_validation.hpp"

namespace growshell {
namespace {

template <class F>
std::string mesh_error_message(F&& f) {
  try {
    f();
  } catch (const MeshError& e) {
    return e.what();
  }
  return "<no MeshError thrown>";
}

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << "message: " << (text)

int ring_start(int k) { return k == 0 ? 0 : 1 + 3 * k * (k - 1); }

int count_elements(const MeshTopology& topo) {
  int count = 0;
  for (int f = 0; f < topo.num_faces(); ++f) {
    const auto& t = topo.face(f);
    if (std::none_of(t.begin(), t.end(), [&](int v) { return topo.is_boundary_vertex(v); })) {
      ++count;
    }
  }
  return count;
}

void expect_interior_valence_six(const MeshTopology& topo) {
  for (int v = 0; v < topo.num_vertices(); ++v) {
    if (!topo.is_boundary_vertex(v)) {
      EXPECT_EQ(topo.valence(v), 6) << "vertex " << v;
    }
  }
}

double distance_to(const TriangleMesh& mesh, int v, const Eigen::Vector2d& center) {
  return (mesh.vertices.row(v).head<2>().transpose() - center).norm();
}

// Largest ratio longest edge / shortest edge over the elements.
double max_element_edge_ratio(const TriangleMesh& mesh) {
  const MeshTopology topo(mesh);
  double worst = 0.0;
  for (int f = 0; f < topo.num_faces(); ++f) {
    const auto& t = topo.face(f);
    if (std::any_of(t.begin(), t.end(), [&](int v) { return topo.is_boundary_vertex(v); })) {
      continue;
    }
    double lo = INFINITY, hi = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double l = (mesh.vertices.row(t[k]) - mesh.vertices.row(t[(k + 1) % 3])).norm();
      lo = std::min(lo, l);
      hi = std::max(hi, l);
    }
    worst = std::max(worst, hi / lo);
  }
  return worst;
}

TEST(DiscMesh, CountsAndRegularity) {
  for (int n : {2, 3, 7, 20}) {
    const TriangleMesh mesh = make_disc_mesh({.radius = 1.0, .rings = n});
    EXPECT_EQ(mesh.vertices.rows(), 1 + 3 * (n + 1) * (n + 2));
    EXPECT_EQ(mesh.faces.rows(), 6 * (n + 1) * (n + 1));
    EXPECT_TRUE((mesh.vertices.col(2).array() == 0.0).all());
    const MeshTopology topo(mesh);
    expect_interior_valence_six(topo);
    // Exactly the ghost ring (ring n+1) is on the boundary.
    for (int v = 0; v < topo.num_vertices(); ++v) {
      EXPECT_EQ(topo.is_boundary_vertex(v), v >= ring_start(n + 1)) << "vertex " << v;
    }
    EXPECT_EQ(count_elements(topo), 6 * n * n);
    EXPECT_NO_THROW(validate_control_mesh(mesh));
  }
}

TEST(DiscMesh, UniformRingRadiiAndAngles) {
  const Eigen::Vector2d center(0.3, -0.2);
  const double R = 2.5;
  const int n = 6;
  const TriangleMesh mesh = make_disc_mesh({.radius = R, .rings = n, .center = center});
  EXPECT_EQ(distance_to(mesh, 0, center), 0.0);
  for (int k = 1; k <= n + 1; ++k) {
    // Ghost ring at R + (r_N - r_{N-1}) = R (1 + 1/N); uniform rings at k R / N.
    const double expected = k * R / n;
    for (int m = 0; m < 6 * k; ++m) {
      const int v = ring_start(k) + m;
      // Positions are r (cos, sin) + center: a few ulps of R.
      EXPECT_NEAR(distance_to(mesh, v, center), expected, 1e-14 * R) << "ring " << k;
      const Eigen::Vector2d d = mesh.vertices.row(v).head<2>().transpose() - center;
      const double angle = std::atan2(d.y(), d.x());
      const double expected_angle = 2.0 * std::numbers::pi * m / (6 * k);
      EXPECT_NEAR(std::remainder(angle - expected_angle, 2.0 * std::numbers::pi), 0.0, 1e-13);
    }
  }
}

TEST(DiscMesh, GradedSpacing) {
  const double R = 1.0;
  const int n = 40;
  const double h_min = 0.005;
  for (double p : {1.5, 2.0, 3.0}) {
    const TriangleMesh mesh =
        make_disc_mesh({.radius = R, .rings = n, .grading_exponent = p, .min_spacing = h_min});
    EXPECT_NO_THROW(validate_control_mesh(mesh));
    std::vector<double> r(n + 2);
    for (int k = 0; k <= n + 1; ++k) r[k] = distance_to(mesh, ring_start(k), {0.0, 0.0});
    // r_1 = h_min + (1 - a) R / N^p with a = h_min N / R = 0.2; for p >= 2 the second term is
    // at most 0.8/1600 = 10% of h_min (p = 1.5: 64%).
    EXPECT_GE(r[1], h_min);
    EXPECT_NEAR(r[1], h_min + 0.8 * R / std::pow(n, p), 1e-15);
    if (p >= 2.0) {
      EXPECT_LE(r[1], 1.1 * h_min * (1.0 + 1e-12)) << "p = " << p;
    }
    for (int k = 2; k <= n; ++k) {
      EXPECT_GT(r[k] - r[k - 1], r[k - 1] - r[k - 2]) << "p = " << p << ", k = " << k;
    }
    EXPECT_DOUBLE_EQ(r[n], R);
    EXPECT_NEAR(r[n + 1] - r[n], r[n] - r[n - 1], 1e-14);
    // The elements stay well shaped: measured worst longest/shortest edge ratios are 1.67,
    // 2.00, 2.72 for p = 1.5, 2, 3 (about p); the bound p + 0.25 leaves 5-20% margin.
    const double ratio = max_element_edge_ratio(mesh);
    EXPECT_LT(ratio, p + 0.25) << "p = " << p;
  }
  // Without a floor the centre is much finer: r_1 = R / N^p.
  const TriangleMesh pure = make_disc_mesh({.radius = R, .rings = 10, .grading_exponent = 2.0});
  EXPECT_NEAR(distance_to(pure, 1, {0.0, 0.0}), 0.01, 1e-15);
  // A floor above R/N is clamped to uniform spacing.
  const TriangleMesh clamped =
      make_disc_mesh({.radius = R, .rings = 10, .grading_exponent = 2.0, .min_spacing = 0.5});
  EXPECT_NEAR(distance_to(clamped, 1, {0.0, 0.0}), 0.1, 1e-15);
}

TEST(DiscMesh, RejectsInvalidOptions) {
  EXPECT_CONTAINS(mesh_error_message([] { make_disc_mesh({.radius = -1.0}); }), "disc radius");
  EXPECT_CONTAINS(mesh_error_message([] { make_disc_mesh({.radius = NAN}); }), "disc radius");
  EXPECT_CONTAINS(mesh_error_message([] { make_disc_mesh({.rings = 1}); }), "disc rings = 1");
  EXPECT_CONTAINS(mesh_error_message([] { make_disc_mesh({.grading_exponent = 0.5}); }),
                  "disc grading_exponent = 0.5 is invalid; it must be finite and >= 1");
  EXPECT_CONTAINS(mesh_error_message([] { make_disc_mesh({.min_spacing = -0.1}); }),
                  "disc min_spacing");
}

TEST(AnnulusMesh, FirstRingMatchesRadialSpacing) {
  // dr = 0.75/16 = 0.046875; tangential spacing 2 pi 0.25 / (6K) is 0.0524 for K = 5 and
  // 0.0436 for K = 6, so K = 6.
  EXPECT_EQ(annulus_first_ring({}), 6);
  for (double ri : {0.05, 0.1, 0.4, 0.7}) {
    for (int layers : {2, 5, 16}) {
      const AnnulusMeshOptions options{
          .inner_radius = ri, .outer_radius = 1.0, .radial_layers = layers};
      const double dr = (1.0 - ri) / layers;
      int best = 2;
      for (int k = 2; k < 1000; ++k) {
        auto mismatch = [&](int kk) { return std::abs(2 * std::numbers::pi * ri / (6 * kk) - dr); };
        if (mismatch(k) < mismatch(best)) best = k;
      }
      EXPECT_EQ(annulus_first_ring(options), best) << "ri = " << ri << ", layers = " << layers;
    }
  }
}

TEST(AnnulusMesh, RadiiCountsAndRegularity) {
  const Eigen::Vector2d center(-1.0, 2.0);
  for (const auto& [ri, layers] : {std::pair{0.25, 16}, std::pair{0.05, 4}, std::pair{0.6, 3}}) {
    const double R = 1.0;
    const AnnulusMeshOptions options{
        .inner_radius = ri, .outer_radius = R, .radial_layers = layers, .center = center};
    const TriangleMesh mesh = make_annulus_mesh(options);
    const int K = annulus_first_ring(options);
    const int N = K + layers;
    int expected_vertices = 0, expected_faces = 0, expected_elements = 0;
    for (int k = K - 1; k <= N + 1; ++k) expected_vertices += 6 * k;
    for (int k = K; k <= N + 1; ++k) expected_faces += 6 * (2 * k - 1);
    for (int k = K + 1; k <= N; ++k) expected_elements += 6 * (2 * k - 1);
    EXPECT_EQ(mesh.vertices.rows(), expected_vertices);
    EXPECT_EQ(mesh.faces.rows(), expected_faces);
    const MeshTopology topo(mesh);
    expect_interior_valence_six(topo);
    EXPECT_EQ(count_elements(topo), expected_elements);
    EXPECT_NO_THROW(validate_control_mesh(mesh));

    const double dr = (R - ri) / layers;
    const double inner_ghost = ri - dr > 0.0 ? ri - dr : 0.5 * ri;
    const int base = ring_start(K - 1);
    for (int k = K - 1; k <= N + 1; ++k) {
      const double expected = k == K - 1 ? inner_ghost : ri + (k - K) * dr;
      for (int m = 0; m < 6 * k; ++m) {
        const int v = ring_start(k) - base + m;
        EXPECT_NEAR(distance_to(mesh, v, center), expected, 1e-14) << "ring " << k;
        EXPECT_EQ(topo.is_boundary_vertex(v), k == K - 1 || k == N + 1);
      }
    }
  }
}

TEST(AnnulusMesh, RejectsInvalidOptions) {
  EXPECT_CONTAINS(mesh_error_message([] { make_annulus_mesh({.inner_radius = 0.0}); }),
                  "annulus inner_radius = 0");
  EXPECT_CONTAINS(
      mesh_error_message([] { make_annulus_mesh({.inner_radius = 1.0, .outer_radius = 1.0}); }),
      "annulus outer_radius = 1 is invalid; it must be finite and > inner_radius");
  EXPECT_CONTAINS(mesh_error_message([] { make_annulus_mesh({.radial_layers = 0}); }),
                  "annulus radial_layers");
}

TEST(StripMesh, ElementRegionAndNumbering) {
  const StripMeshOptions options{.length = 3.0, .width = 0.6, .cells_x = 9, .cells_y = 4};
  const TriangleMesh mesh = make_strip_mesh(options);
  EXPECT_EQ(mesh.vertices.rows(), (9 + 3) * (4 + 3));
  EXPECT_EQ(mesh.faces.rows(), 2 * (9 + 2) * (4 + 2));
  const MeshTopology topo(mesh);
  expect_interior_valence_six(topo);
  EXPECT_EQ(count_elements(topo), 2 * 9 * 4);
  EXPECT_NO_THROW(validate_control_mesh(mesh));

  for (int j = -1; j <= 5; ++j) {
    for (int i = -1; i <= 10; ++i) {
      const int v = strip_vertex_index(options, i, j);
      EXPECT_EQ(v, (i + 1) + (j + 1) * 12);
      // i L / n and j W / n - W/2: correctly rounded products and quotients, 1 ulp of L.
      EXPECT_NEAR(mesh.vertices(v, 0), i * 3.0 / 9, 1e-15);
      EXPECT_NEAR(mesh.vertices(v, 1), j * 0.15 - 0.3, 1e-15);
      EXPECT_EQ(topo.is_boundary_vertex(v), i == -1 || i == 10 || j == -1 || j == 5);
    }
  }
  // The element region is [0, L] x [-W/2, W/2].
  Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  for (int f = 0; f < topo.num_faces(); ++f) {
    const auto& t = topo.face(f);
    if (std::any_of(t.begin(), t.end(), [&](int v) { return topo.is_boundary_vertex(v); })) {
      continue;
    }
    for (int v : t) {
      lo = lo.cwiseMin(mesh.vertices.row(v).head<2>().transpose());
      hi = hi.cwiseMax(mesh.vertices.row(v).head<2>().transpose());
    }
  }
  EXPECT_NEAR(lo.x(), 0.0, 1e-15);
  EXPECT_NEAR(hi.x(), 3.0, 1e-15);
  EXPECT_NEAR(lo.y(), -0.3, 1e-15);
  EXPECT_NEAR(hi.y(), 0.3, 1e-15);

  const std::vector<int> end_row = strip_vertices_with_x_index(options, 9);
  ASSERT_EQ(end_row.size(), 7u);
  for (std::size_t j = 0; j < end_row.size(); ++j) {
    EXPECT_EQ(end_row[j], strip_vertex_index(options, 9, static_cast<int>(j) - 1));
    EXPECT_NEAR(mesh.vertices(end_row[j], 0), 3.0, 1e-15);
  }
  EXPECT_CONTAINS(mesh_error_message([&] { strip_vertices_with_x_index(options, 11); }),
                  "strip column index i = 11 is outside [-1, 10]");
}

TEST(StripMesh, RejectsInvalidOptions) {
  EXPECT_CONTAINS(mesh_error_message([] { make_strip_mesh({.length = 0.0}); }), "strip length");
  EXPECT_CONTAINS(mesh_error_message([] { make_strip_mesh({.width = -1.0}); }), "strip width");
  EXPECT_CONTAINS(mesh_error_message([] { make_strip_mesh({.cells_x = 0}); }), "strip cells_x");
  EXPECT_CONTAINS(mesh_error_message([] { make_strip_mesh({.cells_y = 0}); }), "strip cells_y");
}

}  // namespace
}  // namespace growshell
