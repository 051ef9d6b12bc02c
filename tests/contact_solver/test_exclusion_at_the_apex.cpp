// At the apex of an e-cone every generator runs into the apex, so two points on opposite sides
// at reference radius rho are about c(phi_e) rho apart in space. The closest pair of points
// that are not neighbours (reference distance >= the exclusion radius r_ex) therefore
// straddles the apex at reference distance r_ex, and its distance grows with r_ex: first
// contact is set by r_ex / h, not by the sheet (docs/contact.md, "Exclusion radius"). Checked
// on the contact tests' grown cone.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <numbers>

#include "libshell/analysis/self_distance.hpp"
#include "tests/support/grown_disc.hpp"

namespace growshell {
namespace {

using test_support::disc;
using test_support::GrownDisc;

TEST(ExclusionAtTheApex, ClosestPairStraddlesTheApexAtTheExclusionRadius) {
  GrownDisc& d = disc();
  const double h = GrownDisc::kH;
  double previous = 0.0;
  for (const double factor : {0.5 * std::numbers::pi, 2.0, 3.0, 4.0}) {
    SelfDistanceOptions o;
    o.exclusion_radius = factor * h;
    o.samples_per_edge = 4;
    const SelfDistance s = smallest_self_distance(d.model, d.start(), o);
    const Eigen::Vector2d a = s.reference_a.head<2>(), b = s.reference_b.head<2>();
    const double separation = (a - b).norm();
    // At reference distance r_ex up to about one sample spacing next to the apex (the mesh
    // spacing there is h/2, 4 segments per edge: h/8; measured within 0.04 h)...
    EXPECT_GE(separation, o.exclusion_radius) << "r_ex = " << factor << " h";
    EXPECT_LE(separation, o.exclusion_radius + 0.15 * h) << "r_ex = " << factor << " h";
    // ... on opposite sides of the apex: the centre lies on the chord between them (its
    // midpoint is within a sample spacing of the centre; measured 0 to 0.12 h).
    EXPECT_LE((a + b).norm() / 2, 0.15 * h) << "r_ex = " << factor << " h";
    // ... and closer in space than in the reference: the cone has folded across its apex.
    EXPECT_LT(s.distance, separation) << "r_ex = " << factor << " h";
    // A larger exclusion radius leaves a larger smallest distance.
    EXPECT_GT(s.distance, previous) << "r_ex = " << factor << " h";
    previous = s.distance;
  }
}

}  // namespace
}  // namespace growshell
