// The pattern-orientation check (check_pattern_orientation) on the coarse lattice disc grown to
// phi_e = 5: turned by a symmetry of the mesh (60 degrees), the relaxed state is the traced one
// turned, with the same energy and S4 defect; turned by any angle, the energy change splits
// exactly into its core and outside parts; bad options are refused by name.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "studies/pattern_orientation_check.hpp"
#include "tests/support/grown_disc.hpp"

namespace growshell {
namespace {

using test_support::GrownDisc;

PatternOrientationCheckOptions check_options(const GrownDisc& d, std::vector<double> turns) {
  PatternOrientationCheckOptions o;
  o.turns = std::move(turns);
  o.contact = d.options();
  o.relaxation.gradient_tolerance = 1e-8 * d.model.natural_force_scale();
  o.relaxation.max_iterations = 1000;
  o.relaxation.max_step_inf_norm = 0.25 * GrownDisc::kH;
  o.core_radius = GrownDisc::kH;
  return o;
}

/// a - b as an angle of the two-fold pattern's up-fold, in (-90, 90] degrees.
double fold_angle_difference_deg(double a, double b) {
  return std::remainder(a - b, std::numbers::pi) * 180.0 / std::numbers::pi;
}

TEST(PatternOrientationCheck, ATurnByASymmetryOfTheMeshGivesTheSameState) {
  GrownDisc& d = test_support::disc();
  const Eigen::VectorXd& x = d.start();
  const PatternOrientationCheck check = check_pattern_orientation(
      d.model, d.proxy, x, GrownDisc::kStart, d.pinned, check_options(d, {std::numbers::pi / 3}));
  ASSERT_EQ(check.turned.size(), 1u);
  const TurnedPatternState& t = check.turned[0];
  ASSERT_TRUE(t.converged) << t.message;
  // The lattice disc maps onto itself under the sixth turn: the relaxation ends on the traced
  // equilibrium turned, whatever the smoothing of the transfer.
  EXPECT_LT(std::abs(t.energy_relative), 1e-8);
  EXPECT_NEAR(t.s4_defect, check.s4_defect, 1e-6);
  EXPECT_NEAR(fold_angle_difference_deg(t.fold_angle, check.fold_angle), 60.0, 0.1)
      << "traced " << check.fold_angle << ", turned " << t.fold_angle;
  EXPECT_EQ(t.turn_free_index, 0);
  EXPECT_NEAR(check.largest_energy_change(), std::abs(t.energy_relative), 1e-15);
}

TEST(PatternOrientationCheck, TheEnergyChangeSplitsIntoCoreAndOutside) {
  GrownDisc& d = test_support::disc();
  const Eigen::VectorXd& x = d.start();
  const PatternOrientationCheck check = check_pattern_orientation(
      d.model, d.proxy, x, GrownDisc::kStart, d.pinned, check_options(d, {0.3, -0.2}));
  ASSERT_EQ(check.turned.size(), 2u);
  for (const TurnedPatternState& t : check.turned) {
    ASSERT_TRUE(t.converged) << t.message;
    const double change = t.energy - check.energy;
    EXPECT_NEAR(t.energy_change_core + t.energy_change_outside, change,
                1e-10 * std::abs(check.energy));
    EXPECT_NEAR(t.energy_relative, change / check.energy, 1e-14);
    EXPECT_GT(t.lowest_eigenvalue, -1e-3);  // a minimum, up to the nearly free turn
    EXPECT_TRUE(std::isfinite(t.fold_angle));
  }
  EXPECT_LE(std::abs(check.lowest_energy_relative()), check.largest_energy_change());
}

TEST(PatternOrientationCheck, RefusesBadOptionsByName) {
  GrownDisc& d = test_support::disc();
  const Eigen::VectorXd& x = d.start();
  const auto message = [&](const PatternOrientationCheckOptions& o, const Eigen::VectorXd& state) {
    try {
      check_pattern_orientation(d.model, d.proxy, state, GrownDisc::kStart, d.pinned, o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message(check_options(d, {}), x).find("turns is empty"), std::string::npos);
  EXPECT_NE(message(check_options(d, {std::nan("")}), x).find("non-finite turn"),
            std::string::npos);
  PatternOrientationCheckOptions no_core = check_options(d, {0.3});
  no_core.core_radius = 0.0;
  EXPECT_NE(message(no_core, x).find("core_radius"), std::string::npos);
  EXPECT_NE(message(check_options(d, {0.3}), x.head(6)).find("entries"), std::string::npos);
}

}  // namespace
}  // namespace growshell
