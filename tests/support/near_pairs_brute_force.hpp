#pragma once
// The reference answer of near_contact_pairs for the tests: every pair of the brute-force
// broad phase, measured one by one with ContactGapConstraints (mollifier off).

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "libshell/contact/contact_candidates.hpp"
#include "libshell/contact/contact_gap_constraints.hpp"
#include "libshell/contact/contact_proxy.hpp"

namespace growshell::test_support {

/// Reference answer: brute-force candidates at query distance `distance`, kept if their exact
/// (unmollified) distance is below it; with `nearest`, per vertex only the nearest triangle
/// (the first in index order among equals); edge-edge pairs only if `edges`.
inline ContactCandidates expected_near_pairs(const ContactProxy& proxy, const Eigen::VectorXd& x,
                                             double distance, double exclusion_radius, bool edges,
                                             bool nearest, Eigen::Index* candidates = nullptr) {
  ContactCandidateOptions co;
  co.query_distance = distance;
  co.exclusion_radius = exclusion_radius;
  const ContactCandidates all =
      find_contact_candidates_brute_force(proxy, proxy_positions(proxy, x), co);
  if (candidates != nullptr) *candidates = all.size();
  ContactCandidates out;
  out.vertex_triangle.resize(0, 2);
  out.edge_edge.resize(0, 2);
  if (all.empty()) return out;
  ContactGapOptions plain;
  plain.mollify_edge_edge = false;
  ContactGapConstraints c(proxy, all, 0.0, x.size(), plain);
  std::vector<Eigen::Index> vt, ee;
  const Eigen::Index nvt = all.vertex_triangle.rows();
  for (Eigen::Index k = 0; k < c.count(); ++k) {
    const double d = c.pair_geometry(x, k).distance;
    if (!(d < distance)) continue;
    if (k >= nvt) {
      if (edges) ee.push_back(k - nvt);
      continue;
    }
    if (nearest) {
      // Is there a pair of the same vertex that is nearer, or as near with a lower triangle?
      bool beaten = false;
      for (Eigen::Index m = 0; m < nvt && !beaten; ++m) {
        if (m == k || all.vertex_triangle(m, 0) != all.vertex_triangle(k, 0)) continue;
        const double dm = c.pair_geometry(x, m).distance;
        beaten = dm < distance &&
                 (dm < d || (dm == d && all.vertex_triangle(m, 1) < all.vertex_triangle(k, 1)));
      }
      if (beaten) continue;
    }
    vt.push_back(k);
  }
  out.vertex_triangle.resize(static_cast<Eigen::Index>(vt.size()), 2);
  out.edge_edge.resize(static_cast<Eigen::Index>(ee.size()), 2);
  for (std::size_t i = 0; i < vt.size(); ++i)
    out.vertex_triangle.row(static_cast<Eigen::Index>(i)) = all.vertex_triangle.row(vt[i]);
  for (std::size_t i = 0; i < ee.size(); ++i)
    out.edge_edge.row(static_cast<Eigen::Index>(i)) = all.edge_edge.row(ee[i]);
  return out;
}

/// Both pair sets equal, row for row.
inline void expect_same_pairs(const ContactCandidates& got, const ContactCandidates& want,
                              const std::string& what) {
  ASSERT_EQ(got.vertex_triangle.rows(), want.vertex_triangle.rows()) << what;
  ASSERT_EQ(got.edge_edge.rows(), want.edge_edge.rows()) << what;
  EXPECT_TRUE(got.vertex_triangle == want.vertex_triangle) << what;
  EXPECT_TRUE(got.edge_edge == want.edge_edge) << what;
}

}  // namespace growshell::test_support
