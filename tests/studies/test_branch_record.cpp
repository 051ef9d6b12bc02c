#include "studies/branch_record.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "studies/atomic_file.hpp"
#include "studies/saved_state.hpp"
#include "tests/studies/scratch_directory.hpp"

namespace growshell {
namespace {

namespace fs = std::filesystem;
using BranchRecordTest = testing::ScratchDirectoryTest;

const std::vector<std::string> kColumns = {"phi_e", "n_negative", "s4_defect"};

BranchSample sample(double phi) {
  BranchSample s;
  s.parameter = phi;
  s.tangent_parameter = 1.0;
  s.x = Eigen::VectorXd::Constant(6, phi);
  s.tangent_state = Eigen::VectorXd::Constant(6, -phi);
  return s;
}

/// One sample as a study records it: row, state, commit.
void record_sample(BranchRecord& r, double phi) {
  r.append_row({phi, 0.0, 1e-7 * phi});
  r.save_state(sample(phi));
  r.commit();
}

TEST_F(BranchRecordTest, FreshRecordWritesHeaderRowsStatesAndEvents) {
  BranchRecord r(dir_.string(), kColumns, BranchRecord::Start::Fresh);
  EXPECT_EQ(read(path("branch.csv")), "phi_e,n_negative,s4_defect\n");
  EXPECT_EQ(read(path("events.json")), "[\n]\n");
  r.add_event("{\"kind\": \"branch_point\", \"phi_e\": 0.5}", {"branch_point", 0.5, "flat", {}});
  record_sample(r, 0.5);
  r.add_event("{\"kind\": \"eb_max\", \"phi_e\": 0.75}",
              {"eb_max", 0.75, "cone", {{"eb_hat", 2.5}}});
  record_sample(r, 1.0 / 3.0);
  // Rows at 12 significant digits, NaN as the stream prints it; the record keeps the values
  // as they read back.
  r.append_row({2.0, 1.0, std::numeric_limits<double>::quiet_NaN()});
  EXPECT_EQ(
      read(path("branch.csv")),
      "phi_e,n_negative,s4_defect\n0.5,0,5e-08\n0.333333333333,0,3.33333333333e-08\n2,1,nan\n");
  EXPECT_EQ(r.rows(), 3u);
  EXPECT_EQ(r.value(1, "phi_e"), 0.333333333333);
  EXPECT_TRUE(std::isnan(r.value(2, "s4_defect")));
  EXPECT_THROW(r.value(0, "folds"), std::out_of_range);
  EXPECT_THROW(r.value(3, "phi_e"), std::out_of_range);
  EXPECT_THROW(r.append_row({1.0}), std::invalid_argument);
  EXPECT_EQ(read(path("events.json")),
            "[\n  {\"kind\": \"branch_point\", \"phi_e\": 0.5},\n  {\"kind\": \"eb_max\", "
            "\"phi_e\": 0.75}\n]\n");
  EXPECT_EQ(r.events()[1].value("eb_hat"), 2.5);
  EXPECT_FALSE(r.events()[1].value("eb").has_value());
  EXPECT_EQ(listing("states"), (std::vector<std::string>{"point_00000.txt", "point_00001.txt"}));
  EXPECT_EQ(r.last_state(), "states/point_00001.txt");
  EXPECT_EQ(load_branch_state(path("states/point_00001.txt"), 6).parameter, 1.0 / 3.0);
  EXPECT_EQ(BranchRecord::committed_last_state(dir_.string()), "states/point_00001.txt");
  for (const std::string& name : listing()) EXPECT_FALSE(is_temporary_file_name(name)) << name;
}

TEST_F(BranchRecordTest, ContinueCutsTheRecordBackToItsLastCommit) {
  {
    BranchRecord r(dir_.string(), kColumns, BranchRecord::Start::Fresh);
    r.add_event("{\"kind\": \"branch_point\", \"phi_e\": 0.5}", {"branch_point", 0.5, "flat", {}});
    record_sample(r, 0.5);
    record_sample(r, 0.6);
    // A run killed after a row, an event and a state, before their commit, and while writing
    // a temporary.
    r.append_row({0.7, 0.0, 0.0});
    r.add_event("{\"kind\": \"contact\", \"phi_e\": 0.65}", {"contact", 0.65, "cone", {}});
    r.save_state(sample(0.7));
  }
  write(path("states/.point_00003.txt.tmp"), "partial");
  write(path(".branch.pvd.tmp"), "partial");
  BranchRecord r(dir_.string(), kColumns, BranchRecord::Start::Continue);
  EXPECT_EQ(r.rows(), 2u);
  EXPECT_EQ(read(path("branch.csv")), "phi_e,n_negative,s4_defect\n0.5,0,5e-08\n0.6,0,6e-08\n");
  ASSERT_EQ(r.events().size(), 1u);
  EXPECT_EQ(r.events()[0].branch, "flat");
  EXPECT_EQ(read(path("events.json")), "[\n  {\"kind\": \"branch_point\", \"phi_e\": 0.5}\n]\n");
  EXPECT_EQ(listing("states"), (std::vector<std::string>{"point_00000.txt", "point_00001.txt"}));
  EXPECT_EQ(r.last_state(), "states/point_00001.txt");
  EXPECT_EQ(r.next_state_index(), 2);
  for (const std::string& name : listing()) EXPECT_FALSE(is_temporary_file_name(name)) << name;
  // The record goes on from there.
  record_sample(r, 0.8);
  EXPECT_EQ(read(path("branch.csv")),
            "phi_e,n_negative,s4_defect\n0.5,0,5e-08\n0.6,0,6e-08\n0.8,0,8e-08\n");
  EXPECT_EQ(r.last_state(), "states/point_00002.txt");
}

TEST_F(BranchRecordTest, FreshRecordReplacesAnEarlierOne) {
  {
    BranchRecord r(dir_.string(), kColumns, BranchRecord::Start::Fresh);
    record_sample(r, 0.5);
    SurfaceSnapshot s;
    s.points = Eigen::MatrixX3d::Zero(3, 3);
    s.triangles = Eigen::MatrixX3i(1, 3);
    s.triangles << 0, 1, 2;
    r.add_snapshot(0.5, "point_00000.vtu", s);
    r.write_surface("special_0_mode_0.vtu", s);
    r.commit();
  }
  write(path("notes.txt"), "mine");
  EXPECT_TRUE(fs::exists(path("branch.pvd")));
  BranchRecord r(dir_.string(), kColumns, BranchRecord::Start::Fresh);
  EXPECT_EQ(r.rows(), 0u);
  EXPECT_TRUE(listing("states").empty());
  // The earlier record's files are gone; files it did not write stay.
  EXPECT_EQ(listing(), (std::vector<std::string>{"branch.csv", "events.json", "notes.txt",
                                                 "record.json", "states"}));
}

TEST_F(BranchRecordTest, ContinueAdoptsADirectoryWithoutRecordJson) {
  // As trace_disc wrote it before record.json existed.
  fs::create_directories(path("states"));
  write(path("branch.csv"), "phi_e,n_negative,s4_defect\n0.1,0,nan\n0.2,0,1e-07\n");
  write(path("events.json"),
        "[\n  {\"kind\": \"branch_point\", \"phi_e\": 0.05, \"multiplicity\": 2},\n"
        "  {\"kind\": \"symmetry_lost\", \"phi_e\": 0.2, \"chord_up\": nan}\n]\n");
  save_branch_state(path("states/point_00000.txt"), sample(0.1));
  save_branch_state(path("states/point_00001.txt"), sample(0.2));
  BranchRecord r(dir_.string(), kColumns, BranchRecord::Start::Continue);
  EXPECT_EQ(r.rows(), 2u);
  ASSERT_EQ(r.events().size(), 2u);
  EXPECT_EQ(r.events()[1].kind, "symmetry_lost");
  EXPECT_EQ(r.events()[1].phi_e, 0.2);
  EXPECT_EQ(r.events()[1].branch, "");
  EXPECT_EQ(r.next_state_index(), 2);
  EXPECT_TRUE(BranchRecord::exists(dir_.string()));
  // Without any record a continued one starts fresh.
  fs::remove_all(path("other"));
  BranchRecord fresh(path("other"), kColumns, BranchRecord::Start::Continue);
  EXPECT_EQ(read(path("other/branch.csv")), "phi_e,n_negative,s4_defect\n");
}

TEST_F(BranchRecordTest, ContinueRefusesARecordThatDoesNotFit) {
  {
    BranchRecord r(dir_.string(), kColumns, BranchRecord::Start::Fresh);
    record_sample(r, 0.5);
  }
  EXPECT_THROW(BranchRecord(dir_.string(), {"phi_e", "other"}, BranchRecord::Start::Continue),
               std::runtime_error);
  write(path("branch.csv"), "phi_e,n_negative,s4_defect\n");  // fewer rows than committed
  try {
    BranchRecord r(dir_.string(), kColumns, BranchRecord::Start::Continue);
    FAIL() << "a record that lost a committed row was continued";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("branch.csv has 0 rows"), std::string::npos) << e.what();
  }
}

TEST(SavedState, NamesAndTheirIndices) {
  EXPECT_EQ(saved_state_name(12), "point_00012.txt");
  EXPECT_EQ(saved_state_index("point_00012.txt"), 12);
  EXPECT_EQ(saved_state_index(".point_00012.txt.tmp"), -1);
  EXPECT_EQ(saved_state_index("point_0001x.txt"), -1);
  EXPECT_EQ(saved_state_index("eigenvalues.csv"), -1);
}

}  // namespace
}  // namespace growshell
