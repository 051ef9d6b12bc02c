// Smallest distance between non-neighbouring parts of the sheet: flat disc, a strip folded
// into a U, random folded discs against brute force, cost under refinement, bad input.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>
#include <vector>

#include "libshell/analysis/self_distance.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/subdivision/limit_surface.hpp"
#include "tests/support/sheet_states.hpp"

namespace growshell {
namespace {

using test_support::map_reference;

/// Brute-force O(N^2) reference: the same samples (element order, (i/n, j/n) with i outer,
/// shared corners and edges from their first element), the same squared distances and the
/// same tie rule as smallest_self_distance.
struct BruteForceSelfDistance {
  double distance = std::numeric_limits<double>::infinity();
  Eigen::Index element_a = -1, element_b = -1, samples = 0;
};

BruteForceSelfDistance brute_force_self_distance(const ShellModel& model, const Eigen::VectorXd& x,
                                                 double exclusion_radius, int n) {
  const Eigen::Index nv = x.size() / 3;
  using RowMajorX3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
  const Eigen::MatrixX3d cur = Eigen::Map<const RowMajorX3>(x.data(), nv, 3);
  const Eigen::MatrixX3d ref = Eigen::Map<const RowMajorX3>(model.reference_positions().data(), nv, 3);
  std::vector<Eigen::Vector3d> P, R;
  std::vector<Eigen::Index> E;
  std::set<std::array<int, 4>> seen;  // (smaller vertex, larger vertex, steps from smaller, 0) or (vertex, -1, -1, 1)
  for (Eigen::Index e = 0; e < model.num_elements(); ++e) {
    const auto& control = model.patches().patch[static_cast<std::size_t>(e)];
    const int A = control.control[3], B = control.control[6], C = control.control[7];  // at (v, w) = (0,0), (1,0), (0,1)
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n - i; ++j) {
        // Which mesh entity holds the sample: identify by the lattice point it sits on.
        std::array<int, 4> key{-1, -1, -1, -1};
        const auto edge = [&](int p, int q, int steps_from_p) {
          return p < q ? std::array<int, 4>{p, q, steps_from_p, 0} : std::array<int, 4>{q, p, n - steps_from_p, 0};
        };
        if (i == 0 && j == 0) key = {A, -1, -1, 1};
        else if (i == n) key = {B, -1, -1, 1};
        else if (j == n) key = {C, -1, -1, 1};
        else if (j == 0) key = edge(A, B, i);
        else if (i == 0) key = edge(A, C, j);
        else if (i + j == n) key = edge(C, B, i);
        if (key[0] >= 0 && !seen.insert(key).second) continue;
        P.push_back(evaluate_limit_surface(cur, control, double(i) / n, double(j) / n).position);
        R.push_back(evaluate_limit_surface(ref, control, double(i) / n, double(j) / n).position);
        E.push_back(e);
      }
  }
  BruteForceSelfDistance best;
  best.samples = static_cast<Eigen::Index>(P.size());
  double best_squared = std::numeric_limits<double>::infinity();
  const double r2 = exclusion_radius * exclusion_radius;
  for (std::size_t a = 0; a < P.size(); ++a)
    for (std::size_t b = a + 1; b < P.size(); ++b) {
      const double d2 = (P[a] - P[b]).squaredNorm();
      if (d2 < best_squared && (R[a] - R[b]).squaredNorm() >= r2) {  // a, b ascending: first wins ties
        best_squared = d2;
        best.element_a = E[a];
        best.element_b = E[b];
      }
    }
  best.distance = std::sqrt(best_squared);
  return best;
}

TEST(SelfDistance, FlatDiscFindsPairsJustBeyondTheExclusionRadius) {
  DiscMeshOptions o;
  o.radius = 1.0;
  o.rings = 10;
  ShellModel model(make_disc_mesh(o), ShellModelSettings{});
  const double r_ex = 0.25;
  const SelfDistance d = smallest_self_distance(model, model.reference_positions(), {r_ex, 2});
  // Flat: current = reference positions, so no valid pair is closer than r_ex; and every
  // sample has a sample at reference distance in [r_ex, r_ex + l] along any line, l <= the
  // longest sub-triangle edge, 1.40 R / N / 2 = 0.07 m (disc_mesh.hpp), so the minimum is
  // at most r_ex + 0.07.
  EXPECT_GE(d.distance, r_ex);
  EXPECT_LE(d.distance, r_ex + 0.07);
  EXPECT_NEAR((d.point_a - d.point_b).norm(), d.distance, 1e-15);
  EXPECT_GE((d.reference_a - d.reference_b).norm(), r_ex);
  EXPECT_NEAR((d.point_a - d.reference_a).norm(), 0.0, 1e-15);
  EXPECT_GE(d.element_a, 0);
  EXPECT_GE(d.element_b, 0);
  EXPECT_LT(d.element_a, model.num_elements());
  EXPECT_LT(d.element_b, model.num_elements());
  std::cout << "flat disc N=10, r_ex 0.25: distance " << d.distance << ", pairs " << d.pairs_checked << "\n";

  // An exclusion radius wider than the disc leaves no valid pair.
  const SelfDistance none = smallest_self_distance(model, model.reference_positions(), {2.5, 2});
  EXPECT_TRUE(std::isinf(none.distance));
  EXPECT_EQ(none.element_a, -1);
}

/// The strip x in [0, L] folded into a U: bottom leg z = 0 for x <= l, a half circle of
/// radius rho, top leg z = 2 rho running back. Applied to all control points (ghosts too).
struct UFold {
  double rho, leg;
  double length() const { return 2.0 * leg + std::numbers::pi * rho; }
  Eigen::Vector3d operator()(const Eigen::Vector3d& X) const {
    const double s = X.x();
    if (s <= leg) return {s, X.y(), 0.0};
    if (s >= leg + std::numbers::pi * rho)
      return {leg - (s - leg - std::numbers::pi * rho), X.y(), 2.0 * rho};
    const double t = (s - leg) / rho;
    return {leg + rho * std::sin(t), X.y(), rho * (1.0 - std::cos(t))};
  }
};

TEST(SelfDistance, StripFoldedIntoAU) {
  const UFold fold{0.1, 0.5};
  StripMeshOptions o;
  o.length = fold.length();
  o.width = 0.1;
  o.cells_x = 240;  // dx = 5.5 mm, d theta = dx / rho = 0.055 rad on the arc
  o.cells_y = 2;
  ShellModel model(make_strip_mesh(o), ShellModelSettings{});
  const Eigen::VectorXd x = map_reference(model, fold);
  const double rho = fold.rho, dx = o.length / o.cells_x;
  const int n = 2;

  // Exclusion radius beyond the fold's arclength pi rho: only the legs face each other, at
  // exactly 2 rho wherever all 12 control points of both elements lie on the flat legs
  // (Loop reproduces planes); facing samples exist since L / dx is an integer. The valid
  // facing pairs have x <= l - (r_ex - pi rho) / 2, far (> 2 cells) from the arc.
  {
    const double r_ex = 2.0 * std::numbers::pi * rho;
    const SelfDistance d = smallest_self_distance(model, x, {r_ex, n});
    EXPECT_NEAR(d.distance, 2.0 * rho, 1e-12 * rho);
    EXPECT_NEAR(std::min(d.point_a.z(), d.point_b.z()), 0.0, 1e-12 * rho);
    EXPECT_NEAR(std::max(d.point_a.z(), d.point_b.z()), 2.0 * rho, 1e-12 * rho);
    EXPECT_LE(std::max(d.point_a.x(), d.point_b.x()),
              fold.leg - 0.5 * (r_ex - std::numbers::pi * rho) + 1e-12);
    EXPECT_GE((d.reference_a - d.reference_b).norm(), r_ex);
    std::cout << "U fold r_ex = 2 pi rho: distance / (2 rho) - 1 = " << d.distance / (2 * rho) - 1
              << ", pairs " << d.pairs_checked << "\n";
  }
  // Exclusion radius below pi rho: the closest valid pair is the chord across the fold,
  // 2 rho sin(s / (2 rho)) for the smallest sampled reference separation s >= r_ex (shorter
  // than 2 rho: the legs are not the answer then; any position along the arc gives the same
  // chord). Along x the samples are uniform with step dx / n, so s = ceil(r_ex n / dx) dx / n.
  // Across the strip the Loop limit is the cubic B-spline of the control polygon, which for
  // a circle sampled at angle step dtheta = dx / rho lies inside it by
  // delta = rho (1 - cos dtheta) / 3 at the vertices (and by the same up to O(dtheta^4 rho)
  // = 1e-5 rho between them): the chord is 2 (rho - delta) sin(s / (2 rho)). Tolerance
  // 2e-5 rho covers the O(dtheta^4) terms; the uncorrected chord is 7e-4 rho .. 1e-3 rho off.
  for (double fraction : {0.5, 0.8}) {
    const double r_ex = fraction * std::numbers::pi * rho;
    const SelfDistance d = smallest_self_distance(model, x, {r_ex, n});
    const double s = std::ceil(r_ex * n / dx - 1e-9) * dx / n;
    const double delta = rho * (1.0 - std::cos(dx / rho)) / 3.0;
    const double chord = 2.0 * (rho - delta) * std::sin(s / (2.0 * rho));
    EXPECT_LT(d.distance, 2.0 * rho - 0.01 * rho);
    EXPECT_NEAR(d.distance, chord, 2e-5 * rho);
    EXPECT_NEAR((d.reference_a - d.reference_b).norm(), s, 1e-9 * rho);
    // Both ends on the arc (distance rho - delta from its axis y, x = l, z = rho), not on the
    // legs; 1e-3 rho allows for where the arc meets the legs.
    for (const Eigen::Vector3d& p : {d.point_a, d.point_b})
      EXPECT_NEAR(std::hypot(p.x() - fold.leg, p.z() - rho), rho - delta, 1e-3 * rho) << p.transpose();
    std::cout << "U fold r_ex = " << fraction << " pi rho: distance " << d.distance << ", expected " << chord
              << ", difference / rho " << (d.distance - chord) / rho << ", axis distances / rho "
              << std::hypot(d.point_a.x() - fold.leg, d.point_a.z() - rho) / rho << " "
              << std::hypot(d.point_b.x() - fold.leg, d.point_b.z() - rho) / rho << ", pairs "
              << d.pairs_checked << "\n";
  }
}

TEST(SelfDistance, RandomFoldedDiscsMatchBruteForce) {
  DiscMeshOptions o;
  o.rings = 8;
  ShellModel model(make_disc_mesh(o), ShellModelSettings{});
  for (unsigned seed = 1; seed <= 6; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    // Roll the unit disc onto a cylinder of radius 0.25..0.6 (it wraps up to 1.3 times, so
    // far parts pass close to or through each other), add smooth waves and rotate.
    const double roll = 0.25 + 0.35 * U(rng);
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
    const double r_ex = 0.05 + 0.35 * U(rng);
    const int n = 1 + static_cast<int>(seed % 3);
    const SelfDistance d = smallest_self_distance(model, x, {r_ex, n});
    const BruteForceSelfDistance bf = brute_force_self_distance(model, x, r_ex, n);
    // The same samples and the same pair; the samples come from the cached lattice map here and
    // from evaluate_limit_surface in the brute force, equal up to the order of summation.
    EXPECT_NEAR(d.distance, bf.distance, 1e-14) << "seed " << seed;
    EXPECT_EQ(d.element_a, bf.element_a) << "seed " << seed;
    EXPECT_EQ(d.element_b, bf.element_b) << "seed " << seed;
    // Distinct samples of an N-ring disc: V = 1 + 3 N (N + 1) vertices, E = 3 N (3 N + 1)
    // edges (Euler: V - E + F = 1) with n - 1 each, F = 6 N^2 elements with
    // (n - 1)(n - 2) / 2 inside each.
    const Eigen::Index N = o.rings, samples = bf.samples;
    EXPECT_EQ(samples, 1 + 3 * N * (N + 1) + 3 * N * (3 * N + 1) * (n - 1) + 6 * N * N * (n - 1) * (n - 2) / 2);
    std::cout << "seed " << seed << ": roll " << roll << ", r_ex " << r_ex << ", n " << n << ", distance "
              << d.distance << ", pairs " << d.pairs_checked << " of " << samples * (samples - 1) / 2 << "\n";
    EXPECT_LT(d.pairs_checked, samples * (samples - 1) / 2 / 4) << "seed " << seed;
  }
}

TEST(SelfDistance, CostGrowsLinearlyAtFixedSamplesPerExclusionRadius) {
  // Refining the disc with r_ex a fixed multiple of the element size is, up to scale, a
  // larger sheet at fixed sample density: pairs per sample must stay bounded. Two states:
  // rolled onto a cylinder of radius 0.6 (bent, not touching: the answer is set by r_ex, the
  // expensive case) and of radius 0.3 (wrapped through itself: the answer is tiny).
  for (double roll : {0.6, 0.3}) {
    std::vector<double> per_sample;
    for (int rings : {8, 16, 32}) {
      DiscMeshOptions o;
      o.rings = rings;
      ShellModel model(make_disc_mesh(o), ShellModelSettings{});
      const Eigen::VectorXd x = map_reference(model, [roll](const Eigen::Vector3d& X) {
        const double t = X.x() / roll;
        return Eigen::Vector3d(roll * std::sin(t), X.y() + 0.1 * std::sin(3.0 * X.x()), roll * (1.0 - std::cos(t)));
      });
      const double r_ex = 2.5 / rings;
      const SelfDistance d = smallest_self_distance(model, x, {r_ex, 2});
      // Distinct samples for n = 2: vertices and edge midpoints (see the brute-force test).
      const double samples = 1.0 + 12.0 * rings * rings + 6.0 * rings;
      per_sample.push_back(static_cast<double>(d.pairs_checked) / samples);
      std::cout << "roll " << roll << ", rings " << rings << ", r_ex " << r_ex << ": samples " << samples
                << ", pairs " << d.pairs_checked << " (" << per_sample.back() << " per sample), distance "
                << d.distance << "\n";
    }
    // Linear cost: pairs per sample roughly constant (a 16x larger problem may not cost more
    // than 1.5x per sample); N^2 cost would raise it 16x.
    EXPECT_LT(per_sample[1], 1.5 * per_sample[0]) << "roll " << roll;
    EXPECT_LT(per_sample[2], 1.5 * per_sample[0]) << "roll " << roll;
  }
}

TEST(SelfDistance, RejectsBadOptionsNamingTheField) {
  DiscMeshOptions o;
  o.rings = 3;
  ShellModel model(make_disc_mesh(o), ShellModelSettings{});
  const Eigen::VectorXd& x = model.reference_positions();
  const auto message = [&](const SelfDistanceOptions& options, const Eigen::VectorXd& state) -> std::string {
    try {
      smallest_self_distance(model, state, options);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  for (double r : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()})
    EXPECT_NE(message({r, 2}, x).find("exclusion_radius"), std::string::npos) << r;
  for (int n : {0, -3}) EXPECT_NE(message({0.1, n}, x).find("samples_per_edge"), std::string::npos) << n;
  EXPECT_NE(message({0.1, 2}, x.head(x.size() - 3)).find("dimension"), std::string::npos);
  Eigen::VectorXd bad = x;
  bad(7) = std::numeric_limits<double>::infinity();
  EXPECT_NE(message({0.1, 2}, bad).find("x(7)"), std::string::npos);
}

TEST(SelfDistance, CoreRadiusIgnoresTheSheetAroundTheCentre) {
  DiscMeshOptions o;
  o.rings = 10;
  const ShellModel model(make_disc_mesh(o), ShellModelSettings{});
  SelfDistanceOptions opts;
  opts.exclusion_radius = 0.25;
  opts.core_radius = 0.5;
  const SelfDistance d = smallest_self_distance(model, model.reference_positions(), opts);
  // Flat: the closest admissible pair is still ~r_ex apart, now both points outside the core.
  EXPECT_GE(d.distance, opts.exclusion_radius);
  EXPECT_GE(d.reference_a.norm(), opts.core_radius);
  EXPECT_GE(d.reference_b.norm(), opts.core_radius);
  opts.core_radius = -1.0;
  EXPECT_THROW(smallest_self_distance(model, model.reference_positions(), opts),
               std::invalid_argument);
}

}  // namespace
}  // namespace growshell
