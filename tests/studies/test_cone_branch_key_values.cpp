#include "studies/cone_branch_key_values.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "tests/studies/scratch_directory.hpp"
#include "tests/support/branch_columns.hpp"

namespace growshell {
namespace {

using ConeBranchKeyValues = testing::ScratchDirectoryTest;
using test_support::kBranchColumns;

const double kNan = std::numeric_limits<double>::quiet_NaN();

TEST_F(ConeBranchKeyValues, FromTheRecordedEventsAndRows) {
  BranchRecord r(dir_.string(), kBranchColumns, BranchRecord::Start::Fresh);
  r.add_event("{}", {"branch_point", 0.017, "flat", {}});
  r.add_event("{}", {"branch_point", 0.018, "flat", {}});
  // Rows: the switch onto the cone (left out below 0.1), then a stable stretch, contact at
  // 5.9, an unstable sample after it.
  r.append_row({0.02, 2, kNan});
  r.append_row({0.05, 1, 0.5});  // below 0.1: neither stability loss nor defect
  r.add_event("{}", {"branch_point", 1.3, "cone", {}});  // the cone's: not phi_branch
  r.append_row({1.0, 0, 2e-7});
  r.add_event("{}", {"eb_max", 4.0, "cone", {{"eb_hat", 4.26}}});
  r.add_event("{}", {"eb_max", 4.5, "cone", {{"eb_hat", 4.1}}});  // a minimum
  r.append_row({5.0, 0, 3e-7});
  r.add_event("{}", {"contact", 5.9, "cone", {}});
  r.append_row({6.0, 0, 9e-7});  // past contact: not in the defect
  r.add_event("{}", {"symmetry_lost", 6.1, "cone", {}});
  r.append_row({6.2, 1, kNan});
  r.append_row({6.3, 2, 1e-6});
  ConeBranchResults results;
  results.thickness = 0.04;
  set_cone_branch_key_values(r, results);
  EXPECT_EQ(results.phi_branch, 0.017);
  EXPECT_EQ(results.phi_max, 4.0);
  EXPECT_EQ(results.eb_hat_max, 4.26);
  EXPECT_EQ(results.phi_gap_h, 5.9);
  EXPECT_FALSE(results.phi_kiss.has_value());
  EXPECT_EQ(results.phi_symmetry_lost, 6.1);
  EXPECT_EQ(results.phi_crit_stability, 6.2);
  EXPECT_EQ(results.max_s4_defect_before_contact, 3e-7);
  EXPECT_EQ(results.phi_last, 6.3);
  EXPECT_EQ(results.phi_highest, 6.3);
  EXPECT_EQ(results.thickness, 0.04);  // not the record's

  // The three-fold cone leaves the flat branch at its own branch point, after the two-fold
  // one's: phi_branch is the cone_entry event's.
  BranchRecord three((dir_ / "three").string(), kBranchColumns, BranchRecord::Start::Fresh);
  three.add_event("{}", {"branch_point", 0.017, "flat", {}});
  three.add_event("{}", {"branch_point", 0.034, "flat", {}});
  three.add_event("{}", {"cone_entry", 0.034, "flat", {{"mode", 3.0}}});
  three.add_event("{}", {"branch_point", 0.05, "cone", {}});
  ConeBranchResults three_results;
  set_cone_branch_key_values(three, three_results);
  EXPECT_EQ(three_results.phi_branch, 0.034);
}

TEST_F(ConeBranchKeyValues, NullWhereTheRecordHasNothing) {
  BranchRecord r(dir_.string(), kBranchColumns, BranchRecord::Start::Fresh);
  ConeBranchResults results;
  results.phi_kiss = 7.0;  // reset: the record has no such event
  set_cone_branch_key_values(r, results);
  EXPECT_FALSE(results.phi_branch || results.phi_max || results.eb_hat_max || results.phi_gap_h ||
               results.phi_kiss || results.phi_crit_stability ||
               results.max_s4_defect_before_contact || results.phi_symmetry_lost ||
               results.phi_last || results.phi_highest);
  // Without a contact event every sample from 0.1 on counts for the defect; a cone other than
  // the two-fold one has none.
  r.append_row({0.2, 0, 4e-7});
  r.append_row({7.0, 0, 5e-7});
  set_cone_branch_key_values(r, results);
  EXPECT_EQ(results.max_s4_defect_before_contact, 5e-7);
  EXPECT_FALSE(results.phi_crit_stability.has_value());
  BranchRecord three(path("three"), kBranchColumns, BranchRecord::Start::Fresh);
  three.append_row({0.5, 0, kNan});
  set_cone_branch_key_values(three, results);
  EXPECT_FALSE(results.max_s4_defect_before_contact.has_value());
  EXPECT_EQ(results.phi_last, 0.5);
  // A branch that turns back at a fold: its last sample lies below the fold.
  three.append_row({9.72, 3, kNan});
  three.append_row({9.0, 4, kNan});
  set_cone_branch_key_values(three, results);
  EXPECT_EQ(results.phi_last, 9.0);
  EXPECT_EQ(results.phi_highest, 9.72);
}

}  // namespace
}  // namespace growshell
