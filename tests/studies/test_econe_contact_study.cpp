#include "studies/econe_contact_study.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/studies/scratch_directory.hpp"
#include "tests/support/error_message.hpp"

namespace growshell {
namespace {

using EconeContact = testing::ScratchDirectoryTest;
using test_support::error_of;

EconeContactResults sample_results() {
  EconeContactResults r;
  r.thickness = 0.04;
  r.mesh.family = "rings";
  r.mesh.size_slope = 0.1;
  r.mesh.elements = 3600;
  r.mesh.unknowns = 5691;
  r.contact_distance = 0.04;
  r.exclusion_radius = 0.32;
  r.penalty_stiffness = 3329.0;
  r.proxy_segments_per_edge = 2;
  r.proxy_vertices = 7057;
  r.contact_surface = "limit_surface";
  r.phi_branch = 0.0171;
  r.phi_max = 4.066;
  r.eb_hat_max = 4.27;
  r.phi_contact_start = 6.55;
  r.phi_first_contact = 6.57;
  r.phi_crit_stability = 7.03;
  r.crossings = {{5.6, 1e-5, false}, {7.1, 2e-5, true}};
  r.phi_crit_energy = 6.9;
  r.phi_crit_energy_criterion = "stabilised_below";
  r.max_s4_defect_symmetric = 2e-16;
  r.skewed_found = true;
  r.skewed_message = "relaxed";
  r.skew_search_at = 7.2;
  r.skewed_energy_below_symmetric = 4e-3;
  r.skewed_lowest_phi = 6.5;
  r.skewed_highest_phi = std::numeric_limits<double>::quiet_NaN();  // written as null
  r.completed = true;
  r.end = "completed";
  return r;
}

TEST(EconeContactResultsJson, NamesEveryKeyInOrderWithNullsForWhatIsMissing) {
  const auto j = nlohmann::ordered_json::parse(econe_contact_results_json(sample_results()));
  std::vector<std::string> keys;
  for (auto it = j.begin(); it != j.end(); ++it) keys.push_back(it.key());
  const std::vector<std::string> expected = {"study",
                                             "thickness",
                                             "mesh",
                                             "contact_distance",
                                             "exclusion_radius",
                                             "penalty_stiffness",
                                             "contact_proxy",
                                             "phi_branch",
                                             "phi_max",
                                             "eb_hat_max",
                                             "phi_contact_start",
                                             "phi_kiss",
                                             "phi_kiss_criterion",
                                             "phi_first_contact",
                                             "phi_crit_stability",
                                             "phi_crit_energy",
                                             "phi_crit_energy_criterion",
                                             "phi_crit_energy_reference",
                                             "crossings",
                                             "max_s4_defect_symmetric",
                                             "skewed",
                                             "ipopt",
                                             "hard_contact",
                                             "orientation_check",
                                             "turned",
                                             "compared_modes",
                                             "wound",
                                             "energy_ratio_f",
                                             "warnings",
                                             "completed",
                                             "end",
                                             "cone_csv",
                                             "symmetric_csv",
                                             "skewed_csv",
                                             "turned_csv",
                                             "wound_csv",
                                             "events",
                                             "wall_seconds"};
  EXPECT_EQ(keys, expected);
  EXPECT_EQ(j["study"], "econe_contact");
  // phi_kiss is the first contact on the symmetric branch, and says so.
  EXPECT_EQ(j["phi_kiss"].get<double>(), 6.57);
  EXPECT_EQ(j["phi_kiss_criterion"], "first_contact");
  EXPECT_EQ(j["phi_crit_energy"].get<double>(), 6.9);
  EXPECT_EQ(j["phi_crit_stability"].get<double>(), 7.03);
  EXPECT_EQ(j["phi_crit_energy_criterion"], "stabilised_below");
  EXPECT_EQ(j["phi_crit_energy_reference"], "symmetric");
  ASSERT_EQ(j["crossings"].size(), 2u);
  EXPECT_EQ(j["crossings"][0]["phi_e"].get<double>(), 5.6);
  EXPECT_FALSE(j["crossings"][0]["skewed_stable"].get<bool>());
  EXPECT_TRUE(j["crossings"][1]["skewed_stable"].get<bool>());
  EXPECT_TRUE(j["skewed"]["highest_phi"].is_null());
  EXPECT_EQ(j["skewed"]["lowest_phi"].get<double>(), 6.5);
  EXPECT_TRUE(j["ipopt"].is_null());  // not checked
  EXPECT_EQ(j["symmetric_csv"], "symmetric/branch.csv");
  EXPECT_EQ(j["mesh"]["unknowns"].get<long long>(), 5691);
  EXPECT_EQ(j["contact_proxy"]["segments_per_edge"].get<int>(), 2);
  EXPECT_EQ(j["contact_proxy"]["vertices"].get<long long>(), 7057);
  EXPECT_EQ(j["contact_proxy"]["surface"], "limit_surface");

  EconeContactResults checked = sample_results();
  checked.ipopt = EconeIpoptCheck{true, "Optimal Solution Found", 1e-7, 0.02, 1.01};
  const auto k = nlohmann::json::parse(econe_contact_results_json(checked));
  EXPECT_TRUE(k["ipopt"]["converged"].get<bool>());
  EXPECT_DOUBLE_EQ(k["ipopt"]["min_distance_over_h"].get<double>(), 1.01);
  EXPECT_TRUE(j["orientation_check"].is_null());  // not run
  // study.wind_to: null without it; with it, the path's ends, its jumps and its shapes.
  EXPECT_TRUE(j["wound"].is_null());
  EXPECT_TRUE(j["compared_modes"].is_array() && j["compared_modes"].empty());
  EconeContactResults modes = sample_results();
  EconeComparedMode three;
  three.mode = 3;
  three.directory = "cone_n3";
  three.phi_branch = 0.034;
  three.lowest_energy_above_two_fold = 0.12;
  three.lowest_energy_above_two_fold_phi = 7.3;
  modes.compared_modes.push_back(three);
  const auto mj = nlohmann::json::parse(econe_contact_results_json(modes));
  EXPECT_EQ(mj["compared_modes"][0]["mode"].get<int>(), 3);
  EXPECT_EQ(mj["compared_modes"][0]["csv"], "cone_n3/branch.csv");
  EXPECT_EQ(mj["compared_modes"][0]["lowest_energy_above_two_fold"].get<double>(), 0.12);
  EXPECT_TRUE(mj["compared_modes"][0]["phi_first_contact"].is_null());
  EXPECT_TRUE(j["wound_csv"].is_null());
  EconeContactResults wound = sample_results();
  EconeWindUp w;
  w.start_branch = "turned";
  w.start_phi = 7.29;
  w.target = 12.5;
  w.highest_phi = 8.91;
  w.steps = 33;
  w.failed_steps = 2;
  w.jumps = {8.91};
  w.shapes.push_back({8.5, "wound/shape_phi8.5.vtu", "wound/shape_phi8.5_contact.vtu"});
  w.end = "step below min_step";
  wound.wound = w;
  const auto wj = nlohmann::json::parse(econe_contact_results_json(wound));
  EXPECT_FALSE(wj["wound"]["reached"].get<bool>());
  EXPECT_EQ(wj["wound"]["start_branch"], "turned");
  EXPECT_EQ(wj["wound"]["highest_phi"].get<double>(), 8.91);
  EXPECT_EQ(wj["wound"]["jumps"][0].get<double>(), 8.91);
  EXPECT_EQ(wj["wound"]["shapes"][0]["contact"], "wound/shape_phi8.5_contact.vtu");
  EXPECT_EQ(wj["wound"]["steps"].get<int>(), 33);
  EXPECT_EQ(wj["wound_csv"], "wound/branch.csv");
  EXPECT_EQ(wj["events"].back(), "wound/events.json");
  // study.hard_contact_at: each check with its branch, the angle asked for, its file and the
  // comparison's fields.
  EXPECT_TRUE(j["hard_contact"].is_array() && j["hard_contact"].empty());
  EconeContactResults hard = sample_results();
  EconeHardContactPoint point;
  point.branch = "turned";
  point.at = 7.0;
  point.file = "turned/hard_contact_phi7.json";
  point.check.phi_e = 7.0089;
  point.check.converged = true;
  point.check.hard_gamma = 1.557;
  point.check.penalty_gamma = std::numeric_limits<double>::quiet_NaN();
  hard.hard_contact.push_back(point);
  const auto h = nlohmann::ordered_json::parse(econe_contact_results_json(hard));
  ASSERT_EQ(h["hard_contact"].size(), 1u);
  EXPECT_EQ(h["hard_contact"][0]["branch"], "turned");
  EXPECT_EQ(h["hard_contact"][0]["at"].get<double>(), 7.0);
  EXPECT_EQ(h["hard_contact"][0]["file"], "turned/hard_contact_phi7.json");
  EXPECT_EQ(h["hard_contact"][0]["phi_e"].get<double>(), 7.0089);
  EXPECT_EQ(h["hard_contact"][0]["hard_gamma"].get<double>(), 1.557);
  EXPECT_TRUE(h["hard_contact"][0]["penalty_gamma"].is_null());
  EXPECT_TRUE(h["hard_contact"][0]["converged"].get<bool>());
  EXPECT_TRUE(j["warnings"].is_array() && j["warnings"].empty());
  // f = E_s / E_b at each branch's highest sample, by branch, a NaN (no bending) as null.
  EXPECT_TRUE(j["energy_ratio_f"].is_array() && j["energy_ratio_f"].empty());
  EconeContactResults ratios = sample_results();
  ratios.energy_ratio_f = {{"skewed", 7.3, 0.0125},
                           {"wound", 12.5, std::numeric_limits<double>::quiet_NaN()}};
  const auto f = nlohmann::json::parse(econe_contact_results_json(ratios));
  ASSERT_EQ(f["energy_ratio_f"].size(), 2u);
  EXPECT_EQ(f["energy_ratio_f"][0]["branch"], "skewed");
  EXPECT_EQ(f["energy_ratio_f"][0]["phi_e"].get<double>(), 7.3);
  EXPECT_EQ(f["energy_ratio_f"][0]["f"].get<double>(), 0.0125);
  EXPECT_EQ(f["energy_ratio_f"][1]["branch"], "wound");
  EXPECT_TRUE(f["energy_ratio_f"][1]["f"].is_null());
  // The orientation check: per turn, a failed relaxation has its message and no state.
  EconeContactResults oriented = sample_results();
  EconeOrientationCheck check;
  check.phi_e = 6.55;
  check.core_radius = 0.04;
  EconeOrientationCheck::Turned settled;
  settled.turn_deg = 22.5;
  settled.converged = true;
  settled.fold_angle_deg = 22.54;
  settled.energy_relative = -0.0087;
  settled.s4_defect = 0.0054;
  settled.turn_free_index = 0;
  settled.state = "orientation/turn_22.500.state";
  EconeOrientationCheck::Turned failed;
  failed.turn_deg = -10.0;
  failed.message = "relaxation failed: LineSearchFailed";
  check.turned = {settled, failed};
  oriented.orientation_check = check;
  oriented.warnings = {"orientation: a turned state is lower"};
  const auto o = nlohmann::json::parse(econe_contact_results_json(oriented));
  ASSERT_EQ(o["orientation_check"]["turned"].size(), 2u);
  EXPECT_EQ(o["orientation_check"]["phi_e"].get<double>(), 6.55);
  EXPECT_EQ(o["orientation_check"]["turned"][0]["energy_relative"].get<double>(), -0.0087);
  EXPECT_EQ(o["orientation_check"]["turned"][0]["state"], "orientation/turn_22.500.state");
  EXPECT_FALSE(o["orientation_check"]["turned"][1]["converged"].get<bool>());
  EXPECT_TRUE(o["orientation_check"]["turned"][1]["state"].is_null());
  EXPECT_EQ(o["warnings"][0], "orientation: a turned state is lower");
  // Without the turned branch: null, with no CSV and three events files.
  EXPECT_TRUE(o["turned"].is_null());
  EXPECT_TRUE(o["turned_csv"].is_null());
  EXPECT_EQ(o["events"].size(), 3u);
  // With it: its keys, its CSV and its events.
  EconeTurnedBranch turned;
  turned.start_phi = 6.55;
  turned.turn_deg = 22.5;
  turned.lowest_phi = 4.07;
  turned.highest_phi = 7.3;
  turned.lowest_phi_breaking_s4 = 5.25;
  turned.top_energy_relative = -0.0066;
  turned.largest_energy_below_symmetric = 0.0091;
  turned.largest_energy_below_symmetric_phi = 6.6;
  turned.end = "downwards: reached the parameter bound; upwards: reached the parameter bound";
  oriented.turned = turned;
  const auto t = nlohmann::ordered_json::parse(econe_contact_results_json(oriented));
  std::vector<std::string> turned_keys;
  for (auto it = t["turned"].begin(); it != t["turned"].end(); ++it)
    turned_keys.push_back(it.key());
  const std::vector<std::string> expected_turned = {"start_phi",
                                                    "turn_deg",
                                                    "lowest_phi",
                                                    "highest_phi",
                                                    "lowest_phi_breaking_s4",
                                                    "top_energy_relative",
                                                    "top_s4_defect",
                                                    "top_gamma",
                                                    "largest_energy_below_symmetric",
                                                    "largest_energy_below_symmetric_phi",
                                                    "phi_crit_stability",
                                                    "end"};
  EXPECT_EQ(turned_keys, expected_turned);
  EXPECT_EQ(t["turned"]["lowest_phi_breaking_s4"].get<double>(), 5.25);
  EXPECT_EQ(t["turned"]["largest_energy_below_symmetric"].get<double>(), 0.0091);
  EXPECT_TRUE(t["turned"]["phi_crit_stability"].is_null());
  EXPECT_EQ(t["turned_csv"], "turned/branch.csv");
  ASSERT_EQ(t["events"].size(), 4u);
  EXPECT_EQ(t["events"][3], "turned/events.json");
  // Without phi_e^crit by energy, its criterion is null too.
  EconeContactResults none = sample_results();
  none.phi_crit_energy.reset();
  const auto n = nlohmann::json::parse(econe_contact_results_json(none));
  EXPECT_TRUE(n["phi_crit_energy"].is_null());
  EXPECT_TRUE(n["phi_crit_energy_criterion"].is_null());
}

TEST(EconeContactConeScene, IsTheContactFreeConeBranchStudyInTheConeFolder) {
  Scene scene = default_scene();
  scene.study.kind = StudyKind::EconeContact;
  scene.study.through_contact = true;
  scene.output.directory = "out/econe";
  const Scene cone = econe_contact_cone_scene(scene);
  EXPECT_EQ(cone.study.kind, StudyKind::ConeBranch);
  EXPECT_FALSE(cone.study.through_contact);  // stage 1 stops at first contact
  EXPECT_EQ(std::filesystem::path(cone.output.directory), std::filesystem::path("out/econe/cone"));
  EXPECT_EQ(thickness_at_radius(cone.thickness, 0.0, 1.0),
            thickness_at_radius(scene.thickness, 0.0, 1.0));
  // The contact era's keys are not the contact-free cone's: a scene that winds up gives a cone
  // scene without the winding, which validates.
  scene.study.wind_to = 12.5;
  scene.study.wind_shapes_at = {8.0};
  scene.study.hard_contact_at = {7.0};
  scene.study.hard_contact_branches = {"skewed"};
  scene.study.compare_modes = {3};
  const Scene cone_of_winding = econe_contact_cone_scene(scene);
  EXPECT_TRUE(cone_of_winding.study.compare_modes.empty());
  EXPECT_FALSE(cone_of_winding.study.wind_to.has_value());
  EXPECT_TRUE(cone_of_winding.study.wind_shapes_at.empty());
  EXPECT_TRUE(cone_of_winding.study.hard_contact_at.empty());
  EXPECT_EQ(cone_of_winding.study.hard_contact_branches,
            default_scene().study.hard_contact_branches);
  EXPECT_NO_THROW(validate_scene(cone_of_winding));
}

TEST_F(EconeContact, RefusesBadInputBeforeWritingAnything) {
  Scene scene = default_scene();
  scene.study.kind = StudyKind::EconeContact;
  scene.output.directory = path("run");
  Scene three = scene;
  three.continuation.mode = 3;
  EXPECT_NE(error_of([&] {
              run_econe_contact_study(three, ExistingOutput::Refuse);
            }).find("continuation.mode = 3"),
            std::string::npos);
  Scene cone = scene;
  cone.study.kind = StudyKind::ConeBranch;
  EXPECT_NE(error_of([&] {
              run_econe_contact_study(cone, ExistingOutput::Refuse);
            }).find("not econe_contact"),
            std::string::npos);
  Scene step = scene;
  step.study.contact_max_step = 0.0;
  EXPECT_NE(error_of([&] {
              run_econe_contact_study(step, ExistingOutput::Refuse);
            }).find("study.contact_max_step"),
            std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(path("run")));

  // A used directory is refused under Refuse, and one without the cone's record under Resume.
  std::filesystem::create_directories(path("run"));
  write(path("run/notes.txt"), "mine");
  EXPECT_NE(error_of([&] { run_econe_contact_study(scene, ExistingOutput::Refuse); }), "");
  EXPECT_NE(error_of([&] { run_econe_contact_study(scene, ExistingOutput::Resume); }), "");
  EXPECT_EQ(listing("run"), std::vector<std::string>{"notes.txt"});
}

TEST_F(EconeContact, ResumeRefusesASceneThatDoesNotFitTheRecordedCone) {
  // A recorded cone at h = 0.04; resuming with h = 0.03 would continue it with another sheet.
  Scene recorded = default_scene();
  recorded.study.kind = StudyKind::EconeContact;
  recorded.thickness = ConstantThickness{0.04};
  recorded.output.directory = path("run");
  std::filesystem::create_directories(path("run/cone"));
  write(path("run/cone/scene.json"), scene_to_json(econe_contact_cone_scene(recorded)));
  write(path("run/cone/record.json"), "{}");
  Scene thinner = recorded;
  thinner.thickness = ConstantThickness{0.03};
  const std::string message =
      error_of([&] { run_econe_contact_study(thinner, ExistingOutput::Resume); });
  EXPECT_NE(message.find("thickness"), std::string::npos) << message;
  // Nothing was written: no scene.json, no branch records beside the cone.
  EXPECT_EQ(listing("run"), std::vector<std::string>{"cone"});
  EXPECT_EQ(listing("run/cone"), (std::vector<std::string>{"record.json", "scene.json"}));
}

TEST_F(EconeContact, ResumeRefusesAMalformedStageRecordBeforeWritingAnything) {
  // The cone's record is fine; the record of stages 2-6 was damaged by hand.
  Scene scene = default_scene();
  scene.study.kind = StudyKind::EconeContact;
  scene.output.directory = path("run");
  std::filesystem::create_directories(path("run/cone"));
  write(path("run/cone/scene.json"), scene_to_json(econe_contact_cone_scene(scene)));
  write(path("run/cone/record.json"), "{}");
  write(path("run/stages.json"), "{\"format\": 1, \"key\": ");
  const std::string message = error_of<std::runtime_error>(
      [&] { run_econe_contact_study(scene, ExistingOutput::Resume); });
  EXPECT_NE(message.find(path("run/stages.json")), std::string::npos) << message;
  EXPECT_NE(message.find("not JSON"), std::string::npos) << message;
  // Refused before the study's scene.json or any stage was written.
  EXPECT_EQ(listing("run"), (std::vector<std::string>{"cone", "stages.json"}));
  EXPECT_EQ(listing("run/cone"), (std::vector<std::string>{"record.json", "scene.json"}));
}

}  // namespace
}  // namespace growshell
