#include "studies/branch_record.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "core/content_hash.hpp"
#include "studies/atomic_file.hpp"
#include "studies/saved_state.hpp"
#include "tests/studies/scratch_directory.hpp"
#include "tests/support/branch_columns.hpp"

namespace growshell {
namespace {

namespace fs = std::filesystem;
using BranchRecordTest = testing::ScratchDirectoryTest;
using test_support::kBranchColumns;

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
  BranchRecord r(dir_.string(), kBranchColumns, BranchRecord::Start::Fresh);
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
  EXPECT_EQ(listing("states"), (std::vector<std::string>{"point_00000.state", "point_00001.state"}));
  EXPECT_EQ(r.last_state(), "states/point_00001.state");
  EXPECT_EQ(load_branch_state(path("states/point_00001.state"), 6).parameter, 1.0 / 3.0);
  EXPECT_EQ(BranchRecord::committed_last_state(dir_.string()), "states/point_00001.state");
  for (const std::string& name : listing()) EXPECT_FALSE(is_temporary_file_name(name)) << name;
}

TEST_F(BranchRecordTest, ContinueCutsTheRecordBackToItsLastCommit) {
  {
    BranchRecord r(dir_.string(), kBranchColumns, BranchRecord::Start::Fresh);
    r.add_event("{\"kind\": \"branch_point\", \"phi_e\": 0.5}", {"branch_point", 0.5, "flat", {}});
    record_sample(r, 0.5);
    record_sample(r, 0.6);
    // A run killed after a row, an event and a state, before their commit, and while writing
    // a temporary.
    r.append_row({0.7, 0.0, 0.0});
    r.add_event("{\"kind\": \"contact\", \"phi_e\": 0.65}", {"contact", 0.65, "cone", {}});
    r.save_state(sample(0.7));
  }
  write(path("states/.point_00003.state.tmp"), "partial");
  write(path(".branch.pvd.tmp"), "partial");
  BranchRecord r(dir_.string(), kBranchColumns, BranchRecord::Start::Continue);
  EXPECT_EQ(r.rows(), 2u);
  EXPECT_EQ(read(path("branch.csv")), "phi_e,n_negative,s4_defect\n0.5,0,5e-08\n0.6,0,6e-08\n");
  ASSERT_EQ(r.events().size(), 1u);
  EXPECT_EQ(r.events()[0].branch, "flat");
  EXPECT_EQ(read(path("events.json")), "[\n  {\"kind\": \"branch_point\", \"phi_e\": 0.5}\n]\n");
  EXPECT_EQ(listing("states"), (std::vector<std::string>{"point_00000.state", "point_00001.state"}));
  EXPECT_EQ(r.last_state(), "states/point_00001.state");
  EXPECT_EQ(r.next_state_index(), 2);
  for (const std::string& name : listing()) EXPECT_FALSE(is_temporary_file_name(name)) << name;
  // The record goes on from there.
  record_sample(r, 0.8);
  EXPECT_EQ(read(path("branch.csv")),
            "phi_e,n_negative,s4_defect\n0.5,0,5e-08\n0.6,0,6e-08\n0.8,0,8e-08\n");
  EXPECT_EQ(r.last_state(), "states/point_00002.state");
}

TEST_F(BranchRecordTest, FreshRecordReplacesAnEarlierOne) {
  {
    BranchRecord r(dir_.string(), kBranchColumns, BranchRecord::Start::Fresh);
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
  BranchRecord r(dir_.string(), kBranchColumns, BranchRecord::Start::Fresh);
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
  // Its states in the text format of that version.
  write(path("states/point_00000.txt"), "0.1\n1\n6\n0\n0\n0\n0\n0\n0\n0\n0\n0\n0\n0\n0\n");
  write(path("states/point_00001.txt"), "0.2\n1\n6\n0\n0\n0\n0\n0\n0\n0\n0\n0\n0\n0\n0\n");
  BranchRecord r(dir_.string(), kBranchColumns, BranchRecord::Start::Continue);
  EXPECT_EQ(r.rows(), 2u);
  ASSERT_EQ(r.events().size(), 2u);
  EXPECT_EQ(r.events()[1].kind, "symmetry_lost");
  EXPECT_EQ(r.events()[1].phi_e, 0.2);
  EXPECT_EQ(r.events()[1].branch, "");
  EXPECT_EQ(r.next_state_index(), 2);
  EXPECT_EQ(r.last_state(), "states/point_00001.txt");
  EXPECT_EQ(load_branch_state(path(r.last_state()), 6).parameter, 0.2);
  EXPECT_EQ(r.save_state(sample(0.3)), "states/point_00002.state");
  EXPECT_EQ(saved_state_files(dir_.string()).back().filename(), "point_00002.state");
  EXPECT_TRUE(BranchRecord::exists(dir_.string()));
  // Without any record a continued one starts fresh.
  fs::remove_all(path("other"));
  BranchRecord fresh(path("other"), kBranchColumns, BranchRecord::Start::Continue);
  EXPECT_EQ(read(path("other/branch.csv")), "phi_e,n_negative,s4_defect\n");
}

TEST_F(BranchRecordTest, ContinueRefusesARecordThatDoesNotFit) {
  {
    BranchRecord r(dir_.string(), kBranchColumns, BranchRecord::Start::Fresh);
    record_sample(r, 0.5);
  }
  EXPECT_THROW(BranchRecord(dir_.string(), {"phi_e", "other"}, BranchRecord::Start::Continue),
               std::runtime_error);
  write(path("branch.csv"), "phi_e,n_negative,s4_defect\n");  // fewer rows than committed
  try {
    BranchRecord r(dir_.string(), kBranchColumns, BranchRecord::Start::Continue);
    FAIL() << "a record that lost a committed row was continued";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("branch.csv has 0 rows"), std::string::npos) << e.what();
  }
}

TEST_F(BranchRecordTest, NearestSavedStateIsTheOneWithTheNearestExcessAngle) {
  fs::create_directories(path("states"));
  EXPECT_FALSE(nearest_saved_state(dir_.string(), 1.0, 6).has_value());  // no state in it
  {
    BranchRecord r(dir_.string(), kBranchColumns, BranchRecord::Start::Fresh);
    for (const double phi : {0.5, 0.9, 1.3, 1.1}) record_sample(r, phi);
  }
  EXPECT_EQ(nearest_saved_state(dir_.string(), 1.0, 6)->parameter, 0.9);
  EXPECT_EQ(nearest_saved_state(dir_.string(), 1.2, 6)->parameter, 1.1);
  EXPECT_EQ(nearest_saved_state(dir_.string(), -3.0, 6)->parameter, 0.5);
  EXPECT_EQ(nearest_saved_state(dir_.string(), 9.0, 6)->x, Eigen::VectorXd::Constant(6, 1.3));
  EXPECT_THROW(nearest_saved_state(dir_.string(), 1.0, 5), std::runtime_error);  // another size
}

TEST_F(BranchRecordTest, NearestSavedStatesAreEachOnceInTraceOrder) {
  fs::create_directories(path("states"));
  EXPECT_TRUE(nearest_saved_states(dir_.string(), {1.0}, 6).empty());  // no state in it
  {
    BranchRecord r(dir_.string(), kBranchColumns, BranchRecord::Start::Fresh);
    for (const double phi : {0.5, 0.9, 1.3, 1.1}) record_sample(r, phi);
  }
  // 1.25 and 9 both take 1.3, the third state; 1.2 takes 1.1, the fourth; 0.8 takes 0.9.
  const std::vector<BranchSample> s = nearest_saved_states(dir_.string(), {1.25, 1.2, 9.0, 0.8}, 6);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0].parameter, 0.9);
  EXPECT_EQ(s[1].parameter, 1.3);
  EXPECT_EQ(s[2].parameter, 1.1);
  EXPECT_EQ(s[1].x, Eigen::VectorXd::Constant(6, 1.3));
  EXPECT_TRUE(nearest_saved_states(dir_.string(), {}, 6).empty());
  EXPECT_THROW(nearest_saved_states(dir_.string(), {1.0}, 5), std::runtime_error);
}

TEST(SavedState, NamesAndTheirIndices) {
  EXPECT_EQ(saved_state_name(12), "point_00012.state");
  EXPECT_EQ(saved_state_index("point_00012.state"), 12);
  EXPECT_EQ(saved_state_index("point_00012.txt"), 12);  // an earlier version's name
  EXPECT_EQ(saved_state_index(".point_00012.state.tmp"), -1);
  EXPECT_EQ(saved_state_index("point_0001x.state"), -1);
  EXPECT_EQ(saved_state_index("point_00012.csv"), -1);
  EXPECT_EQ(saved_state_index("eigenvalues.csv"), -1);
}

TEST_F(BranchRecordTest, BinaryStatesRoundTripBitForBitAndNameTheirDamage) {
  BranchSample s;
  s.parameter = 1.0 / 3.0;
  s.tangent_parameter = -std::nextafter(0.7, 1.0);
  s.x = Eigen::VectorXd::LinSpaced(5, -1e-300, 7.0);
  s.x(2) = std::numeric_limits<double>::denorm_min();
  s.tangent_state = Eigen::VectorXd::Constant(5, std::sqrt(2.0));
  s.next_step = 0.0125;
  save_branch_state(path("a.state"), s, 42);
  // header line, n, fingerprint, phi_e, its tangent and the next step, x and dx/ds, the
  // reduced state's size (0), hash
  EXPECT_EQ(fs::file_size(path("a.state")), 18u + 8u + 8u + 24u + 2u * 5u * 8u + 8u + 8u);
  const BranchSample r = load_branch_state(path("a.state"), 5, 42);
  EXPECT_EQ(r.parameter, s.parameter);
  EXPECT_EQ(r.tangent_parameter, s.tangent_parameter);
  EXPECT_EQ(r.next_step, s.next_step);
  EXPECT_EQ(r.x, s.x);  // exact, not to a tolerance
  EXPECT_EQ(r.tangent_state, s.tangent_state);
  EXPECT_EQ(r.reduced_x.size(), 0);
  auto error_loading = [&](const std::string& file, Eigen::Index n) {
    try {
      load_branch_state(path(file), n);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_loading("a.state", 6).find("does not fit this scene (5 unknowns, expected 6)"),
            std::string::npos);
  const std::string bytes = read(path("a.state"));
  write(path("cut.state"), bytes.substr(0, bytes.size() - 9));
  EXPECT_NE(error_loading("cut.state", 5).find("is truncated"), std::string::npos);
  std::string flipped = bytes;
  flipped[40] = static_cast<char>(flipped[40] ^ 1);
  write(path("flipped.state"), flipped);
  EXPECT_NE(error_loading("flipped.state", 5).find("is damaged"), std::string::npos);
  write(path("long.state"), bytes + "x");
  EXPECT_NE(error_loading("long.state", 5).find("bytes after its end"), std::string::npos);
  EXPECT_NE(error_loading("missing.state", 5).find("cannot read"), std::string::npos);
  // The model fingerprint: another model's state is refused; 0 on either side checks nothing.
  EXPECT_THROW(load_branch_state(path("a.state"), 5, 43), std::runtime_error);
  try {
    load_branch_state(path("a.state"), 5, 43);
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("belongs to another model"), std::string::npos);
  }
  EXPECT_NO_THROW(load_branch_state(path("a.state"), 5, 0));
  save_branch_state(path("b.state"), s);
  EXPECT_NO_THROW(load_branch_state(path("b.state"), 5, 43));
  // Version 2 (no reduced state) is still read: its bytes are version 3's without the
  // reduced state's size, under the version-2 header and with its own hash.
  std::string v2 = bytes.substr(0, bytes.size() - 16);
  v2.replace(0, 18, "growshell-state 2\n");
  const std::uint64_t hash2 = fnv1a_64(v2);
  v2.append(reinterpret_cast<const char*>(&hash2), sizeof hash2);
  write(path("v2.state"), v2);
  const BranchSample second = load_branch_state(path("v2.state"), 5, 42);
  EXPECT_EQ(second.next_step, s.next_step);
  EXPECT_EQ(second.x, s.x);
  EXPECT_EQ(second.reduced_x.size(), 0);
  // Version 1 (no next step) is still read, with the next step 0: its bytes are version 2's
  // without the step, under the version-1 header and with its own hash.
  std::string v1 = bytes.substr(0, 18 + 8 + 8 + 16) + bytes.substr(18 + 8 + 8 + 24);
  v1.resize(v1.size() - 16);
  v1.replace(0, 18, "growshell-state 1\n");
  const std::uint64_t hash = fnv1a_64(v1);
  v1.append(reinterpret_cast<const char*>(&hash), sizeof hash);
  write(path("v1.state"), v1);
  const BranchSample old = load_branch_state(path("v1.state"), 5, 42);
  EXPECT_EQ(old.next_step, 0.0);
  EXPECT_EQ(old.parameter, s.parameter);
  EXPECT_EQ(old.x, s.x);
  EXPECT_EQ(old.tangent_state, s.tangent_state);
}

TEST_F(BranchRecordTest, AReducedStateAndItsFrameRoundTripBitForBit) {
  // A sample of a trace in a symmetric subspace keeps the reduced state it was traced in and
  // the frame, so that a resumed trace starts from the same bits (resume_branch_in_subspace).
  BranchSample s;
  s.parameter = 5.25;
  s.x = Eigen::VectorXd::LinSpaced(6, -0.3, 0.9);
  s.tangent_state = Eigen::VectorXd::Constant(6, 1.0 / 3.0);
  s.reduced_x = Eigen::VectorXd::LinSpaced(2, std::nextafter(0.1, 1.0), -2.0 / 7.0);
  s.reduced_frame.rotation = Eigen::AngleAxisd(1e-13, Eigen::Vector3d(1.0, 2.0, 3.0).normalized())
                                 .toRotationMatrix();
  s.reduced_frame.translation = Eigen::Vector3d(1e-17, -0.0, 3e-16);
  save_branch_state(path("r.state"), s, 42);
  EXPECT_EQ(fs::file_size(path("r.state")),
            18u + 8u + 8u + 24u + 2u * 6u * 8u + 8u + 12u * 8u + 2u * 8u + 8u);
  const BranchSample r = load_branch_state(path("r.state"), 6, 42);
  EXPECT_EQ(r.x, s.x);
  EXPECT_EQ(r.reduced_x, s.reduced_x);
  EXPECT_EQ(r.reduced_frame.rotation, s.reduced_frame.rotation);
  EXPECT_EQ(r.reduced_frame.translation, s.reduced_frame.translation);
  EXPECT_TRUE(std::signbit(r.reduced_frame.translation(1)));
  // A reduced state longer than the state is refused on saving, and named as damage on reading.
  BranchSample wrong = s;
  wrong.reduced_x = Eigen::VectorXd::Zero(7);
  EXPECT_THROW(save_branch_state(path("w.state"), wrong), std::invalid_argument);
  std::string bytes = read(path("r.state"));
  const std::size_t m_at = 18 + 8 + 8 + 24 + 2 * 6 * 8;
  const std::int64_t seven = 7;
  bytes.replace(m_at, 8, reinterpret_cast<const char*>(&seven), 8);
  write(path("m.state"), bytes);
  try {
    load_branch_state(path("m.state"), 6);
    ADD_FAILURE() << "a reduced state of 7 entries for 6 unknowns was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("a reduced state of 7 entries for 6 unknowns"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace growshell

namespace growshell {
namespace {

TEST(SpecialPointEvent, FieldsAndSummaryNameThePointAndItsCounts) {
  SpecialPoint sp;
  sp.kind = SpecialPoint::Kind::BranchPoint;
  sp.parameter = 7.0300350123;
  sp.multiplicity = 1;
  sp.negative_before = 0;
  sp.negative_after = 1;
  sp.bracket_width = 6.1e-7;
  EXPECT_EQ("{" + special_point_event_fields(sp) + "}",
            "{\"kind\": \"branch_point\", \"phi_e\": 7.030035012, \"multiplicity\": 1, "
            "\"negative_before\": 0, \"negative_after\": 1, \"bracket\": 6.1e-07}");
  const RecordedEvent e = special_point_summary(sp, "symmetric");
  EXPECT_EQ(e.kind, "branch_point");
  EXPECT_EQ(e.phi_e, 7.0300350123);
  EXPECT_EQ(e.branch, "symmetric");
  EXPECT_EQ(e.value("negative_after"), 1.0);
  EXPECT_EQ(e.value("multiplicity"), 1.0);
}

}  // namespace
}  // namespace growshell
