// econe_winding_options and read_winding_pins: the winding's settings follow the scene (h,
// Y, tolerance, step), and the record's pins file is read back exactly or refused by name.
#include <gtest/gtest.h>

#include <fstream>
#include <stdexcept>
#include <string>

#include "libshell/contact/contact_proxy.hpp"
#include "libshell/io/scene.hpp"
#include "studies/econe_winding_options.hpp"
#include "studies/scene_contact_penalty.hpp"
#include "tests/studies/scratch_directory.hpp"

namespace growshell {
namespace {

class WindingOptions : public testing::ScratchDirectoryTest {};

TEST_F(WindingOptions, FollowTheScene) {
  Scene scene = parse_scene(
      R"({"thickness": 0.08, "mesh": {"rings": 6}, "continuation": {"max_step": 0.03},
          "study": {"kind": "econe_contact", "tolerance": 1e-7}})",
      "test");
  const ShellModel model(scene_mesh(scene), scene_model_settings(scene));
  const ContactProxy proxy = make_contact_proxy(model, 1);
  const ContactGrowthOptions o = econe_winding_options(scene, model, proxy);
  const double h = 0.08, Y = scene.material.youngs_modulus;
  EXPECT_DOUBLE_EQ(o.newton.gradient_tolerance, 1e-7 * model.natural_force_scale());
  EXPECT_DOUBLE_EQ(o.newton.decrement_tolerance, 1e-6 * Y * h * h * h);
  EXPECT_DOUBLE_EQ(o.newton.max_step_inf_norm, 0.25 * h);
  EXPECT_EQ(o.newton.max_iterations, 5000);
  EXPECT_TRUE(o.newton.adaptive_shift);
  EXPECT_TRUE(o.secant_predictor);
  EXPECT_DOUBLE_EQ(o.max_step, 0.03);  // the scene's step, below 0.05
  EXPECT_FALSE(o.contact.selection.nearest_triangle_only);
  EXPECT_FALSE(o.contact.selection.edge_edge_pairs);
  EXPECT_EQ(o.contact.symmetric_subspace, nullptr);
  // The relaxation it builds on is the one the study's other relaxations use.
  const NewtonOptions base = scene_penalty_relaxation(scene, model);
  EXPECT_EQ(base.gradient_tolerance, o.newton.gradient_tolerance);
  EXPECT_EQ(base.decrement_tolerance, o.newton.decrement_tolerance);
  EXPECT_EQ(base.max_iterations, 400);
  EXPECT_FALSE(base.adaptive_shift);
}

TEST_F(WindingOptions, PinsAreReadBackOrRefusedByName) {
  const auto write = [this](const std::string& name, const std::string& text) {
    std::ofstream(path(name)) << text;
    return path(name);
  };
  const std::vector<Eigen::Index> pins = read_winding_pins(write("ok.txt", "0\n1\n2\n40\n"), 42);
  EXPECT_EQ(pins, (std::vector<Eigen::Index>{0, 1, 2, 40}));
  const auto refused = [](const std::string& file, Eigen::Index n) {
    try {
      read_winding_pins(file, n);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(refused(path("missing.txt"), 42).find("cannot be read"), std::string::npos);
  EXPECT_NE(refused(write("range.txt", "0\n42\n"), 42).find("dof 42 is not in [0, 42)"),
            std::string::npos);
  EXPECT_NE(refused(write("text.txt", "0\npin\n"), 42).find("not a list of dofs"),
            std::string::npos);
  EXPECT_NE(refused(write("empty.txt", ""), 42).find("not a list of dofs"), std::string::npos);
}

}  // namespace
}  // namespace growshell
