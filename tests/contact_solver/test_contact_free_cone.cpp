// trace_contact_free_cone: the cone from flat without contact, cut back to its last sample
// free of contact. On the contact tests' disc (h = 0.06, 8 rings) traced to phi_e = 6.6, past
// first contact: the start has no pair within h outside the exclusion radius while the next
// sample had one, the samples increase in phi_e, their slopes are the derivatives of their
// energies, and a larger exclusion radius lets the contact-free cone go further.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <numbers>
#include <stdexcept>

#include "libshell/contact/near_contact_pairs.hpp"
#include "solvers/contact/contact_free_cone.hpp"
#include "tests/support/grown_disc.hpp"

namespace growshell {
namespace {

using test_support::disc;
using test_support::GrownDisc;

TEST(ContactFreeCone, StopsAtTheLastSampleFreeOfContact) {
  GrownDisc& d = disc();
  const ContactFreeConeOptions o = d.cone_options(0.5 * std::numbers::pi);
  const ContactFreeCone cone = trace_contact_free_cone(d.model, d.proxy, d.pinned, o);
  ASSERT_TRUE(cone.found) << cone.message;
  EXPECT_TRUE(cone.stopped_before_contact);
  EXPECT_NEAR(cone.buckling_parameter, 10.56 * GrownDisc::kH * GrownDisc::kH, 0.05 * 0.038);
  ASSERT_GE(cone.samples.size(), 10u);
  EXPECT_EQ(cone.start.parameter, cone.samples.back().parameter);
  EXPECT_LT(cone.start.parameter, 6.6);
  EXPECT_GT(cone.start.parameter, 5.5);  // first contact near 6.0 on this disc
  EXPECT_TRUE(
      near_contact_pairs(d.proxy, cone.start.x, o.contact_distance, o.exclusion_radius).empty());
  for (std::size_t i = 1; i < cone.samples.size(); ++i)
    EXPECT_GT(cone.samples[i].parameter, cone.samples[i - 1].parameter);
  for (const SpecialPoint& p : cone.special_points) EXPECT_LT(p.parameter, cone.start.parameter);

  // Slopes: the trapezoidal rule of the slopes over the last ten intervals reproduces the
  // energy differences to the order of the interval squared.
  const std::vector<BranchEnergySample> e = contact_free_energies(d.model, cone.samples);
  ASSERT_EQ(e.size(), cone.samples.size());
  for (std::size_t i = e.size() - 10; i < e.size(); ++i) {
    const double dphi = e[i].parameter - e[i - 1].parameter;
    const double trapezoid = 0.5 * dphi * (e[i].energy_slope + e[i - 1].energy_slope);
    EXPECT_NEAR(e[i].energy - e[i - 1].energy, trapezoid,
                1e-2 * std::abs(e[i].energy - e[i - 1].energy) + 1e-9)
        << "interval ending at phi_e = " << e[i].parameter;
  }

  // Leaving the apex core out of the contact (8h) lets the contact-free cone go further.
  const ContactFreeCone wider =
      trace_contact_free_cone(d.model, d.proxy, d.pinned, d.cone_options(8.0));
  ASSERT_TRUE(wider.found) << wider.message;
  EXPECT_GT(wider.start.parameter, cone.start.parameter);
}

TEST(ContactFreeCone, BadDistancesAreNamed) {
  GrownDisc& d = disc();
  ContactFreeConeOptions o = d.cone_options(2.0);
  o.exclusion_radius = 0.5 * o.contact_distance;
  EXPECT_THROW(
      {
        try {
          trace_contact_free_cone(d.model, d.proxy, d.pinned, o);
        } catch (const std::invalid_argument& e) {
          EXPECT_NE(std::string(e.what()).find("exclusion_radius"), std::string::npos);
          throw;
        }
      },
      std::invalid_argument);
}

}  // namespace
}  // namespace growshell
