// Point-triangle distance: exact configurations for every region, brute-force sampling of the
// closest point, finite-difference checks of the gradient and Hessian with the region held
// fixed, invariances, slivers, scale sweeps and degenerate input.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <random>
#include <stdexcept>
#include <string>

#include "libshell/contact/point_triangle_distance.hpp"
#include "tests/support/expect_invalid_argument.hpp"
#include "tests/support/finite_difference_errors.hpp"
#include "tests/support/random_rigid_motion.hpp"

namespace growshell {
namespace {

using Eigen::Vector3d;
using PT = PointTriangleRegion;
using test_support::expect_invalid_argument_containing;
using test_support::FdErrors;
using test_support::kFdStep;
using test_support::kFdTolerance;
using test_support::random_motion;
using test_support::random_point;

constexpr std::array<PT, 7> kAllPointTriangleRegions = {
    PT::Face, PT::EdgeAB, PT::EdgeBC, PT::EdgeCA, PT::VertexA, PT::VertexB, PT::VertexC};

/// (p, a, b, c) stacked as in the library's 12-entry order.
Vector12d stack_point_triangle(const Vector3d& p, const Vector3d& a, const Vector3d& b,
                               const Vector3d& c) {
  Vector12d x;
  x << p, a, b, c;
  return x;
}

double point_triangle_value_at(const Vector12d& x, PT region) {
  return point_triangle_distance_squared(x.segment<3>(0), x.segment<3>(3), x.segment<3>(6),
                                         x.segment<3>(9), region);
}
Vector12d point_triangle_gradient_at(const Vector12d& x, PT region) {
  return point_triangle_distance_squared_gradient(x.segment<3>(0), x.segment<3>(3), x.segment<3>(6),
                                                  x.segment<3>(9), region);
}
Matrix12d point_triangle_hessian_at(const Vector12d& x, PT region) {
  return point_triangle_distance_squared_hessian(x.segment<3>(0), x.segment<3>(3), x.segment<3>(6),
                                                 x.segment<3>(9), region);
}
PointTriangleResult point_triangle_closest_at(const Vector12d& x) {
  return point_triangle_closest(x.segment<3>(0), x.segment<3>(3), x.segment<3>(6), x.segment<3>(9));
}

FdErrors point_triangle_fd_errors(const Vector12d& x, PT region, double step) {
  return test_support::finite_difference_errors(
      x, step, [&](const Vector12d& y) { return point_triangle_value_at(y, region); },
      [&](const Vector12d& y) { return point_triangle_gradient_at(y, region); },
      [&](const Vector12d& y) { return point_triangle_hessian_at(y, region); });
}

/// Smallest distance from p to a barycentric grid of n subdivisions of the triangle, and the
/// covering radius of that grid: a point of a triangle with longest edge l lies within
/// l / sqrt(3) of a vertex (min_i |x - v_i|^2 <= sum_i lambda_i |x - v_i|^2
/// = sum_{i<j} lambda_i lambda_j |v_i - v_j|^2 <= l^2 / 3), applied to the grid cells.
struct Sampled {
  double min_distance;
  double covering_radius;
};

Sampled sample_triangle(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c,
                        int n) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; i + j <= n; ++j) {
      const double u = double(i) / n, v = double(j) / n;
      const Vector3d x = (1.0 - u - v) * a + u * b + v * c;
      best = std::min(best, (p - x).norm());
    }
  }
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  return {best, longest / n / std::sqrt(3.0)};
}

// ---- Exact configurations -------------------------------------------------------------------

struct PointTriangleCase {
  Vector3d p;
  PT region;
  double distance_squared;
  Vector3d barycentric;
};

// Unit right triangle a = 0, b = e_x, c = e_y; one point per region, distances by hand.
const std::array<PointTriangleCase, 8> kPointTriangleCases = {{
    {{0.2, 0.3, 0.5}, PT::Face, 0.25, {0.5, 0.2, 0.3}},
    {{0.25, 0.25, 0.0}, PT::Face, 0.0, {0.5, 0.25, 0.25}},
    {{0.5, -1.0, 2.0}, PT::EdgeAB, 5.0, {0.5, 0.5, 0.0}},      // 1^2 + 2^2
    {{1.0, 1.0, 1.0}, PT::EdgeBC, 1.5, {0.0, 0.5, 0.5}},       // 2 (1/2)^2 + 1
    {{-2.0, 0.25, -1.0}, PT::EdgeCA, 5.0, {0.75, 0.0, 0.25}},  // 2^2 + 1
    {{-1.0, -2.0, 3.0}, PT::VertexA, 14.0, {1.0, 0.0, 0.0}},
    {{2.0, -1.0, 0.0}, PT::VertexB, 2.0, {0.0, 1.0, 0.0}},
    {{-1.0, 3.0, 0.5}, PT::VertexC, 5.25, {0.0, 0.0, 1.0}},
}};

TEST(PointTriangleDistance, ExactConfigurationsHitEveryRegion) {
  const Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  std::mt19937 rng(3);
  std::map<PT, int> hits;
  for (const PointTriangleCase& ex : kPointTriangleCases) {
    // Identity frame, then three random rigid frames: only rounding may differ (1e-13 relative
    // on distances of O(1)-O(10) with coordinates up to ~10).
    for (int frame = 0; frame < 4; ++frame) {
      const Eigen::Isometry3d T = frame == 0 ? Eigen::Isometry3d::Identity() : random_motion(rng);
      const PointTriangleResult r = point_triangle_closest(T * ex.p, T * a, T * b, T * c);
      SCOPED_TRACE(std::string("expected ") + to_string(ex.region) + ", frame " +
                   std::to_string(frame));
      EXPECT_EQ(r.region, ex.region) << to_string(r.region);
      EXPECT_NEAR(r.distance_squared, ex.distance_squared, 1e-13 * (1.0 + ex.distance_squared));
      EXPECT_NEAR((r.barycentric - ex.barycentric).cwiseAbs().maxCoeff(), 0.0, 1e-13);
      const Vector3d expected_point =
          T * (ex.barycentric(0) * a + ex.barycentric(1) * b + ex.barycentric(2) * c);
      EXPECT_NEAR((r.closest_point - expected_point).norm(), 0.0, 1e-13);
      EXPECT_EQ(classify_point_triangle(T * ex.p, T * a, T * b, T * c), ex.region);
      EXPECT_NEAR(point_triangle_distance_squared(T * ex.p, T * a, T * b, T * c),
                  ex.distance_squared, 1e-13 * (1.0 + ex.distance_squared));
    }
    ++hits[ex.region];
  }
  for (PT region : kAllPointTriangleRegions) EXPECT_GT(hits[region], 0) << to_string(region);
}

// ---- Brute force ----------------------------------------------------------------------------

TEST(PointTriangleDistance, AgreesWithBruteForceSampling) {
  std::mt19937 rng(11);
  std::map<PT, int> hits;
  double worst_gap = 0.0;  // largest (sampled min - distance) / covering radius seen
  constexpr int kConfigurations = 400;
  constexpr int kSubdivisions = 60;
  for (int trial = 0; trial < kConfigurations; ++trial) {
    const Vector3d a = random_point(rng, 1.0), b = random_point(rng, 1.0),
                   c = random_point(rng, 1.0), p = random_point(rng, 2.0);
    const PointTriangleResult r = point_triangle_closest(p, a, b, c);
    ++hits[r.region];
    const double d = std::sqrt(r.distance_squared);
    const Sampled s = sample_triangle(p, a, b, c, kSubdivisions);
    // The exact minimum can exceed no sample (1e-12 for rounding), and lies at most the grid's
    // covering radius below the best sample (triangle inequality).
    EXPECT_LE(d, s.min_distance + 1e-12) << "trial " << trial;
    EXPECT_GE(d, s.min_distance - s.covering_radius - 1e-12) << "trial " << trial;
    worst_gap = std::max(worst_gap, (s.min_distance - d) / s.covering_radius);

    // The reported closest point is on the triangle and realises the distance.
    EXPECT_GE(r.barycentric.minCoeff(), 0.0);
    EXPECT_NEAR(r.barycentric.sum(), 1.0, 1e-14);
    const Vector3d from_barycentric =
        r.barycentric(0) * a + r.barycentric(1) * b + r.barycentric(2) * c;
    EXPECT_NEAR((r.closest_point - from_barycentric).norm(), 0.0, 1e-13);
    EXPECT_NEAR((p - r.closest_point).squaredNorm(), r.distance_squared, 1e-13);
    // The region's smooth function reproduces the distance.
    EXPECT_NEAR(point_triangle_distance_squared(p, a, b, c, r.region), r.distance_squared,
                1e-13 * (1.0 + r.distance_squared));
  }
  for (PT region : kAllPointTriangleRegions) EXPECT_GT(hits[region], 0) << to_string(region);
  std::cout << "[ measured ] brute force: worst (sampled - exact) / covering radius = " << worst_gap
            << " over " << kConfigurations << " configurations\n";
}

TEST(PointTriangleDistance, SliverTrianglesAgreeWithBruteForce) {
  // Twice the area / longest edge^2 down to 1e-10 (a 1e-10 rad corner), still above the
  // degeneracy threshold 1e-12: classification must stay consistent with sampling.
  std::mt19937 rng(5);
  for (double thinness : {1e-3, 1e-6, 1e-10}) {
    for (int trial = 0; trial < 40; ++trial) {
      const Eigen::Isometry3d T = random_motion(rng);
      const Vector3d a = T * Vector3d(0, 0, 0), b = T * Vector3d(1, 0, 0),
                     c = T * Vector3d(0.3, thinness, 0);
      const Vector3d p = T * random_point(rng, 1.5);
      const PointTriangleResult r = point_triangle_closest(p, a, b, c);
      const Sampled s = sample_triangle(p, a, b, c, 60);
      const double d = std::sqrt(r.distance_squared);
      EXPECT_LE(d, s.min_distance + 1e-12) << "thinness " << thinness << " trial " << trial;
      EXPECT_GE(d, s.min_distance - s.covering_radius - 1e-12);
      EXPECT_NEAR((p - r.closest_point).squaredNorm(), r.distance_squared, 1e-12);
    }
  }
}

// ---- Derivatives with the region held fixed ------------------------------------------------

/// Random configurations, collected until every region has `per_region` of them. Triangles
/// with twice-area / longest-edge^2 < 0.1 are skipped so that third derivatives (which set the
/// finite-difference truncation error) stay O(1); slivers and scales have their own tests.
std::map<PT, std::vector<Vector12d>> point_triangle_configurations(std::mt19937& rng,
                                                                   int per_region) {
  std::map<PT, std::vector<Vector12d>> out;
  for (int attempt = 0; attempt < 100000; ++attempt) {
    const Vector3d a = random_point(rng, 1.0), b = random_point(rng, 1.0),
                   c = random_point(rng, 1.0), p = random_point(rng, 2.0);
    const double longest =
        std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    if ((b - a).cross(c - a).norm() < 0.1 * longest) continue;
    const PT region = classify_point_triangle(p, a, b, c);
    if (static_cast<int>(out[region].size()) < per_region)
      out[region].push_back(stack_point_triangle(p, a, b, c));
    bool done = true;
    for (PT r : kAllPointTriangleRegions)
      done = done && static_cast<int>(out[r].size()) >= per_region;
    if (done) break;
  }
  return out;
}

TEST(PointTriangleDistance, DerivativesMatchFiniteDifferencesInEveryRegion) {
  std::mt19937 rng(17);
  const auto configurations = point_triangle_configurations(rng, 30);
  FdErrors worst;
  for (PT region : kAllPointTriangleRegions) {
    ASSERT_EQ(configurations.at(region).size(), 30u) << to_string(region);
    for (const Vector12d& x : configurations.at(region)) {
      const FdErrors e = point_triangle_fd_errors(x, region, kFdStep);
      EXPECT_LT(e.gradient, kFdTolerance) << to_string(region);
      EXPECT_LT(e.hessian, kFdTolerance) << to_string(region);
      worst.gradient = std::max(worst.gradient, e.gradient);
      worst.hessian = std::max(worst.hessian, e.hessian);
    }
  }
  std::cout << "[ measured ] worst relative FD error: gradient " << worst.gradient << ", Hessian "
            << worst.hessian << " (tolerance " << kFdTolerance << ")\n";
}

TEST(PointTriangleDistance, DerivativeIdentities) {
  // Exact identities of every region's function f(x), checked to rounding (1e-12 relative):
  //  - Hessian symmetric;
  //  - translation invariance: the four 3-blocks of the gradient sum to zero, and so do the
  //    block rows of the Hessian;
  //  - rotation invariance: sum_i x_i x g_i = 0;
  //  - homogeneity of degree 2 (about the origin, given translation invariance):
  //    x . g = 2 f and H x = g.
  std::mt19937 rng(23);
  const auto configurations = point_triangle_configurations(rng, 10);
  for (PT region : kAllPointTriangleRegions) {
    for (const Vector12d& x : configurations.at(region)) {
      SCOPED_TRACE(to_string(region));
      const double f = point_triangle_value_at(x, region);
      const Vector12d g = point_triangle_gradient_at(x, region);
      const Matrix12d H = point_triangle_hessian_at(x, region);
      const double gs = g.cwiseAbs().maxCoeff(), hs = H.cwiseAbs().maxCoeff();
      // The one-call form is the same computation, so bitwise equal.
      const ValueGradientHessian<12> all = point_triangle_distance_squared_derivatives(
          x.segment<3>(0), x.segment<3>(3), x.segment<3>(6), x.segment<3>(9), region);
      EXPECT_EQ(all.value, f);
      EXPECT_EQ(all.gradient, g);
      EXPECT_EQ(all.hessian, H);
      EXPECT_LE((H - H.transpose()).cwiseAbs().maxCoeff(), 1e-14 * hs);
      Vector3d block_sum = Vector3d::Zero(), torque = Vector3d::Zero();
      Eigen::Matrix<double, 12, 3> hessian_block_sum = Eigen::Matrix<double, 12, 3>::Zero();
      for (int k = 0; k < 4; ++k) {
        block_sum += g.segment<3>(3 * k);
        torque += x.segment<3>(3 * k).cross(g.segment<3>(3 * k));
        hessian_block_sum += H.middleCols<3>(3 * k);
      }
      EXPECT_LE(block_sum.cwiseAbs().maxCoeff(), 1e-12 * gs);
      EXPECT_LE(hessian_block_sum.cwiseAbs().maxCoeff(), 1e-12 * hs);
      EXPECT_LE(torque.cwiseAbs().maxCoeff(), 1e-12 * gs * x.cwiseAbs().maxCoeff());
      EXPECT_NEAR(x.dot(g), 2.0 * f, 1e-12 * gs * x.cwiseAbs().maxCoeff());
      EXPECT_LE((H * x - g).cwiseAbs().maxCoeff(), 1e-12 * hs * x.cwiseAbs().maxCoeff());
    }
  }
}

TEST(PointTriangleDistance, DerivativesAcrossScalesAndFarFromOrigin) {
  // f is homogeneous of degree 2 in the coordinates, so with the step scaled like the
  // configuration (h = 1e-6 L) the relative FD error is scale-free; an offset of 1e3 L from
  // the origin rounds coordinate differences at ~1e3 eps L, at worst ~1e-7 after the 1/h of
  // the quotient (in practice those errors are nearly equal at x +- h and cancel; measured
  // ~4e-10), still inside the 1e-6 tolerance. The FD quotient divides by the step actually
  // taken after rounding x +- h.
  std::mt19937 rng(29);
  const auto configurations = point_triangle_configurations(rng, 4);
  FdErrors worst;
  for (double scale : {1e-3, 1.0, 1e3}) {
    for (double offset : {0.0, 1e3}) {
      for (PT region : kAllPointTriangleRegions) {
        for (const Vector12d& x0 : configurations.at(region)) {
          Vector12d x = scale * x0;
          for (int k = 0; k < 4; ++k) x.segment<3>(3 * k) += Vector3d::Constant(offset * scale);
          ASSERT_EQ(point_triangle_closest_at(x).region, region)
              << "scale " << scale << " offset " << offset;
          const FdErrors e = point_triangle_fd_errors(x, region, kFdStep * scale);
          EXPECT_LT(e.gradient, kFdTolerance) << to_string(region) << " scale " << scale;
          EXPECT_LT(e.hessian, kFdTolerance) << to_string(region) << " scale " << scale;
          worst.gradient = std::max(worst.gradient, e.gradient);
          worst.hessian = std::max(worst.hessian, e.hessian);
          // Homogeneity: g scales like L, H is scale-free (rounding only).
          const Vector12d g1 = point_triangle_gradient_at(scale * x0, region);
          EXPECT_LE((g1 - scale * point_triangle_gradient_at(x0, region)).cwiseAbs().maxCoeff(),
                    1e-12 * g1.cwiseAbs().maxCoeff());
        }
      }
    }
  }
  std::cout << "[ measured ] scales 1e-3..1e3, offset 0 or 1e3 L: worst relative FD error "
            << "gradient " << worst.gradient << ", Hessian " << worst.hessian << "\n";
}

TEST(PointTriangleDistance, FaceDerivativesOfSliversStayFiniteAndAccurate) {
  // Sliver (0,0,0), (1,0,0), (0.4, thinness, 0) with p above its interior, in random frames.
  // The face function's Hessian grows like 1/thinness^2 and its third derivatives like
  // 1/thinness^3 (the normal turns by dx / thinness), so the FD steps shrink with thinness:
  //  - Hessian (differencing the analytic gradient): h = 1e-4 thinness, truncation
  //    ~ (h / thinness)^2 = 1e-8 relative; checked down to thinness 1e-6.
  //  - gradient (differencing the value): the gradient stays O(1) while f^(3) ~ 1/thinness^3,
  //    so truncation is ~ h^2 / thinness^3, and h = 1e-4 thinness^(3/2) makes it ~1e-8. But the
  //    value itself carries relative rounding ~ eps / thinness (forming n = (b - a) x (c - a)
  //    from O(1) coordinates), amplified by 1/h in the FD quotient: measured, it passes 1e-6
  //    near thinness 1e-3. So the gradient is FD-checked only down to thinness 1e-2; below,
  //    it is tied to the checked Hessian by the exact identity H (x - centroid) = g
  //    (homogeneity of degree 2 plus translation invariance), to 1e-12 of |H| |x - centroid|.
  // Down to thinness 1e-9 the derivatives must be finite and the Hessian symmetric.
  std::mt19937 rng(31);
  FdErrors worst;
  for (int trial = 0; trial < 5; ++trial) {
    for (double thinness : {1e-1, 1e-2, 1e-3, 1e-4, 1e-6, 1e-9}) {
      SCOPED_TRACE("thinness " + std::to_string(thinness));
      const Eigen::Isometry3d T = random_motion(rng);
      const Vector3d a = T * Vector3d(0, 0, 0), b = T * Vector3d(1, 0, 0),
                     c = T * Vector3d(0.4, thinness, 0);
      const Vector3d p = T * Vector3d(0.5, 0.3 * thinness, 0.7);
      const Vector12d x = stack_point_triangle(p, a, b, c);
      const Vector12d g = point_triangle_gradient_at(x, PT::Face);
      const Matrix12d H = point_triangle_hessian_at(x, PT::Face);
      EXPECT_TRUE(H.allFinite() && g.allFinite());
      EXPECT_LE((H - H.transpose()).cwiseAbs().maxCoeff(), 1e-14 * H.cwiseAbs().maxCoeff());
      if (thinness < 1e-6) continue;  // the sliver's normal is then only known to ~eps/thinness
      // (At thinness 1e-9 rounding can move p's projection off the sliver, so no region check.)
      ASSERT_EQ(classify_point_triangle(p, a, b, c), PT::Face);
      Vector12d centred = x;
      const Vector3d centroid = (p + a + b + c) / 4.0;
      for (int k = 0; k < 4; ++k) centred.segment<3>(3 * k) -= centroid;
      EXPECT_LE((H * centred - g).cwiseAbs().maxCoeff(),
                1e-12 * H.cwiseAbs().maxCoeff() * centred.cwiseAbs().maxCoeff());
      const FdErrors e_hessian = point_triangle_fd_errors(x, PT::Face, 1e-4 * thinness);
      EXPECT_LT(e_hessian.hessian, kFdTolerance);
      worst.hessian = std::max(worst.hessian, e_hessian.hessian);
      if (thinness >= 1e-2) {
        const FdErrors e_gradient =
            point_triangle_fd_errors(x, PT::Face, 1e-4 * thinness * std::sqrt(thinness));
        EXPECT_LT(e_gradient.gradient, kFdTolerance);
        worst.gradient = std::max(worst.gradient, e_gradient.gradient);
      }
    }
  }
  std::cout << "[ measured ] slivers: worst relative FD error gradient " << worst.gradient
            << " (thinness >= 1e-2), Hessian " << worst.hessian << " (thinness >= 1e-6)\n";
}

// ---- Degenerate input ------------------------------------------------------------------------

TEST(PointTriangleDistance, DegenerateInputThrowsNamingTheProblem) {
  const Vector3d p(0.1, 0.2, 0.3), a(0.1, 0.2, 0.3), b(0.7, 1.1, 0.4);
  // Collinear (rounded, so |n| is ~1e-17 rather than exactly 0), coincident, a single point.
  const Vector3d collinear = a + 0.3 * (b - a);
  expect_invalid_argument_containing([&] { point_triangle_closest(p, a, b, collinear); },
                                     "zero area");
  expect_invalid_argument_containing([&] { point_triangle_closest(p, a, b, b); }, "zero area");
  expect_invalid_argument_containing([&] { point_triangle_closest(p, a, a, a); }, "zero area");
  const Vector3d o = Vector3d::Zero();
  // Just below the threshold (twice area 1e-13 of longest edge^2) throws, just above does not.
  expect_invalid_argument_containing(
      [&] { classify_point_triangle(p, o, Vector3d(1, 0, 0), Vector3d(0.5, 1e-13, 0)); },
      "zero area");
  EXPECT_NO_THROW(classify_point_triangle(p, o, Vector3d(1, 0, 0), Vector3d(0.5, 1e-11, 0)));
  // The region-held functions validate too.
  for (PT region : kAllPointTriangleRegions) {
    expect_invalid_argument_containing(
        [&] { point_triangle_distance_squared_gradient(p, a, b, collinear, region); }, "zero area");
    expect_invalid_argument_containing(
        [&] { point_triangle_distance_squared_hessian(p, a, b, collinear, region); }, "zero area");
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  expect_invalid_argument_containing(
      [&] { point_triangle_closest(Vector3d(nan, 0, 0), o, b, Vector3d(0, 1, 0)); }, "point p");
  expect_invalid_argument_containing([&] { point_triangle_closest(p, o, b, Vector3d(0, inf, 0)); },
                                     "point c");
  expect_invalid_argument_containing([&] { point_line_distance_squared_derivatives(p, a, a); },
                                     "coincide");
  expect_invalid_argument_containing([&] { plane_distance_squared_derivatives(p, b, 2.0 * b); },
                                     "parallel");
}

}  // namespace
}  // namespace growshell
