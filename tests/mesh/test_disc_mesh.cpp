#include "libshell/mesh/disc_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "libshell/mesh/mesh_error.hpp"
#include "libshell/mesh/mesh_topology.hpp"
#include "libshell/mesh/mesh_validation.hpp"
#include "tests/support/mesh_checks.hpp"

namespace growshell {
namespace {

using test_support::count_elements;
using test_support::mesh_error_message;

int ring_start(int k) { return k == 0 ? 0 : 1 + 3 * k * (k - 1); }

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

bool touches_rim_corner(const TriangleMesh& mesh, int f, int n) {
  for (int c = 0; c < 3; ++c) {
    const int v = mesh.faces(f, c);
    if (v >= ring_start(n) && v < ring_start(n + 1) && (v - ring_start(n)) % n == 0) return true;
  }
  return false;
}

struct ElementQuality {
  double max_edge_ratio = 0.0;  // longest / shortest edge of one element
  double min_angle_degrees = 180.0;
};

// Worst shape over the elements (not the ghost faces); optionally without the elements that
// have a rim corner of an n-ring disc as a vertex.
ElementQuality element_quality(const TriangleMesh& mesh, bool skip_rim_corners = false, int n = 0) {
  const MeshTopology topo(mesh);
  ElementQuality q;
  for (int f = 0; f < topo.num_faces(); ++f) {
    const auto& t = topo.face(f);
    if (std::any_of(t.begin(), t.end(), [&](int v) { return topo.is_boundary_vertex(v); })) {
      continue;
    }
    if (skip_rim_corners && touches_rim_corner(mesh, f, n)) continue;
    double l[3];
    for (int k = 0; k < 3; ++k) {
      l[k] = (mesh.vertices.row(t[k]) - mesh.vertices.row(t[(k + 1) % 3])).norm();
    }
    q.max_edge_ratio =
        std::max(q.max_edge_ratio, std::max({l[0], l[1], l[2]}) / std::min({l[0], l[1], l[2]}));
    for (int k = 0; k < 3; ++k) {
      const double a = l[k], b = l[(k + 1) % 3], c = l[(k + 2) % 3];
      const double angle = std::acos((a * a + b * b - c * c) / (2.0 * a * b));
      q.min_angle_degrees = std::min(q.min_angle_degrees, angle * 180.0 / std::numbers::pi);
    }
  }
  return q;
}

// g'(0) = 1 / C of hexagon_to_disc: C = 6 Gamma(5/6) / (Gamma(1/6) Gamma(2/3)) = 0.8986.
double hexagon_map_constant() {
  return 6.0 * std::tgamma(5.0 / 6.0) / (std::tgamma(1.0 / 6.0) * std::tgamma(2.0 / 3.0));
}

double mean_ring_radius(const TriangleMesh& mesh, int k, const Eigen::Vector2d& center) {
  if (k == 0) return distance_to(mesh, 0, center);
  double sum = 0.0;
  for (int m = 0; m < 6 * k; ++m) sum += distance_to(mesh, ring_start(k) + m, center);
  return sum / (6 * k);
}

TEST(DiscMesh, CountsAndRegularity) {
  for (DiscLayout layout : {DiscLayout::Conformal, DiscLayout::EqualAngleRings}) {
    for (int n : {2, 3, 7, 20}) {
      const TriangleMesh mesh = make_disc_mesh({.radius = 1.0, .rings = n, .layout = layout});
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
      EXPECT_NO_THROW(validate_control_mesh(mesh)) << "n = " << n;
    }
  }
}

TEST(DiscMesh, ConformalRimIsTheCircleAndRealVerticesAreInside) {
  const Eigen::Vector2d center(0.3, -0.2);
  const double R = 2.5;
  for (int n : {2, 5, 16}) {
    for (double p : {1.0, 3.0}) {
      const TriangleMesh mesh = make_disc_mesh(
          {.radius = R, .rings = n, .grading_exponent = p, .min_spacing = 0.02, .center = center});
      EXPECT_EQ(distance_to(mesh, 0, center), 0.0);
      for (int k = 1; k <= n + 1; ++k) {
        for (int m = 0; m < 6 * k; ++m) {
          const double r = distance_to(mesh, ring_start(k) + m, center);
          // Ring n is normalised onto the circle; the rest is a few ulps of |center| and R.
          if (k == n) {
            EXPECT_NEAR(r, R, 1e-12 * R) << "n = " << n << ", m = " << m;
          } else if (k < n) {
            EXPECT_LT(r, R * (1.0 - 1e-3)) << "n = " << n << ", k = " << k;
          } else {
            EXPECT_GT(r, R * (1.0 + 1e-3)) << "n = " << n << ", m = " << m;
          }
        }
      }
    }
  }
}

TEST(DiscMesh, ConformalLayoutHasTheHexagonSymmetries) {
  const Eigen::Vector2d center(-1.0, 0.5);
  const double R = 1.5;
  const int n = 9;
  const TriangleMesh mesh = make_disc_mesh(
      {.radius = R, .rings = n, .grading_exponent = 3.0, .min_spacing = 0.05, .center = center});
  const Eigen::Rotation2Dd rotation(std::numbers::pi / 3.0);
  for (int k = 1; k <= n + 1; ++k) {
    for (int m = 0; m < 6 * k; ++m) {
      const Eigen::Vector2d x = mesh.vertices.row(ring_start(k) + m).head<2>().transpose() - center;
      // Rotation by 60 degrees: vertex m -> m + k. Only rounding of the rotation: 1e-14 R.
      const int rotated = ring_start(k) + (m + k) % (6 * k);
      const Eigen::Vector2d y = mesh.vertices.row(rotated).head<2>().transpose() - center;
      EXPECT_LT((rotation * x - y).norm(), 1e-14 * R) << "ring " << k << ", vertex " << m;
      // Reflection in the x-axis through the centre: vertex m -> -m. The generator maps only
      // side 0, so this checks hexagon_to_disc(conj z) = conj hexagon_to_disc(z) (1e-13)
      // and the ghost-corner rules' mirror symmetry.
      const int mirrored = ring_start(k) + (6 * k - m) % (6 * k);
      const Eigen::Vector2d z = mesh.vertices.row(mirrored).head<2>().transpose() - center;
      EXPECT_LT((Eigen::Vector2d(x.x(), -x.y()) - z).norm(), 1e-12 * R)
          << "ring " << k << ", vertex " << m;
    }
  }
}

TEST(DiscMesh, ConformalCentreSpacingAndGrading) {
  const double C = hexagon_map_constant();
  const double R = 2.0;
  const int n = 20;
  // Near the centre g(z) = z / C + O(z^7): ring 1 is at R / (C n) up to (1/n)^7 ~ 1e-9
  // (measured 8e-11 for R = 1).
  const TriangleMesh uniform = make_disc_mesh({.radius = R, .rings = n});
  for (int m = 0; m < 6; ++m) {
    EXPECT_NEAR(distance_to(uniform, 1 + m, {0.0, 0.0}), R / (C * n), 1e-9 * R);
  }
  // p = 3 with a floor: sigma(rho) = a rho + (1 - a) rho^3, a = h_min n / R = 0.1.
  const double h_min = 0.01;
  const TriangleMesh graded =
      make_disc_mesh({.radius = R, .rings = n, .grading_exponent = 3.0, .min_spacing = h_min});
  EXPECT_NO_THROW(validate_control_mesh(graded));
  const double rho = 1.0 / (C * n), a = h_min * n / R;
  for (int m = 0; m < 6; ++m) {
    EXPECT_NEAR(distance_to(graded, 1 + m, {0.0, 0.0}), R * (a * rho + (1 - a) * rho * rho * rho),
                1e-9 * R);
  }
  // So the centre spacing is h_min / C ~ 1.11 h_min, plus (1 - a) R rho^3 = 2.8% of that.
  EXPECT_NEAR(distance_to(graded, 1, {0.0, 0.0}), h_min / C, 0.035 * h_min);
  std::vector<double> mean(n + 2);
  for (int k = 0; k <= n + 1; ++k) mean[k] = mean_ring_radius(graded, k, {0.0, 0.0});
  for (int k = 1; k <= n + 1; ++k) EXPECT_GT(mean[k], mean[k - 1]) << "k = " << k;
  // Graded: the outer rings are far coarser than the inner ones (sigma'(1) / sigma'(0) =
  // (a + 3 (1 - a)) / a = 28 for a = 0.1, times the map's own 1.4 / 1.11 growth).
  EXPECT_GT((mean[n] - mean[n - 1]) / (mean[1] - mean[0]), 10.0);
  // Without a floor (a = 0) the centre is much finer: R rho^3.
  const TriangleMesh pure = make_disc_mesh({.radius = R, .rings = n, .grading_exponent = 3.0});
  EXPECT_NEAR(distance_to(pure, 1, {0.0, 0.0}), R * rho * rho * rho, 1e-12 * R);
  // A floor above R/N is clamped to uniform spacing (a = 1).
  const TriangleMesh clamped =
      make_disc_mesh({.radius = R, .rings = n, .grading_exponent = 3.0, .min_spacing = 1.0});
  EXPECT_NEAR(distance_to(clamped, 1, {0.0, 0.0}), R * rho, 1e-9 * R);
  // Non-odd p leave only a weak singularity at the centre; the meshes are valid.
  for (double p : {1.5, 2.0}) {
    EXPECT_NO_THROW(validate_control_mesh(
        make_disc_mesh({.radius = R, .rings = n, .grading_exponent = p, .min_spacing = h_min})));
  }
}

TEST(DiscMesh, ConformalElementQuality) {
  // Measured for n = 10, 20, 40 (p = 1): worst edge ratio 1.4134, 1.4141, 1.4142 and smallest
  // angle 45.015, 45.002, 45.000 degrees, both at the rim corners, where the elements tend to
  // right isosceles triangles (the map opens the 120-degree corner to 180 degrees). Without
  // the rim-corner elements: 1.1997, 1.2125, 1.2168 and 49.84, 48.93, 48.60 degrees
  // (n = 80: 1.2183, 48.49), i.e. near-equilateral.
  for (int n : {10, 20, 40}) {
    const TriangleMesh mesh = make_disc_mesh({.radius = 1.0, .rings = n});
    const ElementQuality all = element_quality(mesh);
    EXPECT_LT(all.max_edge_ratio, 1.42) << "n = " << n;
    EXPECT_GT(all.min_angle_degrees, 44.9) << "n = " << n;
    const ElementQuality smooth = element_quality(mesh, true, n);
    EXPECT_LT(smooth.max_edge_ratio, 1.23) << "n = " << n;
    EXPECT_GT(smooth.min_angle_degrees, 48.0) << "n = " << n;
  }
  // Graded (p = 3, h_min = 0.005, so a = 0.05, 0.1, 0.2): the grading stretches the elements
  // radially; measured worst ratio 3.019, 2.899, 2.762 and angle 19.19, 20.18, 21.23 degrees.
  for (int n : {10, 20, 40}) {
    const TriangleMesh mesh =
        make_disc_mesh({.radius = 1.0, .rings = n, .grading_exponent = 3.0, .min_spacing = 0.005});
    const ElementQuality q = element_quality(mesh);
    EXPECT_LT(q.max_edge_ratio, 3.1) << "n = " << n;
    EXPECT_GT(q.min_angle_degrees, 19.0) << "n = " << n;
  }
}

TEST(DiscMesh, EqualAngleRingsRadiiAndAngles) {
  const Eigen::Vector2d center(0.3, -0.2);
  const double R = 2.5;
  const int n = 6;
  const TriangleMesh mesh = make_disc_mesh(
      {.radius = R, .rings = n, .center = center, .layout = DiscLayout::EqualAngleRings});
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

TEST(DiscMesh, EqualAngleRingsGradedSpacing) {
  const double R = 1.0;
  const int n = 40;
  const double h_min = 0.005;
  for (double p : {1.5, 2.0, 3.0}) {
    const TriangleMesh mesh = make_disc_mesh({.radius = R,
                                              .rings = n,
                                              .grading_exponent = p,
                                              .min_spacing = h_min,
                                              .layout = DiscLayout::EqualAngleRings});
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
    // Measured worst longest/shortest edge ratios are 1.67, 2.00, 2.72 for p = 1.5, 2, 3
    // (about p); the bound p + 0.25 leaves 5-20% margin.
    EXPECT_LT(element_quality(mesh).max_edge_ratio, p + 0.25) << "p = " << p;
  }
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

TEST(AnnulusMesh, VerticesPerRingMatchTheLogarithmicStep) {
  // dl = ln(4) / 16 = 0.0866: 2 pi / dl = 72.5 -> 73.
  EXPECT_EQ(annulus_vertices_per_ring({}), 73);
  // dl = ln(1 / 0.6) / 3 = 0.170: 2 pi / dl = 36.9 -> 37.
  EXPECT_EQ(annulus_vertices_per_ring({.inner_radius = 0.6, .radial_layers = 3}), 37);
  // dl = ln(100) / 2 = 2.30: 2 pi / dl = 2.7, raised to the minimum 6.
  EXPECT_EQ(annulus_vertices_per_ring({.inner_radius = 0.01, .radial_layers = 2}), 6);
  for (double ri : {0.05, 0.2, 0.7}) {
    for (int layers : {4, 16}) {
      const AnnulusMeshOptions o{.inner_radius = ri, .outer_radius = 1.0, .radial_layers = layers};
      const int M = annulus_vertices_per_ring(o);
      // Grid cells are as square as an integer M allows: |M - 2 pi / dl| <= 1/2, i.e.
      // |2 pi / M - dl| <= dl / (2 M).
      const double dl = std::log(1.0 / ri) / layers;
      const double step = 2.0 * std::numbers::pi / M;
      EXPECT_LE(std::abs(step - dl), 0.5 * dl / M + 1e-15)
          << "ri = " << ri << ", layers = " << layers;
    }
  }
}

TEST(AnnulusMesh, LogPolarGridRadiiCountsAndRegularity) {
  const Eigen::Vector2d center(-1.0, 2.0);
  for (const auto& [ri, layers] : {std::pair{0.25, 16}, std::pair{0.05, 4}, std::pair{0.6, 3}}) {
    const double R = 1.0;
    const AnnulusMeshOptions options{
        .inner_radius = ri, .outer_radius = R, .radial_layers = layers, .center = center};
    const TriangleMesh mesh = make_annulus_mesh(options);
    const int M = annulus_vertices_per_ring(options);
    EXPECT_EQ(mesh.vertices.rows(), M * (layers + 3));
    EXPECT_EQ(mesh.faces.rows(), 2 * M * (layers + 2));
    EXPECT_TRUE((mesh.vertices.col(2).array() == 0.0).all());
    const MeshTopology topo(mesh);
    expect_interior_valence_six(topo);
    EXPECT_EQ(count_elements(topo), 2 * M * layers);
    EXPECT_NO_THROW(validate_control_mesh(mesh));

    const double dl = std::log(R / ri) / layers;
    for (int j = -1; j <= layers + 1; ++j) {
      const double expected = ri * std::exp(j * dl);
      for (int i = 0; i < M; ++i) {
        const int v = (j + 1) * M + i;
        const double r = distance_to(mesh, v, center);
        // Real rim rings are exact up to the rounding of cos, sin and + center (|center| = 2.2).
        if (j == 0) {
          EXPECT_NEAR(r, ri, 2e-15) << "vertex " << v;
        } else if (j == layers) {
          EXPECT_NEAR(r, R, 2e-15) << "vertex " << v;
        }
        // Others: exp(j dl) to a few ulps.
        EXPECT_NEAR(r, expected, 1e-14) << "ring " << j;
        const Eigen::Vector2d d = mesh.vertices.row(v).head<2>().transpose() - center;
        EXPECT_NEAR(std::remainder(std::atan2(d.y(), d.x()) - 2.0 * std::numbers::pi * i / M,
                                   2.0 * std::numbers::pi),
                    0.0, 1e-13);
        EXPECT_EQ(topo.is_boundary_vertex(v), j == -1 || j == layers + 1) << "vertex " << v;
      }
    }
    // Ghost rings one logarithmic step beyond the rims.
    EXPECT_NEAR(distance_to(mesh, 0, center), ri * std::exp(-dl), 1e-14);
    EXPECT_NEAR(distance_to(mesh, (layers + 2) * M, center), R * std::exp(dl), 1e-14);
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
  EXPECT_CONTAINS(
      mesh_error_message([] {
        make_annulus_mesh({.inner_radius = 1.0, .outer_radius = 1.0 + 1e-9, .radial_layers = 2});
      }),
      "at most 1e6 vertices");
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
