#include "studies/study_results.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "studies/atomic_file.hpp"
#include "tests/studies/scratch_directory.hpp"

namespace growshell {
namespace {

using StudyResults = testing::ScratchDirectoryTest;

ConeBranchResults full_results() {
  ConeBranchResults r;
  r.thickness = 0.04;
  r.mode = 2;
  r.mesh = {"rings", 0.25, 752, 1275};
  r.phi_branch = 0.017151279982356354;
  r.phi_max = 4.014;
  r.eb_hat_max = 4.2623;
  r.phi_gap_h = 5.8671;
  r.phi_kiss = 7.0819;
  r.phi_crit_stability = 6.2;
  r.max_s4_defect_before_contact = 1.5e-7;
  r.phi_symmetry_lost = 3.9;
  r.phi_last = 7.675;
  r.completed = true;
  r.end = "reached the parameter bound";
  r.wall_seconds = 230.5;
  return r;
}

TEST(StudyResultsJson, HasEveryKeyInOrderWithItsValue) {
  const std::string text = cone_branch_results_json(full_results());
  ASSERT_EQ(text.back(), '\n');
  const nlohmann::ordered_json j = nlohmann::ordered_json::parse(text);
  std::vector<std::string> keys;
  for (const auto& item : j.items()) keys.push_back(item.key());
  const std::vector<std::string> expected = {"study",
                                             "thickness",
                                             "mode",
                                             "mesh",
                                             "phi_branch",
                                             "phi_max",
                                             "eb_hat_max",
                                             "phi_gap_h",
                                             "phi_kiss",
                                             "phi_kiss_criterion",
                                             "phi_crit_stability",
                                             "max_s4_defect_before_contact",
                                             "phi_symmetry_lost",
                                             "phi_last",
                                             "phi_highest",
                                             "orientation_phi",
                                             "orientation_turn_deg",
                                             "orientation_fold_angle_deg",
                                             "orientation_energy_relative",
                                             "orientation_s4_defect",
                                             "orientation_chord_up",
                                             "orientation_chord_down",
                                             "orientation_energy_change_core",
                                             "orientation_energy_change_outside",
                                             "completed",
                                             "end",
                                             "branch_csv",
                                             "events",
                                             "wall_seconds"};
  EXPECT_EQ(keys, expected);
  EXPECT_EQ(j["study"], "cone_branch");
  EXPECT_EQ(j["mode"], 2);
  EXPECT_EQ(j["mesh"]["family"], "rings");
  EXPECT_EQ(j["mesh"]["size_slope"], 0.25);
  EXPECT_EQ(j["mesh"]["elements"], 752);
  EXPECT_EQ(j["mesh"]["unknowns"], 1275);
  EXPECT_EQ(j["phi_kiss_criterion"], "midsurface_contact");
  EXPECT_EQ(j["branch_csv"], "branch.csv");
  EXPECT_EQ(j["events"], "events.json");
  EXPECT_EQ(j["phi_kiss"], 7.0819);
  EXPECT_EQ(j["completed"], true);
  // Shortest round-trip form: the double comes back exactly, and is not padded to 17 digits.
  EXPECT_EQ(j["phi_branch"].get<double>(), 0.017151279982356354);
  EXPECT_NE(text.find("\"phi_kiss\": 7.0819,"), std::string::npos) << text;
  EXPECT_TRUE(j["orientation_energy_relative"].is_null());  // no check
  ConeBranchResults checked = full_results();
  checked.orientation =
      ConeBranchResults::Orientation{6.0, 22.5, 22.54, -0.009, 0.0058, 0.3667, 0.3664, -0.012, 0.005};
  const nlohmann::json k = nlohmann::json::parse(cone_branch_results_json(checked));
  EXPECT_EQ(k["orientation_phi"], 6.0);
  EXPECT_EQ(k["orientation_fold_angle_deg"], 22.54);
  EXPECT_EQ(k["orientation_energy_relative"], -0.009);
  EXPECT_EQ(k["orientation_chord_down"], 0.3664);
  EXPECT_EQ(k["orientation_energy_change_outside"], 0.005);
}

TEST(StudyResultsJson, ValuesThatDoNotApplyAreNull) {
  ConeBranchResults r = full_results();
  r.phi_kiss.reset();
  r.phi_gap_h.reset();
  r.phi_symmetry_lost.reset();
  r.phi_crit_stability.reset();
  r.mesh.size_slope.reset();
  r.eb_hat_max = std::numeric_limits<double>::quiet_NaN();  // non-finite: null, not "nan"
  const std::string text = cone_branch_results_json(r);
  const nlohmann::json j = nlohmann::json::parse(text);
  for (const char* key :
       {"phi_kiss", "phi_gap_h", "phi_symmetry_lost", "phi_crit_stability", "eb_hat_max"}) {
    ASSERT_TRUE(j.contains(key)) << key;
    EXPECT_TRUE(j[key].is_null()) << key;
  }
  EXPECT_TRUE(j["mesh"]["size_slope"].is_null());
  EXPECT_EQ(j["phi_max"], 4.014);  // the others stay
  EXPECT_EQ(text.find("nan"), std::string::npos);
  // A default (nothing traced) result: every key present, the optional ones null.
  const nlohmann::json empty = nlohmann::json::parse(cone_branch_results_json(ConeBranchResults{}));
  EXPECT_EQ(empty.size(), j.size());
  EXPECT_TRUE(empty["phi_branch"].is_null());
  EXPECT_TRUE(empty["phi_last"].is_null());
  EXPECT_EQ(empty["completed"], false);
}

TEST_F(StudyResults, WriteIsAtomicAndLeavesNoTemporary) {
  write(path("results.json"), "old");
  write_cone_branch_results(dir_.string(), full_results());
  EXPECT_EQ(listing(), std::vector<std::string>{"results.json"});
  EXPECT_EQ(read(path("results.json")), cone_branch_results_json(full_results()));
  // The temporary it goes through lies in the same directory, under a hidden name.
  EXPECT_EQ(temporary_path_for(path("results.json")), path(".results.json.tmp"));
  EXPECT_TRUE(is_temporary_file_name(".results.json.tmp"));
  EXPECT_FALSE(is_temporary_file_name("results.json"));
}

TEST_F(StudyResults, FailedWriteNamesTheFileAndLeavesNothing) {
  const std::string missing = path("no_such_directory");
  try {
    write_cone_branch_results(missing, full_results());
    FAIL() << "writing into a missing directory did not throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing + "/results.json"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(listing().empty());
  // A writer that throws halfway leaves neither the temporary nor a changed target.
  write(path("results.json"), "old");
  EXPECT_THROW(write_atomically_with(path("results.json"),
                                     [](const std::string& temporary) {
                                       write(temporary, "half");
                                       throw std::runtime_error("disk full");
                                     }),
               std::runtime_error);
  EXPECT_EQ(listing(), std::vector<std::string>{"results.json"});
  EXPECT_EQ(read(path("results.json")), "old");
}

TEST_F(StudyResults, AppendWritesWholeLines) {
  append_to_file(path("rows.csv"), "a,b\n");
  append_to_file(path("rows.csv"), "1,2\n");
  EXPECT_EQ(read(path("rows.csv")), "a,b\n1,2\n");
  EXPECT_THROW(append_to_file(path("missing/rows.csv"), "x\n"), std::runtime_error);
}

}  // namespace
}  // namespace growshell
