#include "solvers/contact/lowest_skewed_state.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

namespace growshell {
namespace {

Eigen::VectorXd state_of(double value) { return Eigen::VectorXd::Constant(3, value); }

// The two pushes measured at h = 0.02, phi_e = 7.095: 9e-6 J apart, less than the margin
// 1e-4 * 0.105968 = 1.06e-5 J. The lower one is chosen although it comes second.
TEST(LowestSkewedState, TheLowerOfTwoSkewedStatesCloserThanTheMarginIsChosen) {
  LowestSkewedState choice(0.105968, 1e-4);
  EXPECT_TRUE(choice.offer(0.105639, state_of(1.0)));
  EXPECT_TRUE(choice.offer(0.105630, state_of(2.0)));
  EXPECT_FALSE(choice.offer(0.105635, state_of(3.0)));
  ASSERT_TRUE(choice.found());
  EXPECT_DOUBLE_EQ(choice.energy(), 0.105630);
  EXPECT_DOUBLE_EQ(choice.state()(0), 2.0);
}

TEST(LowestSkewedState, AStateWithinTheMarginBelowTheSymmetricOneIsNotSkewed) {
  LowestSkewedState choice(-2.0, 0.01);  // the margin scales with |E|: threshold -2.02
  EXPECT_FALSE(choice.offer(-2.019, state_of(1.0)));
  EXPECT_FALSE(choice.offer(std::numeric_limits<double>::quiet_NaN(), state_of(1.0)));
  EXPECT_FALSE(choice.found());
  EXPECT_DOUBLE_EQ(choice.energy(), -2.0);
  EXPECT_EQ(choice.state().size(), 0);
  EXPECT_TRUE(choice.offer(-2.021, state_of(1.0)));
  EXPECT_DOUBLE_EQ(choice.energy(), -2.021);
}

TEST(LowestSkewedState, BadSettingsAreRejected) {
  EXPECT_THROW(LowestSkewedState(std::numeric_limits<double>::infinity(), 1e-4),
               std::invalid_argument);
  EXPECT_THROW(LowestSkewedState(1.0, -1e-4), std::invalid_argument);
  EXPECT_THROW(LowestSkewedState(1.0, std::numeric_limits<double>::quiet_NaN()),
               std::invalid_argument);
}

}  // namespace
}  // namespace growshell
