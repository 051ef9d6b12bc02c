// Edge-edge distance: exact configurations for every region, brute-force sampling of the
// closest pair, finite-difference checks of the gradient and Hessian with the region held
// fixed, invariances, (nearly) parallel edges, the IPC mollifier, and degenerate input.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <random>
#include <stdexcept>
#include <string>

#include "libshell/contact/edge_edge_distance.hpp"
#include "tests/support/expect_invalid_argument.hpp"
#include "tests/support/finite_difference_errors.hpp"
#include "tests/support/random_rigid_motion.hpp"

namespace growshell {
namespace {

using Eigen::Vector3d;
using EE = EdgeEdgeRegion;
using test_support::expect_invalid_argument_containing;
using test_support::FdErrors;
using test_support::finite_difference_errors;
using test_support::kFdStep;
using test_support::kFdTolerance;
using test_support::random_motion;
using test_support::random_point;

constexpr std::array<EE, 9> kAllEdgeEdgeRegions = {EE::EdgeEdge, EE::P0EdgeQ, EE::P1EdgeQ,
                                                   EE::Q0EdgeP,  EE::Q1EdgeP, EE::P0Q0,
                                                   EE::P0Q1,     EE::P1Q0,    EE::P1Q1};

/// (p0, p1, q0, q1) stacked as in the library's 12-entry order.
Vector12d stack_edge_pair(const Vector3d& p0, const Vector3d& p1, const Vector3d& q0,
                          const Vector3d& q1) {
  Vector12d x;
  x << p0, p1, q0, q1;
  return x;
}

double edge_edge_value_at(const Vector12d& x, EE region) {
  return edge_edge_distance_squared(x.segment<3>(0), x.segment<3>(3), x.segment<3>(6),
                                    x.segment<3>(9), region);
}
Vector12d edge_edge_gradient_at(const Vector12d& x, EE region) {
  return edge_edge_distance_squared_gradient(x.segment<3>(0), x.segment<3>(3), x.segment<3>(6),
                                             x.segment<3>(9), region);
}
Matrix12d edge_edge_hessian_at(const Vector12d& x, EE region) {
  return edge_edge_distance_squared_hessian(x.segment<3>(0), x.segment<3>(3), x.segment<3>(6),
                                            x.segment<3>(9), region);
}
EdgeEdgeResult edge_edge_closest_at(const Vector12d& x) {
  return edge_edge_closest(x.segment<3>(0), x.segment<3>(3), x.segment<3>(6), x.segment<3>(9));
}

FdErrors edge_edge_fd_errors(const Vector12d& x, EE region, double step) {
  return finite_difference_errors(
      x, step, [&](const Vector12d& y) { return edge_edge_value_at(y, region); },
      [&](const Vector12d& y) { return edge_edge_gradient_at(y, region); },
      [&](const Vector12d& y) { return edge_edge_hessian_at(y, region); });
}

double sin_squared_angle(const Vector3d& e0, const Vector3d& e1) {
  return e0.cross(e1).squaredNorm() / (e0.squaredNorm() * e1.squaredNorm());
}

// ---- Exact configurations -------------------------------------------------------------------

struct EdgeEdgeCase {
  const char* name;
  Vector3d p0, p1, q0, q1;
  EE region;
  double distance_squared;
  double s, t;
  /// Two candidates at exactly the same distance: only the identity frame decides the tie by
  /// the documented order; in rotated frames rounding may pick the other one.
  bool tie = false;
};

// Distances by hand. "Skew" pairs: P along z above the x axis, Q on the x axis, so the lines
// meet at the origin outside one or both segments.
const std::array<EdgeEdgeCase, 12> kEdgeEdgeCases = {{
    {"crossing", {-1, 0, 0}, {1, 0, 0}, {0, -1, 1}, {0, 1, 1}, EE::EdgeEdge, 1.0, 0.5, 0.5},
    {"p0 over Q", {0, 0, 1}, {0, 0, 3}, {-1, 0, 0}, {1, 0, 0}, EE::P0EdgeQ, 1.0, 0.0, 0.5},
    {"p1 over Q", {0, 0, 3}, {0, 0, 1}, {-1, 0, 0}, {1, 0, 0}, EE::P1EdgeQ, 1.0, 1.0, 0.5},
    {"q0 over P", {-1, 0, 0}, {1, 0, 0}, {0, 0, 1}, {0, 0, 3}, EE::Q0EdgeP, 1.0, 0.5, 0.0},
    {"q1 over P", {-1, 0, 0}, {1, 0, 0}, {0, 0, 3}, {0, 0, 1}, EE::Q1EdgeP, 1.0, 0.5, 1.0},
    {"p0-q0", {0, 0, 1}, {0, 0, 3}, {1, 0, 0}, {3, 0, 0}, EE::P0Q0, 2.0, 0.0, 0.0},
    {"p0-q1", {0, 0, 1}, {0, 0, 3}, {3, 0, 0}, {1, 0, 0}, EE::P0Q1, 2.0, 0.0, 1.0},
    {"p1-q0", {0, 0, 3}, {0, 0, 1}, {1, 0, 0}, {3, 0, 0}, EE::P1Q0, 2.0, 1.0, 0.0},
    {"p1-q1", {0, 0, 3}, {0, 0, 1}, {3, 0, 0}, {1, 0, 0}, EE::P1Q1, 2.0, 1.0, 1.0},
    // Parallel edges: the boundary candidates in the order p0, p1, q0, q1 decide ties.
    {"parallel overlapping",
     {0, 0, 0},
     {2, 0, 0},
     {1, 1, 0},
     {3, 1, 0},
     EE::P1EdgeQ,
     1.0,
     1.0,
     0.5,
     true},
    {"parallel disjoint", {0, 0, 0}, {1, 0, 0}, {2, 1, 0}, {3, 1, 0}, EE::P1Q0, 2.0, 1.0, 0.0},
    {"collinear overlapping",
     {0, 0, 0},
     {2, 0, 0},
     {1, 0, 0},
     {3, 0, 0},
     EE::P1EdgeQ,
     0.0,
     1.0,
     0.5,
     true},
}};

TEST(EdgeEdgeDistance, ExactConfigurationsHitEveryRegion) {
  std::mt19937 rng(3);
  std::map<EE, int> hits;
  for (const EdgeEdgeCase& ex : kEdgeEdgeCases) {
    // Identity frame, then random rigid frames; only the identity frame keeps parallel edges
    // exactly parallel, and rounding in the others (~1e-16) stays far below the threshold.
    for (int frame = 0; frame < 4; ++frame) {
      SCOPED_TRACE(std::string(ex.name) + ", frame " + std::to_string(frame));
      const Eigen::Isometry3d T = frame == 0 ? Eigen::Isometry3d::Identity() : random_motion(rng);
      const EdgeEdgeResult r = edge_edge_closest(T * ex.p0, T * ex.p1, T * ex.q0, T * ex.q1);
      EXPECT_NEAR(r.distance_squared, ex.distance_squared, 1e-13 * (1.0 + ex.distance_squared));
      EXPECT_NEAR(edge_edge_distance_squared(T * ex.p0, T * ex.p1, T * ex.q0, T * ex.q1),
                  ex.distance_squared, 1e-13 * (1.0 + ex.distance_squared));
      if (ex.tie && frame > 0) continue;
      EXPECT_EQ(r.region, ex.region) << to_string(r.region);
      EXPECT_NEAR(r.s, ex.s, 1e-13);
      EXPECT_NEAR(r.t, ex.t, 1e-13);
      EXPECT_NEAR((r.closest_point_p - T * (ex.p0 + ex.s * (ex.p1 - ex.p0))).norm(), 0.0, 1e-13);
      EXPECT_NEAR((r.closest_point_q - T * (ex.q0 + ex.t * (ex.q1 - ex.q0))).norm(), 0.0, 1e-13);
      EXPECT_EQ(classify_edge_edge(T * ex.p0, T * ex.p1, T * ex.q0, T * ex.q1), ex.region);
    }
    ++hits[ex.region];
  }
  for (EE region : kAllEdgeEdgeRegions) EXPECT_GT(hits[region], 0) << to_string(region);
}

// ---- Brute force ----------------------------------------------------------------------------

TEST(EdgeEdgeDistance, AgreesWithBruteForceSampling) {
  // Grid s_i = i/n, t_j = j/n: every (s, t) is within 1/(2n) of a grid node in each parameter,
  // so the sampled minimum exceeds the exact one by at most (|e0| + |e1|) / (2n).
  // A quarter of the pairs are made parallel (q1 - q0 a multiple of p1 - p0) to exercise the
  // boundary-only path.
  std::mt19937 rng(11);
  constexpr int kConfigurations = 400;
  constexpr int kSubdivisions = 100;
  std::map<EE, int> hits;
  double worst_gap = 0.0;
  for (int trial = 0; trial < kConfigurations; ++trial) {
    const Vector3d p0 = random_point(rng, 1.0), p1 = random_point(rng, 1.0),
                   q0 = random_point(rng, 1.0);
    const Vector3d q1 = trial % 4 == 3 ? Vector3d(q0 + 0.7 * (p1 - p0)) : random_point(rng, 1.0);
    const EdgeEdgeResult r = edge_edge_closest(p0, p1, q0, q1);
    ++hits[r.region];
    double sampled = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= kSubdivisions; ++i) {
      const Vector3d x = p0 + (double(i) / kSubdivisions) * (p1 - p0);
      for (int j = 0; j <= kSubdivisions; ++j) {
        sampled = std::min(sampled, (x - q0 - (double(j) / kSubdivisions) * (q1 - q0)).norm());
      }
    }
    const double bound = ((p1 - p0).norm() + (q1 - q0).norm()) / (2.0 * kSubdivisions);
    const double d = std::sqrt(r.distance_squared);
    EXPECT_LE(d, sampled + 1e-12) << "trial " << trial;
    EXPECT_GE(d, sampled - bound - 1e-12) << "trial " << trial;
    worst_gap = std::max(worst_gap, (sampled - d) / bound);

    EXPECT_GE(r.s, 0.0);
    EXPECT_LE(r.s, 1.0);
    EXPECT_GE(r.t, 0.0);
    EXPECT_LE(r.t, 1.0);
    EXPECT_NEAR((r.closest_point_p - r.closest_point_q).squaredNorm(), r.distance_squared, 1e-13);
    if (trial % 4 != 3) {
      EXPECT_NEAR(edge_edge_distance_squared(p0, p1, q0, q1, r.region), r.distance_squared,
                  1e-12 * (1.0 + r.distance_squared));
    }
  }
  for (EE region : kAllEdgeEdgeRegions) EXPECT_GT(hits[region], 0) << to_string(region);
  std::cout << "[ measured ] brute force: worst (sampled - exact) / sampling bound = " << worst_gap
            << " over " << kConfigurations << " configurations\n";
}

// ---- Derivatives with the region held fixed ------------------------------------------------

/// Random pairs collected until every region has `per_region`. Pairs closer to parallel than
/// sin^2 = 0.05 or with an edge shorter than 0.2 are skipped, so third derivatives stay O(1);
/// near-parallel pairs have their own test.
std::map<EE, std::vector<Vector12d>> edge_pair_configurations(std::mt19937& rng, int per_region) {
  std::map<EE, std::vector<Vector12d>> out;
  for (int attempt = 0; attempt < 100000; ++attempt) {
    const Vector3d p0 = random_point(rng, 1.0), p1 = random_point(rng, 1.0),
                   q0 = random_point(rng, 1.0), q1 = random_point(rng, 1.0);
    if ((p1 - p0).norm() < 0.2 || (q1 - q0).norm() < 0.2) continue;
    if (sin_squared_angle(p1 - p0, q1 - q0) < 0.05) continue;
    const EE region = classify_edge_edge(p0, p1, q0, q1);
    if (static_cast<int>(out[region].size()) < per_region) {
      out[region].push_back(stack_edge_pair(p0, p1, q0, q1));
    }
    bool done = true;
    for (EE r : kAllEdgeEdgeRegions) done = done && static_cast<int>(out[r].size()) >= per_region;
    if (done) break;
  }
  return out;
}

TEST(EdgeEdgeDistance, DerivativesMatchFiniteDifferencesInEveryRegion) {
  std::mt19937 rng(17);
  const auto configurations = edge_pair_configurations(rng, 30);
  FdErrors worst;
  for (EE region : kAllEdgeEdgeRegions) {
    ASSERT_EQ(configurations.at(region).size(), 30u) << to_string(region);
    for (const Vector12d& x : configurations.at(region)) {
      const FdErrors e = edge_edge_fd_errors(x, region, kFdStep);
      EXPECT_LT(e.gradient, kFdTolerance) << to_string(region);
      EXPECT_LT(e.hessian, kFdTolerance) << to_string(region);
      worst.gradient = std::max(worst.gradient, e.gradient);
      worst.hessian = std::max(worst.hessian, e.hessian);
    }
  }
  std::cout << "[ measured ] worst relative FD error: gradient " << worst.gradient << ", Hessian "
            << worst.hessian << " (tolerance " << kFdTolerance << ")\n";
}

TEST(EdgeEdgeDistance, DerivativeIdentities) {
  // As for the point-triangle distance: symmetric Hessian; translation invariance (gradient
  // blocks and Hessian block columns sum to zero); rotation invariance (sum x_i x g_i = 0);
  // homogeneity of degree 2 (x . g = 2 f, H x = g). All to rounding, 1e-12 relative.
  std::mt19937 rng(23);
  const auto configurations = edge_pair_configurations(rng, 10);
  for (EE region : kAllEdgeEdgeRegions) {
    for (const Vector12d& x : configurations.at(region)) {
      SCOPED_TRACE(to_string(region));
      const double f = edge_edge_value_at(x, region);
      const Vector12d g = edge_edge_gradient_at(x, region);
      const Matrix12d H = edge_edge_hessian_at(x, region);
      const double gs = g.cwiseAbs().maxCoeff(), hs = H.cwiseAbs().maxCoeff();
      const double xs = x.cwiseAbs().maxCoeff();
      // The one-call form is the same computation, so bitwise equal.
      const ValueGradientHessian<12> all = edge_edge_distance_squared_derivatives(
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
      EXPECT_LE(torque.cwiseAbs().maxCoeff(), 1e-12 * gs * xs);
      EXPECT_NEAR(x.dot(g), 2.0 * f, 1e-12 * gs * xs);
      EXPECT_LE((H * x - g).cwiseAbs().maxCoeff(), 1e-12 * hs * xs);
    }
  }
}

TEST(EdgeEdgeDistance, DerivativesAcrossScalesAndFarFromOrigin) {
  // Homogeneous of degree 2: with h = 1e-6 L the relative FD error does not depend on L; an
  // offset of 1e3 L rounds coordinate differences at ~1e3 eps L, at worst ~1e-7 after the 1/h
  // of the quotient (those errors nearly cancel between x +- h; measured ~4e-10), still inside
  // the 1e-6 tolerance.
  std::mt19937 rng(29);
  const auto configurations = edge_pair_configurations(rng, 4);
  FdErrors worst;
  for (double scale : {1e-3, 1.0, 1e3}) {
    for (double offset : {0.0, 1e3}) {
      for (EE region : kAllEdgeEdgeRegions) {
        for (const Vector12d& x0 : configurations.at(region)) {
          Vector12d x = scale * x0;
          for (int k = 0; k < 4; ++k) x.segment<3>(3 * k) += Vector3d::Constant(offset * scale);
          ASSERT_EQ(edge_edge_closest_at(x).region, region)
              << "scale " << scale << " offset " << offset;
          const FdErrors e = edge_edge_fd_errors(x, region, kFdStep * scale);
          EXPECT_LT(e.gradient, kFdTolerance) << to_string(region) << " scale " << scale;
          EXPECT_LT(e.hessian, kFdTolerance) << to_string(region) << " scale " << scale;
          worst.gradient = std::max(worst.gradient, e.gradient);
          worst.hessian = std::max(worst.hessian, e.hessian);
          const Vector12d g1 = edge_edge_gradient_at(scale * x0, region);
          EXPECT_LE((g1 - scale * edge_edge_gradient_at(x0, region)).cwiseAbs().maxCoeff(),
                    1e-12 * g1.cwiseAbs().maxCoeff());
        }
      }
    }
  }
  std::cout << "[ measured ] scales 1e-3..1e3, offset 0 or 1e3 L: worst relative FD error "
            << "gradient " << worst.gradient << ", Hessian " << worst.hessian << "\n";
}

// ---- (Nearly) parallel edges ---------------------------------------------------------------

/// P = (0,0,0)-(1,0,0); Q of length 1.2 centred at (0.5, 0, 0.3), turned by `angle` about z.
/// The lines are 0.3 apart and their closest points are interior (s = t = 0.5), so the exact
/// squared distance is 0.09 for every angle.
std::array<Vector3d, 4> crossing_pair(double angle, const Eigen::Isometry3d& T) {
  const Vector3d centre(0.5, 0.0, 0.3), direction(std::cos(angle), std::sin(angle), 0.0);
  return {T * Vector3d(0, 0, 0), T * Vector3d(1, 0, 0), T * (centre - 0.6 * direction),
          T * (centre + 0.6 * direction)};
}

TEST(EdgeEdgeDistance, NearlyParallelEdgesPickEndpointRegionsWithinTheStatedBound) {
  std::mt19937 rng(37);
  // sin^2 angle: 1e-16 (angle 1e-8), half the threshold, twice the threshold, 1e-6.
  for (double sin_squared :
       {1e-16, 0.5 * kParallelEdgeTolerance, 2.0 * kParallelEdgeTolerance, 1e-6}) {
    const double angle = std::asin(std::sqrt(sin_squared));
    for (int frame = 0; frame < 4; ++frame) {
      SCOPED_TRACE("sin^2 " + std::to_string(sin_squared) + ", frame " + std::to_string(frame));
      const Eigen::Isometry3d T = frame == 0 ? Eigen::Isometry3d::Identity() : random_motion(rng);
      const auto q = crossing_pair(angle, T);
      const EdgeEdgeResult r = edge_edge_closest(q[0], q[1], q[2], q[3]);
      if (sin_squared < kParallelEdgeTolerance) {
        EXPECT_NE(r.region, EE::EdgeEdge);
        // Overestimate at most (1/4) sin^2 min(|e0|^2, |e1|^2) = sin^2 / 4 here (|e0| = 1):
        // the endpoints p0, p1 lie 0.5 along P from the interior minimiser, so the bound is
        // attained; 1e-15 absorbs rounding of the O(0.1) distances.
        EXPECT_GE(r.distance_squared - 0.09, -1e-15);
        EXPECT_LE(r.distance_squared - 0.09, 0.25 * sin_squared + 1e-15);
      } else {
        EXPECT_EQ(r.region, EE::EdgeEdge) << to_string(r.region);
        // Relative rounding ~ eps / sin(angle) <= 1e-11 in the cross product.
        EXPECT_NEAR(r.distance_squared, 0.09, 1e-10);
      }
      // Derivatives of the classified region are finite; so are the line-line ones even
      // below the threshold, as long as the edges are not exactly parallel.
      const Vector12d x = stack_edge_pair(q[0], q[1], q[2], q[3]);
      EXPECT_TRUE(edge_edge_gradient_at(x, r.region).allFinite());
      EXPECT_TRUE(edge_edge_hessian_at(x, r.region).allFinite());
      EXPECT_TRUE(edge_edge_gradient_at(x, EE::EdgeEdge).allFinite());
      EXPECT_TRUE(edge_edge_hessian_at(x, EE::EdgeEdge).allFinite());
      // At angle 1e-8 the cross product has relative rounding ~1e-16 / 1e-8 in rotated
      // frames, hence 1e-6 relative on the line-line value.
      EXPECT_NEAR(edge_edge_value_at(x, EE::EdgeEdge), 0.09, 1e-6 * 0.09);
    }
  }
}

TEST(EdgeEdgeDistance, ExactlyParallelEdges) {
  const auto q = crossing_pair(0.0, Eigen::Isometry3d::Identity());
  const EdgeEdgeResult r = edge_edge_closest(q[0], q[1], q[2], q[3]);
  EXPECT_EQ(r.region, EE::P0EdgeQ);
  EXPECT_DOUBLE_EQ(r.distance_squared, 0.09);
  const Vector12d x = stack_edge_pair(q[0], q[1], q[2], q[3]);
  EXPECT_TRUE(edge_edge_hessian_at(x, r.region).allFinite());
  expect_invalid_argument_containing([&] { edge_edge_gradient_at(x, EE::EdgeEdge); },
                                     "exactly parallel");
  expect_invalid_argument_containing([&] { edge_edge_hessian_at(x, EE::EdgeEdge); },
                                     "exactly parallel");
  expect_invalid_argument_containing([&] { edge_edge_value_at(x, EE::EdgeEdge); },
                                     "exactly parallel");
}

TEST(EdgeEdgeDistance, LineLineDerivativesAtSmallAnglesMatchFiniteDifferences) {
  // Same situation as a sliver triangle (see the point-triangle test): at a crossing the
  // line-line gradient stays O(1) while the Hessian grows like 1/angle and third derivatives
  // like 1/angle^2 (the common normal turns by dx / angle), and the value carries relative
  // rounding ~ eps / angle from forming e0 x e1. Hence:
  //  - Hessian (differencing the analytic gradient) with h = 1e-4 angle: truncation
  //    ~ (h / angle)^2 = 1e-8; checked down to angle 1e-4 (sin^2 = 1e-8, still EdgeEdge).
  //  - gradient (differencing the value) with h = 1e-4 angle^(3/2), only down to angle 1e-2:
  //    below, value rounding / h exceeds the tolerance (measured 4e-6 at angle 1e-3). There
  //    the exact identity H (x - centroid) = g ties it to the checked Hessian.
  // The pairs are generic: where Q crosses over P, the gap, both lengths and the angle (+-20 %)
  // are drawn at random, then a random rigid motion. (Perturbing endpoints independently would
  // not do: an out-of-plane perturbation delta turns the common normal by ~delta / angle and
  // moves the crossing by ~gap delta / angle^2, off the segments.)
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  FdErrors worst;
  for (double angle : {1e-1, 1e-2, 1e-3, 1e-4}) {
    for (int trial = 0; trial < 5; ++trial) {
      SCOPED_TRACE("angle " + std::to_string(angle));
      const double turn = angle * (1.0 + 0.2 * u(rng));
      const double crossing = 0.5 + 0.2 * u(rng), gap = 0.3 + 0.1 * u(rng);
      const double back = 0.6 + 0.2 * u(rng), ahead = 0.6 + 0.2 * u(rng);
      const Vector3d centre(crossing, 0.0, gap), direction(std::cos(turn), std::sin(turn), 0.0);
      const Eigen::Isometry3d T = random_motion(rng);
      const Vector12d x =
          stack_edge_pair(T * Vector3d(0, 0, 0), T * Vector3d(1, 0, 0),
                          T * (centre - back * direction), T * (centre + ahead * direction));
      ASSERT_EQ(edge_edge_closest_at(x).region, EE::EdgeEdge);
      const Vector12d g = edge_edge_gradient_at(x, EE::EdgeEdge);
      const Matrix12d H = edge_edge_hessian_at(x, EE::EdgeEdge);
      Vector12d centred = x;
      Vector3d centroid = Vector3d::Zero();
      for (int k = 0; k < 4; ++k) centroid += x.segment<3>(3 * k) / 4.0;
      for (int k = 0; k < 4; ++k) centred.segment<3>(3 * k) -= centroid;
      EXPECT_LE((H * centred - g).cwiseAbs().maxCoeff(),
                1e-12 * H.cwiseAbs().maxCoeff() * centred.cwiseAbs().maxCoeff());
      const FdErrors e_hessian = edge_edge_fd_errors(x, EE::EdgeEdge, 1e-4 * angle);
      EXPECT_LT(e_hessian.hessian, kFdTolerance);
      worst.hessian = std::max(worst.hessian, e_hessian.hessian);
      if (angle >= 1e-2) {
        const FdErrors e_gradient =
            edge_edge_fd_errors(x, EE::EdgeEdge, 1e-4 * angle * std::sqrt(angle));
        EXPECT_LT(e_gradient.gradient, kFdTolerance);
        worst.gradient = std::max(worst.gradient, e_gradient.gradient);
      }
    }
  }
  std::cout << "[ measured ] line-line at small angles: worst relative FD error gradient "
            << worst.gradient << " (angle >= 1e-2), Hessian " << worst.hessian
            << " (angle >= 1e-4)\n";
}

// ---- IPC mollifier ---------------------------------------------------------------------------

TEST(EdgeEdgeDistance, MollifierValuesAndThreshold) {
  const Vector3d o = Vector3d::Zero();
  // Rest edges of lengths 2 and 3: eps_x = 1e-3 * 4 * 9.
  EXPECT_DOUBLE_EQ(
      edge_edge_mollifier_threshold(o, Vector3d(2, 0, 0), Vector3d(0, 0, 1), Vector3d(0, 3, 1)),
      1e-3 * 36.0);
  // c = |e0 x e1|^2 = 1 for unit perpendicular edges: m = (2 - x) x with x = c / eps_x.
  const Vector3d p1(1, 0, 0), q0(0, 0, 1), q1(0, 1, 1);
  EXPECT_DOUBLE_EQ(edge_edge_mollifier(o, p1, q0, q1, 2.0), 0.75);
  EXPECT_DOUBLE_EQ(edge_edge_mollifier(o, p1, q0, q1, 1.0), 1.0);
  EXPECT_DOUBLE_EQ(edge_edge_mollifier(o, p1, q0, q1, 0.5), 1.0);
  EXPECT_TRUE(edge_edge_mollifier_gradient(o, p1, q0, q1, 0.5).isZero(0.0));
  EXPECT_TRUE(edge_edge_mollifier_hessian(o, p1, q0, q1, 0.5).isZero(0.0));
  // Parallel edges: m = 0.
  EXPECT_EQ(edge_edge_mollifier(o, p1, q0, Vector3d(3, 0, 1), 2.0), 0.0);
  // C1 at c = eps_x: the gradient just inside tends to zero like (1 - x).
  const double just_inside =
      edge_edge_mollifier_gradient(o, p1, q0, q1, 1.0 + 1e-9).cwiseAbs().maxCoeff();
  EXPECT_LT(just_inside, 1e-8);
  expect_invalid_argument_containing([&] { edge_edge_mollifier(o, p1, q0, q1, 0.0); }, "eps_x");
  expect_invalid_argument_containing([&] { edge_edge_mollifier(o, p1, q0, q1, -1.0); }, "eps_x");
}

TEST(EdgeEdgeDistance, MollifierDerivativesMatchFiniteDifferences) {
  // eps_x set to c / x for x in (0, 1), i.e. inside the mollified band; the mollifier is a
  // polynomial of degree 4 in the positions there, so the same 1e-6 / 1e-6 budget applies.
  std::mt19937 rng(43);
  std::uniform_real_distribution<double> fraction(0.05, 0.95);
  FdErrors worst;
  for (int trial = 0; trial < 40; ++trial) {
    Vector12d x;
    for (int k = 0; k < 4; ++k) x.segment<3>(3 * k) = random_point(rng, 1.0);
    const double c =
        (x.segment<3>(3) - x.segment<3>(0)).cross(x.segment<3>(9) - x.segment<3>(6)).squaredNorm();
    const double eps_x = c / fraction(rng);
    auto split = [](const Vector12d& y) {
      return std::array<Vector3d, 4>{y.segment<3>(0), y.segment<3>(3), y.segment<3>(6),
                                     y.segment<3>(9)};
    };
    const FdErrors e = finite_difference_errors(
        x, kFdStep,
        [&](const Vector12d& y) {
          const auto q = split(y);
          return edge_edge_mollifier(q[0], q[1], q[2], q[3], eps_x);
        },
        [&](const Vector12d& y) {
          const auto q = split(y);
          return edge_edge_mollifier_gradient(q[0], q[1], q[2], q[3], eps_x);
        },
        [&](const Vector12d& y) {
          const auto q = split(y);
          return edge_edge_mollifier_hessian(q[0], q[1], q[2], q[3], eps_x);
        });
    EXPECT_LT(e.gradient, kFdTolerance);
    EXPECT_LT(e.hessian, kFdTolerance);
    worst.gradient = std::max(worst.gradient, e.gradient);
    worst.hessian = std::max(worst.hessian, e.hessian);
  }
  std::cout << "[ measured ] mollifier: worst relative FD error gradient " << worst.gradient
            << ", Hessian " << worst.hessian << "\n";
}

// ---- Degenerate input ------------------------------------------------------------------------

TEST(EdgeEdgeDistance, DegenerateInputThrowsNamingTheProblem) {
  const Vector3d p0(0.1, 0.2, 0.3), p1(1, 0, 0), q0(0, 1, 1), q1(0, 2, 1);
  expect_invalid_argument_containing([&] { edge_edge_closest(p0, p0, q0, q1); },
                                     "edge (p0, p1) has zero length");
  expect_invalid_argument_containing([&] { classify_edge_edge(p0, p1, q1, q1); },
                                     "edge (q0, q1) has zero length");
  for (EE region : kAllEdgeEdgeRegions) {
    expect_invalid_argument_containing(
        [&] { edge_edge_distance_squared_hessian(p0, p1, q0, q0, region); }, "zero length");
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expect_invalid_argument_containing([&] { edge_edge_closest(p0, p1, Vector3d(0, nan, 0), q1); },
                                     "point q0");
  expect_invalid_argument_containing(
      [&] {
        edge_edge_distance_squared_gradient(
            p0, Vector3d(std::numeric_limits<double>::infinity(), 0, 0), q0, q1, EE::EdgeEdge);
      },
      "point p1");
}

}  // namespace
}  // namespace growshell
