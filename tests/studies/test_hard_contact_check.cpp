// hard_contact_check: the JSON of a check (every field in order, non-finite values null) and
// the refusal of a state of the wrong size. The check itself runs end to end in the ctest
// growshell_econe_contact (the study's stage 6 and the program hard_contact_at on the same
// state, which must agree).
#include "studies/hard_contact_check.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libshell/contact/contact_proxy.hpp"
#include "tests/support/error_message.hpp"

namespace growshell {
namespace {

TEST(HardContactCheck, JsonHoldsEveryFieldInOrderWithNullForUndefinedMeasures) {
  HardContactCheck c;
  c.phi_e = 7.0;
  c.unknowns = 2427;
  c.converged = true;
  c.message = "converged with contact";
  c.seconds = 24.5;
  c.rounds = 1;
  c.iterations = 35;
  c.penalty_elastic_energy = 0.7155505240070001;
  c.hard_elastic_energy = 0.717806249742;
  c.relative_energy_difference = -0.00314252729867;
  c.state_difference_over_h = 0.81;
  c.penalty_min_distance_over_h = 0.948;
  c.hard_min_distance_over_h = std::numeric_limits<double>::infinity();
  c.penalty_s4_defect = 0.0055;
  c.hard_s4_defect = 0.0078;
  c.penalty_gamma = std::numeric_limits<double>::quiet_NaN();
  c.hard_gamma = 1.5624851826900001;
  c.x = Eigen::VectorXd::Ones(3);
  const auto j = nlohmann::ordered_json::parse(hard_contact_check_json(c));
  const std::vector<std::string> keys = {
      "phi_e", "unknowns", "converged", "message", "seconds", "rounds", "iterations",
      "penalty_elastic_energy", "hard_elastic_energy", "relative_energy_difference",
      "state_difference_over_h", "penalty_min_distance_over_h", "hard_min_distance_over_h",
      "penalty_s4_defect", "hard_s4_defect", "penalty_gamma", "hard_gamma"};
  std::vector<std::string> written;
  for (const auto& [key, value] : j.items()) written.push_back(key);
  EXPECT_EQ(written, keys);  // the state is not written
  EXPECT_EQ(j["penalty_elastic_energy"].get<double>(), 0.7155505240070001);  // round trip
  EXPECT_EQ(j["hard_gamma"].get<double>(), 1.5624851826900001);
  EXPECT_TRUE(j["hard_min_distance_over_h"].is_null());
  EXPECT_TRUE(j["penalty_gamma"].is_null());
  EXPECT_EQ(j["iterations"].get<int>(), 35);
  EXPECT_TRUE(j["converged"].get<bool>());
}

TEST(HardContactCheck, AStateOfTheWrongSizeIsRefusedByName) {
  Scene scene = default_scene();
  scene.thickness = ConstantThickness{0.05};
  scene.mesh.size_slope = 0.3;
  validate_scene(scene);
  const ShellModel model(scene_mesh(scene), scene_model_settings(scene));
  const ContactProxy proxy = make_contact_proxy(model, 1);
  BranchSample state;
  state.parameter = 7.0;
  state.x = Eigen::VectorXd::Zero(model.dimension() - 3);
  const std::string error =
      test_support::error_of([&] { check_hard_contact(scene, model, proxy, state); });
  EXPECT_NE(error.find("the state has"), std::string::npos) << error;
}

}  // namespace
}  // namespace growshell
