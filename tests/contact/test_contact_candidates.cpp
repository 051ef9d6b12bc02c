// Broad phase on the contact proxy: the spatial hash equals brute force on random folded
// discs, its exclusions are the neighbours on the sheet, nothing close is missed, the
// no-contact fast path, cost linear at fixed density, bad input.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "libshell/contact/contact_candidates.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "support/sheet_states.hpp"

namespace growshell {
namespace {

using test_support::map_reference;

/// The unit disc rolled onto a cylinder of radius 0.25..0.6 (it wraps up to 1.3 times, so far
/// parts pass close to or through each other), with smooth random waves and a random rotation.
Eigen::VectorXd random_folded_disc(const ShellModel& model, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const double roll = 0.25 + 0.35 * U(rng);
  Eigen::Matrix3d wave_k, wave_phase;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      wave_k(i, j) = 1.0 + 3.0 * U(rng);
      wave_phase(i, j) = 2.0 * std::numbers::pi * U(rng);
    }
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(2.0 * std::numbers::pi * U(rng),
                        Eigen::Vector3d(U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5).normalized())
          .toRotationMatrix();
  return map_reference(model, [&](const Eigen::Vector3d& X) {
    const double t = X.x() / roll;
    Eigen::Vector3d p(roll * std::sin(t), X.y(), roll * (1.0 - std::cos(t)));
    for (int c = 0; c < 3; ++c)
      p(c) += 0.05 * std::sin(wave_k(c, 0) * X.x() + wave_k(c, 1) * X.y() + wave_phase(c, 0)) *
              std::cos(wave_k(c, 2) * X.y() + wave_phase(c, 1));
    return Eigen::Vector3d(rotation * p);
  });
}

using PairSet = std::set<std::pair<int, int>>;

PairSet as_set(const Eigen::MatrixX2i& m) {
  PairSet s;
  for (Eigen::Index k = 0; k < m.rows(); ++k) s.insert({m(k, 0), m(k, 1)});
  return s;
}

/// Rows strictly increasing (sorted, no duplicates).
bool strictly_sorted(const Eigen::MatrixX2i& m) {
  for (Eigen::Index k = 1; k < m.rows(); ++k)
    if (!(std::make_pair(m(k - 1, 0), m(k - 1, 1)) < std::make_pair(m(k, 0), m(k, 1))))
      return false;
  return true;
}

double reference_distance(const ContactProxy& proxy, std::initializer_list<int> a,
                          std::initializer_list<int> b) {
  double best = std::numeric_limits<double>::infinity();
  for (int p : a)
    for (int q : b)
      best = std::min(best,
                      (proxy.reference_positions.row(p) - proxy.reference_positions.row(q)).norm());
  return best;
}

TEST(ContactCandidates, SpatialHashEqualsBruteForceOnRandomFoldedDiscs) {
  DiscMeshOptions o;
  o.rings = 8;
  const ShellModel model(make_disc_mesh(o), ShellModelSettings{});
  const ContactProxy proxy = make_contact_proxy(model, 2);
  Eigen::Index total_vt = 0, total_ee = 0, total_excluded = 0;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Eigen::MatrixX3d y = proxy_positions(proxy, random_folded_disc(model, seed));
    std::mt19937 rng(100 + seed);
    const double r_ex = std::uniform_real_distribution<double>(0.05, 0.3)(rng);
    for (double d : {0.0, 0.01, 0.05, 0.3}) {
      const ContactCandidateOptions options{d, r_ex};
      const ContactCandidates hash = find_contact_candidates(proxy, y, options);
      const ContactCandidates brute = find_contact_candidates_brute_force(proxy, y, options);
      // Exact equality: both apply the same predicate; the hash must not lose or add a pair.
      ASSERT_EQ(hash.vertex_triangle, brute.vertex_triangle) << "seed " << seed << " d " << d;
      ASSERT_EQ(hash.edge_edge, brute.edge_edge) << "seed " << seed << " d " << d;
      EXPECT_TRUE(strictly_sorted(hash.vertex_triangle));
      EXPECT_TRUE(strictly_sorted(hash.edge_edge));
      EXPECT_EQ(has_contact_candidates(proxy, y, options), !hash.empty());
      // The hash looks at far fewer pairs than brute force: about 20 per primitive for d well
      // below the proxy edge length (0.03 .. 0.09 m), about 100 for d = 0.05 (the query boxes
      // then span several edges), against 1300 for brute force. Not so for d = 0.3, a third of
      // the sheet, where most pairs are candidates anyway.
      if (d <= 0.01) {
        EXPECT_LT(hash.pairs_examined, brute.pairs_examined / 20) << "seed " << seed << " d " << d;
      } else if (d <= 0.05) {
        EXPECT_LT(hash.pairs_examined, brute.pairs_examined / 8) << "seed " << seed << " d " << d;
      }

      // Every reported pair is admissible ...
      for (Eigen::Index k = 0; k < hash.vertex_triangle.rows(); ++k) {
        const int p = hash.vertex_triangle(k, 0), t = hash.vertex_triangle(k, 1);
        const auto tri = proxy.triangles.row(t);
        ASSERT_TRUE(tri(0) != p && tri(1) != p && tri(2) != p);
        ASSERT_GE(reference_distance(proxy, {p}, {tri(0), tri(1), tri(2)}), r_ex);
      }
      for (Eigen::Index k = 0; k < hash.edge_edge.rows(); ++k) {
        const auto a = proxy.edges.row(hash.edge_edge(k, 0)),
                   b = proxy.edges.row(hash.edge_edge(k, 1));
        ASSERT_LT(hash.edge_edge(k, 0), hash.edge_edge(k, 1));
        ASSERT_GE(reference_distance(proxy, {a(0), a(1)}, {b(0), b(1)}), r_ex);
      }
      // ... and every pair the exclusion removed is a neighbour on the sheet: without the
      // exclusion (r_ex = 0) the result is a superset whose extra pairs all have reference
      // distance < r_ex.
      const ContactCandidates all = find_contact_candidates(proxy, y, {d, 0.0});
      const PairSet vt = as_set(hash.vertex_triangle), ee = as_set(hash.edge_edge);
      for (Eigen::Index k = 0; k < all.vertex_triangle.rows(); ++k) {
        const int p = all.vertex_triangle(k, 0), t = all.vertex_triangle(k, 1);
        if (vt.count({p, t})) continue;
        ++total_excluded;
        ASSERT_LT(
            reference_distance(
                proxy, {p}, {proxy.triangles(t, 0), proxy.triangles(t, 1), proxy.triangles(t, 2)}),
            r_ex);
      }
      for (Eigen::Index k = 0; k < all.edge_edge.rows(); ++k) {
        const int a = all.edge_edge(k, 0), b = all.edge_edge(k, 1);
        if (ee.count({a, b})) continue;
        ++total_excluded;
        ASSERT_LT(reference_distance(proxy, {proxy.edges(a, 0), proxy.edges(a, 1)},
                                     {proxy.edges(b, 0), proxy.edges(b, 1)}),
                  r_ex);
      }
      EXPECT_EQ(static_cast<Eigen::Index>(vt.size()) + static_cast<Eigen::Index>(ee.size()),
                hash.size());
      EXPECT_LE(hash.vertex_triangle.rows(), all.vertex_triangle.rows());
      total_vt += hash.vertex_triangle.rows();
      total_ee += hash.edge_edge.rows();
      std::cout << "seed " << seed << " r_ex " << r_ex << " d " << d << ": vertex-triangle "
                << hash.vertex_triangle.rows() << ", edge-edge " << hash.edge_edge.rows()
                << ", without exclusion " << all.size() << ", pairs examined "
                << hash.pairs_examined << " of " << brute.pairs_examined << "\n";
    }
  }
  // The test is only meaningful if the folds produce candidates and exclusions.
  EXPECT_GT(total_vt, 1000);
  EXPECT_GT(total_ee, 1000);
  EXPECT_GT(total_excluded, 1000);
}

TEST(ContactCandidates, NoCloseVertexPairIsMissed) {
  // Independent of the box predicate: if vertex p is within d of a vertex q of triangle t (and
  // t is outside the exclusion radius of p), then p is within d of t, so (p, t) must be found.
  DiscMeshOptions o;
  o.rings = 6;
  const ShellModel model(make_disc_mesh(o), ShellModelSettings{});
  const ContactProxy proxy = make_contact_proxy(model, 2);
  std::vector<std::vector<int>> triangles_of(static_cast<std::size_t>(proxy.num_vertices()));
  for (Eigen::Index t = 0; t < proxy.triangles.rows(); ++t)
    for (int c = 0; c < 3; ++c)
      triangles_of[static_cast<std::size_t>(proxy.triangles(t, c))].push_back(static_cast<int>(t));
  Eigen::Index checked = 0;
  for (unsigned seed = 11; seed <= 13; ++seed) {
    const Eigen::MatrixX3d y = proxy_positions(proxy, random_folded_disc(model, seed));
    const double d = 0.03, r_ex = 0.1;
    const PairSet vt = as_set(find_contact_candidates(proxy, y, {d, r_ex}).vertex_triangle);
    for (int p = 0; p < proxy.num_vertices(); ++p)
      for (int q = 0; q < proxy.num_vertices(); ++q) {
        if (p == q || (y.row(p) - y.row(q)).norm() > d) continue;
        for (int t : triangles_of[static_cast<std::size_t>(q)]) {
          const auto tri = proxy.triangles.row(t);
          if (reference_distance(proxy, {p}, {tri(0), tri(1), tri(2)}) < r_ex) continue;
          ++checked;
          ASSERT_TRUE(vt.count({p, t})) << "vertex " << p << " triangle " << t << " seed " << seed;
        }
      }
  }
  std::cout << "close vertex-triangle pairs checked: " << checked << "\n";
  EXPECT_GT(checked, 100);
}

TEST(ContactCandidates, FlatDiscHasNoCandidatesWithinASmallDistance) {
  DiscMeshOptions o;
  o.rings = 8;
  const ShellModel model(make_disc_mesh(o), ShellModelSettings{});
  const ContactProxy proxy = make_contact_proxy(model, 2);
  const Eigen::MatrixX3d& y = proxy.reference_positions;
  // Flat, current = reference: a vertex at reference distance >= r_ex = 0.3 from all corners of
  // a triangle (edges <= 0.09 m: 1.40 R / N / n, disc_mesh.hpp) is at least 0.3 - 0.09 from
  // the triangle, and its boxes' largest axis gap is at least that / sqrt(2) = 0.15 in the
  // plane; same for two edges. So d = 0.1 finds nothing, while d = 0.25 must find pairs.
  const ContactCandidateOptions small{0.1, 0.3}, large{0.25, 0.3};
  EXPECT_FALSE(has_contact_candidates(proxy, y, small));
  EXPECT_TRUE(find_contact_candidates(proxy, y, small).empty());
  EXPECT_TRUE(has_contact_candidates(proxy, y, large));
  const ContactCandidates found = find_contact_candidates(proxy, y, large);
  EXPECT_FALSE(found.empty());
  EXPECT_EQ(found.vertex_triangle,
            find_contact_candidates_brute_force(proxy, y, large).vertex_triangle);
}

TEST(ContactCandidates, CostGrowsLinearlyAtFixedDensity) {
  // Refining the disc with d and r_ex fixed multiples of the spacing is, up to scale, a larger
  // sheet at fixed density: pairs examined per primitive must stay bounded (brute force grows
  // like N). State: rolled onto a cylinder of radius 0.3 with a wave, wrapped through itself.
  std::vector<double> per_primitive;
  for (int rings : {8, 16, 32}) {
    DiscMeshOptions o;
    o.rings = rings;
    const ShellModel model(make_disc_mesh(o), ShellModelSettings{});
    const ContactProxy proxy = make_contact_proxy(model, 2);
    const double roll = 0.3;
    const Eigen::MatrixX3d y = proxy_positions(
        proxy, map_reference(model, [roll](const Eigen::Vector3d& X) {
          const double t = X.x() / roll;
          return Eigen::Vector3d(roll * std::sin(t), X.y() + 0.1 * std::sin(3.0 * X.x()),
                                 roll * (1.0 - std::cos(t)));
        }));
    const ContactCandidateOptions options{0.4 / rings, 2.5 / rings};
    const ContactCandidates c = find_contact_candidates(proxy, y, options);
    const double primitives = static_cast<double>(proxy.num_vertices() + proxy.edges.rows());
    per_primitive.push_back(static_cast<double>(c.pairs_examined) / primitives);
    std::cout << "rings " << rings << ": primitives " << primitives << ", candidates " << c.size()
              << ", pairs examined " << c.pairs_examined << " (" << per_primitive.back()
              << " per primitive)\n";
    EXPECT_FALSE(c.empty()) << rings;  // wrapped through itself: real candidates exist
  }
  // Linear cost: a 16x larger problem may not cost more than 1.5x per primitive; quadratic
  // cost would raise it 16x.
  EXPECT_LT(per_primitive[1], 1.5 * per_primitive[0]);
  EXPECT_LT(per_primitive[2], 1.5 * per_primitive[0]);
}

TEST(ContactCandidates, RejectsBadInputNamingIt) {
  DiscMeshOptions o;
  o.rings = 3;
  const ShellModel model(make_disc_mesh(o), ShellModelSettings{});
  const ContactProxy proxy = make_contact_proxy(model, 2);
  const Eigen::MatrixX3d y = proxy.reference_positions;
  const auto message = [&](const Eigen::MatrixX3d& positions,
                           ContactCandidateOptions options) -> std::string {
    try {
      find_contact_candidates(proxy, positions, options);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  const double nan = std::numeric_limits<double>::quiet_NaN(),
               inf = std::numeric_limits<double>::infinity();
  for (double bad : {-1.0, nan, inf}) {
    EXPECT_NE(message(y, {bad, 0.1}).find("query_distance"), std::string::npos) << bad;
    EXPECT_NE(message(y, {0.1, bad}).find("exclusion_radius"), std::string::npos) << bad;
  }
  EXPECT_NE(message(y.topRows(y.rows() - 1), {0.1, 0.1}).find("rows"), std::string::npos);
  Eigen::MatrixX3d broken = y;
  broken(5, 1) = nan;
  EXPECT_NE(message(broken, {0.1, 0.1}).find("positions(5, 1)"), std::string::npos);
  EXPECT_THROW(find_contact_candidates_brute_force(proxy, broken, {0.1, 0.1}),
               std::invalid_argument);
  EXPECT_THROW(has_contact_candidates(proxy, broken, {0.1, 0.1}), std::invalid_argument);
}

}  // namespace
}  // namespace growshell
