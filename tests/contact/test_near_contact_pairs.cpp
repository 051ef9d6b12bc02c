// near_contact_pairs, merge_contact_pairs and smallest_pair_distance: the near pairs are
// exactly the brute-force candidates whose exact (unmollified) distance is below the query
// distance, with and without the nearest-triangle selection; the union of two pair sets is
// sorted and free of duplicates; the smallest distance is that of the closest pair.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <initializer_list>
#include <limits>
#include <string>
#include <utility>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_candidates.hpp"
#include "libshell/contact/contact_gap_constraints.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "libshell/contact/near_contact_pairs.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "support/near_pairs_brute_force.hpp"
#include "support/sheet_states.hpp"

namespace growshell {
namespace {

using test_support::expect_same_pairs;
using test_support::expected_near_pairs;
using test_support::folded_sheet;

TEST(NearContactPairs, ExactlyThePairsCloserThanTheDistance) {
  DiscMeshOptions mesh;
  mesh.rings = 5;
  ShellModel model(make_disc_mesh(mesh), ShellModelSettings{});
  const ContactProxy proxy = make_contact_proxy(model, 2);
  // Layers 0.08 m apart, wobble 0.01 m: distances between the layers spread over about
  // 0.06 .. 0.1 m, so a query at 0.09 m cuts through the middle of them.
  const Eigen::VectorXd x = folded_sheet(model, 0.0, 0.04, 0.01);
  const double r_ex = 0.2;
  for (const double distance : {0.09, 0.12}) {
    Eigen::Index candidates = 0;
    const ContactCandidates want =
        expected_near_pairs(proxy, x, distance, r_ex, true, false, &candidates);
    const ContactCandidates got = near_contact_pairs(proxy, x, distance, r_ex);
    // Measured: at 0.09 m 1559 vertex-triangle + 4160 edge-edge pairs of 12664 candidates,
    // at 0.12 m 2995 + 7739 of 21475.
    // The filter is exercised: some candidates of the boxes are dropped, both kinds kept.
    EXPECT_GT(want.vertex_triangle.rows(), 0);
    EXPECT_GT(want.edge_edge.rows(), 0);
    EXPECT_LT(want.size(), candidates);
    expect_same_pairs(got, want, "all pairs at " + std::to_string(distance));

    NearPairSelection nearest;
    nearest.edge_edge_pairs = false;
    nearest.nearest_triangle_only = true;
    const ContactCandidates want_nearest =
        expected_near_pairs(proxy, x, distance, r_ex, false, true);
    const ContactCandidates got_nearest = near_contact_pairs(proxy, x, distance, r_ex, nearest);
    EXPECT_LT(want_nearest.vertex_triangle.rows(), want.vertex_triangle.rows());
    expect_same_pairs(got_nearest, want_nearest,
                      "nearest triangles at " + std::to_string(distance));
  }
  // Below the smallest distance between the layers: nothing.
  EXPECT_TRUE(near_contact_pairs(proxy, x, 0.03, r_ex).empty());
}

Eigen::MatrixX2i rows(std::initializer_list<std::pair<int, int>> pairs) {
  Eigen::MatrixX2i m(static_cast<Eigen::Index>(pairs.size()), 2);
  Eigen::Index i = 0;
  for (const auto& [a, b] : pairs) m.row(i++) << a, b;
  return m;
}

TEST(NearContactPairs, MergeIsTheSortedUnionWithoutDuplicates) {
  ContactCandidates a, b;
  a.vertex_triangle = rows({{1, 4}, {3, 0}, {3, 2}});
  a.edge_edge = rows({{0, 5}});
  b.vertex_triangle = rows({{0, 7}, {3, 0}, {3, 1}});
  b.edge_edge = rows({{0, 5}, {2, 3}});
  const ContactCandidates m = merge_contact_pairs(a, b);
  EXPECT_TRUE(m.vertex_triangle == rows({{0, 7}, {1, 4}, {3, 0}, {3, 1}, {3, 2}}));
  EXPECT_TRUE(m.edge_edge == rows({{0, 5}, {2, 3}}));
  const ContactCandidates none;
  expect_same_pairs(merge_contact_pairs(a, none), a, "a with nothing");
  expect_same_pairs(merge_contact_pairs(none, a), a, "nothing with a");
}

TEST(NearContactPairs, SmallestPairDistanceIsTheClosestPairs) {
  DiscMeshOptions mesh;
  mesh.rings = 5;
  ShellModel model(make_disc_mesh(mesh), ShellModelSettings{});
  const ContactProxy proxy = make_contact_proxy(model, 2);
  const Eigen::VectorXd x = folded_sheet(model, 0.0, 0.04, 0.01);
  const ContactCandidates near = near_contact_pairs(proxy, x, 0.09, 0.2);
  ASSERT_FALSE(near.empty());
  ContactGapOptions plain;
  plain.mollify_edge_edge = false;
  ContactGapConstraints gaps(proxy, near, 0.0, x.size(), plain);
  Eigen::VectorXd d;
  gaps.evaluate(x, d, nullptr);
  // The same distance primitives, evaluated once through the gap constraints' proxy map:
  // equal to rounding.
  EXPECT_NEAR(smallest_pair_distance(proxy, near, x), d.minCoeff(), 1e-14);
  EXPECT_EQ(smallest_pair_distance(proxy, ContactCandidates{}, x),
            std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace growshell
