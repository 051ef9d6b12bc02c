#include "studies/ground_state_exchange.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace growshell {
namespace {

/// The first branch: E = 1 on phi in [5, 8], sampled every 0.1.
std::vector<BranchStateSample> flat_branch() {
  std::vector<BranchStateSample> out;
  for (int k = 0; k <= 30; ++k) out.push_back({5.0 + 0.1 * k, 1.0, 0});
  return out;
}

/// The second branch E = 1 - (phi - c) / 100 with the given negative count per phi, sampled
/// every 0.1 from 5.5 to 7.5, listed in the order a trace down and a trace up would write it.
std::vector<BranchStateSample> line_branch(double c, double stable_from) {
  std::vector<BranchStateSample> down, up;
  for (int k = 0; k <= 20; ++k) {
    const double phi = 5.5 + 0.1 * k;
    const BranchStateSample s{phi, 1.0 - (phi - c) / 100.0, phi >= stable_from ? 0 : 1};
    (phi < 6.55 ? down : up).push_back(s);
  }
  std::vector<BranchStateSample> out(down.rbegin(), down.rend());
  out.insert(out.end(), up.begin(), up.end());
  return out;
}

TEST(GroundStateExchange, IsTheCrossingWhereTheSecondBranchIsStableThere) {
  // Crosses at 6.25 and is stable from 5.5: the accurate crossing given replaces the linear one.
  const auto x = ground_state_exchange(flat_branch(), line_branch(6.25, 0.0), {6.2501}, {});
  ASSERT_TRUE(x.has_value());
  EXPECT_EQ(x->criterion, "energy_crossing");
  EXPECT_DOUBLE_EQ(x->phi_e, 6.2501);
  // One interval away (the linear interpolation of a coarsely sampled first branch can move
  // the sign change by an interval): still the accurate one.
  const auto near = ground_state_exchange(flat_branch(), line_branch(6.25, 0.0), {6.17}, {});
  ASSERT_TRUE(near.has_value());
  EXPECT_DOUBLE_EQ(near->phi_e, 6.17);
  // Two intervals away it is another crossing: the linear estimate stands.
  const auto far = ground_state_exchange(flat_branch(), line_branch(6.25, 0.0), {6.02}, {});
  ASSERT_TRUE(far.has_value());
  EXPECT_NEAR(far->phi_e, 6.25, 1e-12);
  // Without it, the linear estimate, exact for these lines.
  const auto linear = ground_state_exchange(flat_branch(), line_branch(6.25, 0.0), {}, {});
  ASSERT_TRUE(linear.has_value());
  EXPECT_NEAR(linear->phi_e, 6.25, 1e-12);
}

TEST(GroundStateExchange, IsWhereALowerSaddleTurnsStable) {
  // Below the first branch from 5.8 on, but a saddle up to 6.65 (a branch point at 6.62): the
  // crossing at 5.8 is not the exchange.
  const auto x = ground_state_exchange(flat_branch(), line_branch(5.8, 6.65), {5.8}, {6.62});
  ASSERT_TRUE(x.has_value());
  EXPECT_EQ(x->criterion, "stabilised_below");
  EXPECT_DOUBLE_EQ(x->phi_e, 6.62);
  // Without the special point, the first stable sample below.
  const auto coarse = ground_state_exchange(flat_branch(), line_branch(5.8, 6.65), {5.8}, {});
  ASSERT_TRUE(coarse.has_value());
  EXPECT_NEAR(coarse->phi_e, 6.7, 1e-12);
}

TEST(GroundStateExchange, IsNoneWhileTheSecondBranchStaysAboveOrUnstable) {
  EXPECT_FALSE(ground_state_exchange(flat_branch(), line_branch(9.0, 0.0), {}, {}).has_value());
  EXPECT_FALSE(ground_state_exchange(flat_branch(), line_branch(5.0, 99.0), {5.0}, {}));
  // Stable and below from its lowest sample: only an upper bound, and said so.
  const auto x = ground_state_exchange(flat_branch(), line_branch(5.0, 0.0), {}, {});
  ASSERT_TRUE(x.has_value());
  EXPECT_EQ(x->criterion, "lowest_sample");
  EXPECT_NEAR(x->phi_e, 5.5, 1e-12);
}

TEST(BranchEnergyAt, InterpolatesBetweenTheBracketingSamplesAndIsNoneOutside) {
  const std::vector<BranchStateSample> branch = {{5.0, 1.0, 0}, {6.0, 3.0, 0}, {7.0, 2.0, 1}};
  EXPECT_DOUBLE_EQ(*branch_energy_at(branch, 5.25), 1.5);
  EXPECT_DOUBLE_EQ(*branch_energy_at(branch, 6.0), 3.0);
  EXPECT_DOUBLE_EQ(*branch_energy_at(branch, 6.5), 2.5);
  EXPECT_FALSE(branch_energy_at(branch, 4.99).has_value());
  EXPECT_FALSE(branch_energy_at(branch, 7.01).has_value());
  EXPECT_FALSE(branch_energy_at({}, 6.0).has_value());
}

}  // namespace
}  // namespace growshell
