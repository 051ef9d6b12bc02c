// Whether the sheet passes through itself: flat discs, a strip folded into a U and the same
// U with its top leg tilted through the bottom one, tight folds inside the exclusion radius,
// random rolled discs against an independent brute force, the signed gap, bad input.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "libshell/analysis/self_distance.hpp"
#include "libshell/analysis/self_intersection.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/subdivision/limit_surface.hpp"
#include "tests/support/sheet_states.hpp"

namespace growshell {
namespace {

using test_support::map_reference;

/// The strip x in [0, L] folded into a U: bottom leg z = 0 for x <= l, a half circle of
/// radius rho, then the top leg leaving the arc's end (l, 2 rho) in the direction
/// (-cos a, 0, -sin a): a = 0 is the plain U (legs 2 rho apart); for sin a > 2 rho / l the
/// top leg passes through the bottom one along the line z = 0, x = l - 2 rho cot a. Applied
/// to all control points (ghosts too), so wherever an element's 12 control points lie on
/// one leg the limit surface is exactly that plane (Loop reproduces linear functions).
struct TiltedU {
  double rho, leg, tilt = 0.0;
  double length() const { return 2.0 * leg + std::numbers::pi * rho; }
  double crossing_x() const { return leg - 2.0 * rho / std::tan(tilt); }
  Eigen::Vector3d operator()(const Eigen::Vector3d& X) const {
    const double s = X.x();
    if (s <= leg) return {s, X.y(), 0.0};
    if (s >= leg + std::numbers::pi * rho) {
      const double u = s - leg - std::numbers::pi * rho;
      return {leg - u * std::cos(tilt), X.y(), 2.0 * rho - u * std::sin(tilt)};
    }
    const double t = (s - leg) / rho;
    return {leg + rho * std::sin(t), X.y(), rho * (1.0 - std::cos(t))};
  }
};

SelfIntersectionOptions options(double exclusion_radius, int n = 2) {
  SelfIntersectionOptions o;
  o.exclusion_radius = exclusion_radius;
  o.samples_per_edge = n;
  return o;
}

TEST(SelfIntersection, FlatDiscNeverIntersects) {
  DiscMeshOptions o;
  o.radius = 1.0;
  o.rings = 10;
  const ShellModel model(make_disc_mesh(o), ShellModelSettings{});
  // On the near-equilateral disc mesh, sub-triangles with overlapping bounding boxes nearly
  // all share a vertex, so few pairs reach the narrow phase. A strong in-plane shear (x + 1.5 y, y)
  // skews the triangles so that many non-neighbours have overlapping boxes: exactly in
  // z = 0 (every limit point is a combination of z = 0 control points) they go through the
  // coplanar 2-D test, and after a rotation, where rounding makes them only nearly coplanar,
  // through the edge-triangle tests.
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  const auto shear = [](const Eigen::Vector3d& X) { return Eigen::Vector3d(X.x() + 1.5 * X.y(), X.y(), 0.0); };
  const Eigen::VectorXd sheared = map_reference(model, shear);
  const Eigen::VectorXd rotated =
      map_reference(model, [&](const Eigen::Vector3d& X) { return Eigen::Vector3d(rotation * shear(X)); });
  const std::array<const Eigen::VectorXd*, 3> states{&model.reference_positions(), &sheared, &rotated};
  // 0.01 m is below the sub-triangle size (about 0.03 m): then every pair of triangles that
  // do not share a vertex is admissible; 3 m is wider than the disc.
  for (double r_ex : {0.01, 0.1, 0.5, 3.0}) {
    for (int n : {1, 2}) {
      for (std::size_t k = 0; k < states.size(); ++k) {
        const Eigen::VectorXd& x = *states[k];
        const SelfIntersection s = find_self_intersection(model, x, options(r_ex, n));
        EXPECT_FALSE(s.intersects) << "state " << k << ", r_ex " << r_ex << ", n " << n << ", point "
                                   << s.point.transpose();
        EXPECT_EQ(s.element_a, -1);
        if (k > 0 && r_ex < 0.5) {
          EXPECT_GT(s.triangle_pairs_tested, 0) << "state " << k << ", r_ex " << r_ex;  // the narrow phase ran
        }
        if (r_ex > 2.0) {
          EXPECT_EQ(s.triangle_pairs_tested, 0);
        }
        const double gap = signed_self_gap(model, x, options(r_ex, n));
        SelfDistanceOptions d;
        d.exclusion_radius = r_ex;
        d.samples_per_edge = n;
        EXPECT_EQ(gap, smallest_self_distance(model, x, d).distance);
        if (r_ex < 2.0) {
          EXPECT_GT(gap, 0.0);
        }
        std::cout << "flat disc state " << k << ", n " << n << ", r_ex " << r_ex << ": pairs tested " << s.triangle_pairs_tested
                    << ", gap " << gap << "\n";
      }
    }
  }
}

TEST(SelfIntersection, DiscFoldedFlatOntoItselfIntersects) {
  // (|x|, y, 0): the left half folded flat onto the right one. Coplanar overlapping
  // triangles must count (touching counts), and since the mesh is mirror-symmetric in the
  // y-axis (60-degree rotation and the x-axis reflection generate it) samples coincide up to
  // rounding: the sampled distance is about 0, and the gap must still be negative.
  DiscMeshOptions o;
  o.rings = 8;
  const ShellModel model(make_disc_mesh(o), ShellModelSettings{});
  const Eigen::VectorXd x =
      map_reference(model, [](const Eigen::Vector3d& X) { return Eigen::Vector3d(std::abs(X.x()), X.y(), 0.0); });
  const SelfIntersection s = find_self_intersection(model, x, options(0.2));
  ASSERT_TRUE(s.intersects);
  EXPECT_EQ(s.point.z(), 0.0);
  EXPECT_LE(s.point.norm(), 1.0 + 1e-12);  // on the (half) disc
  EXPECT_GE(s.point.x(), 0.1 - 1e-12);     // admissible points are >= r_ex / 2 from the crease
  const double gap = signed_self_gap(model, x, options(0.2));
  EXPECT_LT(gap, 0.0);
  EXPECT_GT(gap, -1e-12);
  std::cout << "disc folded flat: point " << s.point.transpose() << ", gap " << gap << ", pairs tested "
            << s.triangle_pairs_tested << "\n";
}

class TiltedStrip : public ::testing::Test {
 protected:
  void SetUp() override {
    strip.length = fold.length();
    strip.width = 0.1;
    strip.cells_x = 120;  // dx = 6.8 mm
    strip.cells_y = 2;
    model.emplace(make_strip_mesh(strip), ShellModelSettings{});
  }
  Eigen::VectorXd state(double tilt) const {
    TiltedU f = fold;
    f.tilt = tilt;
    return map_reference(*model, f);
  }
  TiltedU fold{0.1, 0.5};
  StripMeshOptions strip;
  std::optional<ShellModel> model;
};

TEST_F(TiltedStrip, PlainUDoesNotIntersect) {
  const Eigen::VectorXd x = state(0.0);
  const double rho = fold.rho;
  for (double r_ex : {0.5 * std::numbers::pi * rho, 2.0 * std::numbers::pi * rho}) {
    const SelfIntersection s = find_self_intersection(*model, x, options(r_ex));
    EXPECT_FALSE(s.intersects) << "r_ex " << r_ex << ", point " << s.point.transpose();
  }
  // Beyond the arclength of the fold only the legs face each other, exactly 2 rho apart
  // (see test_self_distance.cpp: facing samples exist, the legs are exact planes there).
  const double gap = signed_self_gap(*model, x, options(2.0 * std::numbers::pi * rho));
  EXPECT_NEAR(gap, 2.0 * rho, 1e-12 * rho);
}

TEST_F(TiltedStrip, TopLegPushedThroughIntersectsOnTheCrossingLine) {
  const double rho = fold.rho, dx = strip.length / strip.cells_x,
               r_ex = 2.0 * std::numbers::pi * rho;
  // The top leg's free end sits at z_end = 2 rho - l sin a; it reaches the bottom leg's
  // plane at sin a = 2 rho / l. Below that factor the legs are apart, above it they cross.
  const double critical = 2.0 * rho / fold.leg;
  for (double factor : {0.5, 0.9, 1.1, 2.0}) {
    const double tilt = std::asin(factor * critical);
    const Eigen::VectorXd x = state(tilt);
    const SelfIntersection s = find_self_intersection(*model, x, options(r_ex));
    const double gap = signed_self_gap(*model, x, options(r_ex));
    TiltedU f = fold;
    f.tilt = tilt;
    std::cout << "tilt factor " << factor << ": intersects " << s.intersects << ", point " << s.point.transpose()
              << ", crossing x " << f.crossing_x() << ", gap " << gap << ", pairs tested "
              << s.triangle_pairs_tested << "\n";
    if (factor < 1.0) {
      EXPECT_FALSE(s.intersects) << factor;
      // Every top-leg sample is at least z_end above the bottom plane; the end row's samples
      // have a bottom sample at the same y within dx / 4 in x (samples every dx / 2).
      const double z_end = 2.0 * rho - fold.leg * std::sin(tilt);
      EXPECT_GE(gap, z_end - 1e-12) << factor;
      EXPECT_LE(gap, std::hypot(z_end, dx / 4.0) + 1e-12) << factor;
    } else {
      ASSERT_TRUE(s.intersects) << factor;
      // Both legs are exact planes at the crossing (>= 8 cells from the arc and the ends),
      // so the sampled surfaces cross exactly on the line z = 0, x = crossing_x(), up to
      // rounding of O(1e-16) m amplified by 1 / tan a < 3.
      EXPECT_NEAR(s.point.z(), 0.0, 1e-12) << factor;
      EXPECT_NEAR(s.point.x(), f.crossing_x(), 1e-12) << factor;
      EXPECT_LE(std::abs(s.point.y()), 0.5 * strip.width + 1e-12) << factor;
      EXPECT_LT(gap, 0.0) << factor;
      // Nearest top-leg sample to the line: within dx / 4 along the leg, and a bottom sample
      // at the same y within dx / 4 in x of it: |gap| < sqrt(2) dx / 4 < dx / 2.
      EXPECT_LE(-gap, 0.5 * dx) << factor;
    }
  }
}

TEST(SelfIntersection, TightFoldInsideTheExclusionRadiusNeverCounts) {
  // A tight fold (rho = 1 cm) whose top leg, tilted by 30 degrees, passes through the bottom
  // leg at u = 2 rho / sin a = 4 cm beyond the arc: the two sheets cross at reference
  // separation pi rho + u (1 + cos a) = 0.106 m.
  TiltedU fold{0.01, 0.4, std::numbers::pi / 6.0};
  StripMeshOptions strip;
  strip.length = fold.length();
  strip.width = 0.05;
  strip.cells_x = 240;  // dx = 3.5 mm, 9 cells on the arc
  strip.cells_y = 2;
  const ShellModel model(make_strip_mesh(strip), ShellModelSettings{});
  const Eigen::VectorXd x = map_reference(model, fold);
  const double separation = std::numbers::pi * fold.rho +
                            2.0 * fold.rho / std::sin(fold.tilt) * (1.0 + std::cos(fold.tilt));
  EXPECT_NEAR(separation, 0.106, 1e-3);

  // Exclusion radius 0.05 m < separation: the crossing counts, on its line.
  const SelfIntersection counted = find_self_intersection(model, x, options(0.05));
  ASSERT_TRUE(counted.intersects);
  EXPECT_NEAR(counted.point.z(), 0.0, 1e-12);
  EXPECT_NEAR(counted.point.x(), fold.crossing_x(), 1e-12);
  EXPECT_LT(signed_self_gap(model, x, options(0.05)), 0.0);
  // Exclusion radius 0.15 m > separation + a sub-triangle diagonal (about 0.003 m): the
  // parts that cross are neighbours along the sheet and never count.
  const SelfIntersection ignored = find_self_intersection(model, x, options(0.15));
  EXPECT_FALSE(ignored.intersects) << ignored.point.transpose();
  EXPECT_GT(signed_self_gap(model, x, options(0.15)), 0.0);
  std::cout << "tight fold: pairs tested " << counted.triangle_pairs_tested << " (r_ex 0.05), "
            << ignored.triangle_pairs_tested << " (r_ex 0.15)\n";
}

/// Independent O(T^2) reference: the same sub-triangles (evaluated per element, without
/// sharing, in the documented order), the same admissibility, and a different narrow
/// phase: Moeller-Trumbore segment-triangle tests of the six edges.
struct BruteForceIntersection {
  bool intersects = false;
  Eigen::Index element_a = -1, element_b = -1, admissible_pairs = 0, triangles = 0;
};

bool segment_hits_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const std::array<Eigen::Vector3d, 3>& t) {
  const Eigen::Vector3d d = q - p, e1 = t[1] - t[0], e2 = t[2] - t[0];
  const Eigen::Vector3d h = d.cross(e2);
  const double det = e1.dot(h);
  if (det == 0.0) return false;  // parallel: never the case in the generic random states
  const Eigen::Vector3d s = p - t[0];
  const double u = s.dot(h) / det;
  const Eigen::Vector3d qv = s.cross(e1);
  const double v = d.dot(qv) / det;
  const double along = e2.dot(qv) / det;
  return u >= 0.0 && v >= 0.0 && u + v <= 1.0 && along >= 0.0 && along <= 1.0;
}

BruteForceIntersection brute_force(const ShellModel& model, const Eigen::VectorXd& x,
                                   const SelfIntersectionOptions& o) {
  const Eigen::Index nv = x.size() / 3;
  using RowMajorX3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
  const Eigen::MatrixX3d cur = Eigen::Map<const RowMajorX3>(x.data(), nv, 3);
  const Eigen::MatrixX3d ref = Eigen::Map<const RowMajorX3>(model.reference_positions().data(), nv, 3);
  const int n = o.samples_per_edge;
  std::vector<std::array<Eigen::Vector3d, 3>> P, R;
  std::vector<Eigen::Index> E;
  for (Eigen::Index e = 0; e < model.num_elements(); ++e) {
    const auto& control = model.patches().patch[static_cast<std::size_t>(e)];
    const auto add = [&](std::array<std::array<int, 2>, 3> ij) {
      std::array<Eigen::Vector3d, 3> p, r;
      for (int k = 0; k < 3; ++k) {
        const double v = double(ij[k][0]) / n, w = double(ij[k][1]) / n;
        p[k] = evaluate_limit_surface(cur, control, v, w).position;
        r[k] = evaluate_limit_surface(ref, control, v, w).position;
      }
      P.push_back(p);
      R.push_back(r);
      E.push_back(e);
    };
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n - i; ++j) {
        add({{{i, j}, {i + 1, j}, {i, j + 1}}});
        if (i + j < n - 1) add({{{i + 1, j}, {i + 1, j + 1}, {i, j + 1}}});
      }
  }
  BruteForceIntersection result;
  result.triangles = static_cast<Eigen::Index>(P.size());
  const double r2 = o.exclusion_radius * o.exclusion_radius;
  std::vector<char> in_core(P.size(), 0);
  for (std::size_t t = 0; t < P.size(); ++t)
    for (const auto& r : R[t]) in_core[t] = in_core[t] || (r - o.core_center).norm() < o.core_radius;
  for (std::size_t a = 0; a < P.size(); ++a) {
    if (in_core[a]) continue;
    for (std::size_t b = a + 1; b < P.size(); ++b) {
      if (in_core[b]) continue;
      bool admissible = true;
      for (const auto& ra : R[a])
        for (const auto& rb : R[b]) admissible = admissible && (ra - rb).squaredNorm() >= r2;
      if (!admissible) continue;
      ++result.admissible_pairs;
      if (result.intersects) continue;  // (a, b) ascending: the first hit is the smallest pair
      bool hit = false;
      for (int k = 0; k < 3 && !hit; ++k)
        hit = segment_hits_triangle(P[a][k], P[a][(k + 1) % 3], P[b]) ||
              segment_hits_triangle(P[b][k], P[b][(k + 1) % 3], P[a]);
      if (hit) {
        result.intersects = true;
        result.element_a = E[a];
        result.element_b = E[b];
      }
    }
  }
  return result;
}

TEST(SelfIntersection, RandomRolledDiscsMatchBruteForce) {
  DiscMeshOptions o;
  o.rings = 8;
  const ShellModel model(make_disc_mesh(o), ShellModelSettings{});
  int intersecting = 0, clear = 0;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    // Roll the unit disc onto a cylinder of radius 0.25..0.45: it spans 2 / roll = 4.4..8
    // radians, so for roll < 1 / pi the ends overlap a layer, which smooth waves of
    // different phase then push through each other; add a random rotation.
    const double roll = 0.25 + 0.2 * U(rng);
    Eigen::Matrix<double, 3, 3> wave_k, wave_phase;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        wave_k(i, j) = 1.0 + 3.0 * U(rng);
        wave_phase(i, j) = 2.0 * std::numbers::pi * U(rng);
      }
    const Eigen::Matrix3d rotation =
        Eigen::AngleAxisd(2.0 * std::numbers::pi * U(rng),
                          Eigen::Vector3d(U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5).normalized())
            .toRotationMatrix();
    const Eigen::VectorXd x = map_reference(model, [&](const Eigen::Vector3d& X) {
      const double t = X.x() / roll;
      Eigen::Vector3d p(roll * std::sin(t), X.y(), roll * (1.0 - std::cos(t)));
      for (int c = 0; c < 3; ++c)
        p(c) += 0.05 * std::sin(wave_k(c, 0) * X.x() + wave_k(c, 1) * X.y() + wave_phase(c, 0)) *
                std::cos(wave_k(c, 2) * X.y() + wave_phase(c, 1));
      return Eigen::Vector3d(rotation * p);
    });
    SelfIntersectionOptions opts = options(0.05 + 0.25 * U(rng), 1 + static_cast<int>(seed % 3));
    if (seed % 2 == 0) opts.core_radius = 0.3;
    const SelfIntersection s = find_self_intersection(model, x, opts);
    const BruteForceIntersection bf = brute_force(model, x, opts);
    EXPECT_EQ(s.intersects, bf.intersects) << "seed " << seed;
    // Same triangle order, so the same smallest intersecting pair.
    EXPECT_EQ(s.element_a, bf.element_a) << "seed " << seed;
    EXPECT_EQ(s.element_b, bf.element_b) << "seed " << seed;
    // The broad phase tests far fewer pairs than all admissible ones.
    EXPECT_LT(s.triangle_pairs_tested, bf.admissible_pairs / 10) << "seed " << seed;
    const double gap = signed_self_gap(model, x, opts);
    EXPECT_EQ(gap < 0.0, s.intersects) << "seed " << seed;
    (s.intersects ? intersecting : clear) += 1;
    std::cout << "seed " << seed << ": roll " << roll << ", r_ex " << opts.exclusion_radius << ", n "
              << opts.samples_per_edge << ", core " << opts.core_radius << ": intersects " << s.intersects
              << " (brute force " << bf.intersects << "), gap " << gap << ", pairs tested "
              << s.triangle_pairs_tested << " of " << bf.admissible_pairs << " admissible, " << bf.triangles
              << " triangles\n";
  }
  // The sample must exercise both answers, or agreement would prove little.
  EXPECT_GE(intersecting, 2);
  EXPECT_GE(clear, 2);
}

TEST(SelfIntersection, RejectsBadOptionsNamingTheField) {
  DiscMeshOptions o;
  o.rings = 3;
  const ShellModel model(make_disc_mesh(o), ShellModelSettings{});
  const Eigen::VectorXd& x = model.reference_positions();
  const auto messages = [&](const SelfIntersectionOptions& opts, const Eigen::VectorXd& state) {
    std::array<std::string, 2> m;
    try {
      find_self_intersection(model, state, opts);
    } catch (const std::invalid_argument& e) {
      m[0] = e.what();
    }
    try {
      signed_self_gap(model, state, opts);
    } catch (const std::invalid_argument& e) {
      m[1] = e.what();
    }
    return m;
  };
  const auto expect_field = [&](const SelfIntersectionOptions& opts, const Eigen::VectorXd& state,
                                const std::string& field) {
    for (const std::string& m : messages(opts, state)) EXPECT_NE(m.find(field), std::string::npos) << "'" << m << "'";
  };
  for (double r : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) expect_field(options(r), x, "exclusion_radius");
  for (int n : {0, -3}) expect_field(options(0.1, n), x, "samples_per_edge");
  for (double c : {-0.1, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
    SelfIntersectionOptions opts = options(0.1);
    opts.core_radius = c;
    expect_field(opts, x, "core_radius");
  }
  SelfIntersectionOptions opts = options(0.1);
  opts.core_center.y() = std::numeric_limits<double>::quiet_NaN();
  expect_field(opts, x, "core_center");
  expect_field(options(0.1), x.head(x.size() - 3), "dimension");
  Eigen::VectorXd bad = x;
  bad(7) = std::numeric_limits<double>::infinity();
  expect_field(options(0.1), bad, "x(7)");
  // Valid options go through.
  EXPECT_NO_THROW(find_self_intersection(model, x, options(0.1)));
}

}  // namespace
}  // namespace growshell
