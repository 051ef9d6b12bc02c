#include "studies/econe_stage_record.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "tests/studies/scratch_directory.hpp"
#include "tests/support/error_message.hpp"

namespace growshell {
namespace {

using EconeStageRecordFile = testing::ScratchDirectoryTest;
/// The message of the std::runtime_error that `f` throws ("" if it throws nothing).
template <class F>
std::string runtime_error_of(F&& f) {
  return test_support::error_of<std::runtime_error>(std::forward<F>(f));
}

/// A record with every field set, some to values that are awkward to round-trip.
EconeStageRecord full_record() {
  EconeStageRecord r;
  r.key = 0x0123456789abcdefull;
  EconeStageRecord::ContactBranches b;
  EconeBranchResult& t = b.traced;
  t.symmetric.reached_bound = true;
  t.symmetric.message = "reached the parameter bound (39 steps)";
  t.skewed_down.message = "step below min_step at phi_e = 5.2 \"quoted\"";
  t.skewed_up.reached_bound = true;
  t.skewed_up.message = "reached the parameter bound";
  t.first_contact = LocatedEvent{};
  t.first_contact->parameter = 6.541591234567891;
  t.stability_loss = SpecialPoint{};
  t.stability_loss->parameter = 0.1 + 0.2;  // not a short decimal
  t.skewed_found = true;
  t.skewed_message = "relaxed along mode 2";
  t.skewed_relaxed_energy = 1.234567890123e-3;
  t.symmetric_top_energy = 1.2446e-3;
  t.skew_search_parameter = 7.2;
  t.crossings.push_back({5.618, 1e-3, -2e-4, 3.5e-6, 1, 2});
  t.crossings.push_back({6.1, 1.1e-3, 0.0, std::numeric_limits<double>::infinity(), 3, 4});
  t.crossing_skewed_stable = {true, false};
  t.skewed_search_seconds = 12.5;
  t.ipopt_checked = true;
  t.ipopt_converged = false;
  t.ipopt_message = "Maximum_Iterations_Exceeded";
  t.ipopt_energy = 1.1e-3;
  t.penalty_elastic_energy = 1.2e-3;
  t.ipopt_state_difference = 1e-5;
  t.ipopt_min_distance = 0.0399;
  t.ipopt_seconds = 100.25;
  b.max_s4_defect_symmetric = 2.2e-16;
  b.top_skewed = EconeTopSample{"skewed/states/point_00012.state", 7.3000000001, 1.3e-3};
  r.contact_branches = b;
  EconeStageRecord::Turned turned;
  turned.down = {true, "reached the parameter bound"};
  turned.up = {false, "segment start did not converge"};
  turned.lowest_phi_breaking_s4 = 5.2681;
  r.turned = turned;  // no top: none stable that breaks S4
  HardContactCheck c;
  c.phi_e = 7.0;
  c.unknowns = 2427;
  c.converged = true;
  c.message = "Optimal Solution Found";
  c.seconds = 31.5;
  c.rounds = 2;
  c.iterations = 57;
  c.penalty_elastic_energy = 1.2e-3;
  c.hard_elastic_energy = 1.19e-3;
  c.relative_energy_difference = 8.4e-3;
  c.state_difference_over_h = 0.03;
  c.penalty_min_distance_over_h = 0.95;
  c.hard_min_distance_over_h = std::numeric_limits<double>::infinity();  // no pair near
  c.penalty_s4_defect = std::numeric_limits<double>::quiet_NaN();
  c.hard_s4_defect = 0.0089;
  c.penalty_gamma = 1.5;
  c.hard_gamma = 1.504;
  r.hard_contact.push_back({"turned", 7.0, c});
  return r;
}

TEST(EconeStageRecordJson, ReadsBackWhatItWroteBitForBit) {
  const EconeStageRecord r = full_record();
  const std::string text = econe_stage_record_json(r);
  const EconeStageRecord back = parse_econe_stage_record(text, "test");
  EXPECT_EQ(econe_stage_record_json(back), text);
  EXPECT_EQ(back.key, r.key);
  ASSERT_TRUE(back.contact_branches);
  const EconeBranchResult& t = back.contact_branches->traced;
  const EconeBranchResult& o = r.contact_branches->traced;
  EXPECT_TRUE(t.symmetric.reached_bound);
  EXPECT_EQ(t.symmetric.message, o.symmetric.message);
  EXPECT_FALSE(t.skewed_down.reached_bound);
  EXPECT_EQ(t.skewed_down.message, o.skewed_down.message);
  EXPECT_TRUE(t.skewed_up.reached_bound);
  ASSERT_TRUE(t.first_contact && t.stability_loss);
  // Exactly the doubles written, not decimal approximations of them.
  EXPECT_EQ(t.first_contact->parameter, o.first_contact->parameter);
  EXPECT_EQ(t.stability_loss->parameter, 0.1 + 0.2);
  EXPECT_EQ(t.skewed_relaxed_energy, o.skewed_relaxed_energy);
  EXPECT_EQ(t.skewed_message, o.skewed_message);
  ASSERT_EQ(t.crossings.size(), 2u);
  EXPECT_EQ(t.crossings[0].parameter, 5.618);
  EXPECT_EQ(t.crossings[0].error_estimate, 3.5e-6);
  EXPECT_EQ(t.crossings[0].slope_difference, -2e-4);
  EXPECT_TRUE(std::isnan(t.crossings[1].error_estimate));  // non-finite: null, read as NaN
  EXPECT_EQ(t.crossing_skewed_stable, (std::vector<bool>{true, false}));
  EXPECT_TRUE(t.ipopt_checked);
  EXPECT_FALSE(t.ipopt_converged);
  EXPECT_EQ(t.ipopt_message, o.ipopt_message);
  EXPECT_EQ(t.ipopt_seconds, 100.25);
  EXPECT_EQ(back.contact_branches->max_s4_defect_symmetric, 2.2e-16);
  ASSERT_TRUE(back.contact_branches->top_skewed);
  EXPECT_EQ(back.contact_branches->top_skewed->state, "skewed/states/point_00012.state");
  EXPECT_EQ(back.contact_branches->top_skewed->phi_e, 7.3000000001);
  ASSERT_TRUE(back.turned);
  EXPECT_TRUE(back.turned->down.reached_bound);
  EXPECT_FALSE(back.turned->up.reached_bound);
  EXPECT_EQ(back.turned->up.message, "segment start did not converge");
  EXPECT_EQ(back.turned->lowest_phi_breaking_s4, 5.2681);
  EXPECT_FALSE(back.turned->top);
  const HardContactCheck* c = back.hard_contact_at("turned", 7.0);
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(back.hard_contact_at("symmetric", 7.0), nullptr);
  EXPECT_EQ(back.hard_contact_at("turned", 7.0000001), nullptr);
  EXPECT_EQ(c->unknowns, 2427);
  EXPECT_EQ(c->iterations, 57);
  EXPECT_EQ(c->hard_gamma, 1.504);
  EXPECT_TRUE(std::isnan(c->penalty_s4_defect));
  EXPECT_FALSE(std::isfinite(c->hard_min_distance_over_h));
}

TEST(EconeStageRecordJson, AnEmptyRecordHoldsOnlyItsKey) {
  EconeStageRecord r;
  r.key = 42;
  const EconeStageRecord back = parse_econe_stage_record(econe_stage_record_json(r), "test");
  EXPECT_EQ(back.key, 42u);
  EXPECT_FALSE(back.contact_branches);
  EXPECT_FALSE(back.turned);
  EXPECT_TRUE(back.hard_contact.empty());
}

TEST(EconeStageRecordJson, NamesWhatIsWrongWithABadRecord) {
  const auto error = [](const std::string& text) {
    return runtime_error_of(
        [&] { parse_econe_stage_record(text, "the stage record x/stages.json"); });
  };
  const std::string good = econe_stage_record_json(full_record());
  EXPECT_NE(error("{").find("x/stages.json: not JSON"), std::string::npos) << error("{");
  std::string other_format = good;
  other_format.replace(other_format.find("\"format\": 1"), 11, "\"format\": 7");
  EXPECT_NE(error(other_format).find("format is 7, not 1"), std::string::npos)
      << error(other_format);
  std::string bad_key = good;
  bad_key.replace(bad_key.find("0123456789abcdef"), 16, "0123456789abcdeZ");
  EXPECT_NE(error(bad_key).find("key '0123456789abcdeZ' is not 16 hexadecimal digits"),
            std::string::npos)
      << error(bad_key);
  std::string missing = good;
  missing.replace(missing.find("\"skewed_found\""), 14, "\"skewed_lost\"");
  EXPECT_NE(error(missing).find("contact_branches.skewed_found is missing"), std::string::npos)
      << error(missing);
  std::string mistyped = good;
  mistyped.replace(mistyped.find("\"iterations\": 57"), 16, "\"iterations\": \"57\"");
  EXPECT_NE(error(mistyped).find("hard_contact[0].check.iterations is not an integer"),
            std::string::npos)
      << error(mistyped);
}

TEST_F(EconeStageRecordFile, IsAbsentUntilWrittenThenReadBack) {
  const std::string file = path("stages.json");
  EXPECT_FALSE(read_econe_stage_record(file));
  write_econe_stage_record(file, full_record());
  const std::optional<EconeStageRecord> back = read_econe_stage_record(file);
  ASSERT_TRUE(back);
  EXPECT_EQ(econe_stage_record_json(*back), econe_stage_record_json(full_record()));
  EXPECT_EQ(listing(), (std::vector<std::string>{"stages.json"}));  // no temporary left
  write(file, "{\"format\": 1");  // cut short
  EXPECT_NE(runtime_error_of([&] { read_econe_stage_record(file); }).find(file + ": not JSON"),
            std::string::npos);
}

TEST(EconeStageKey, ChangesWithWhatStagesTwoToSixDependOnAndWithNothingElse) {
  Scene scene = default_scene();
  scene.study.kind = StudyKind::EconeContact;
  BranchSample start;
  start.parameter = 6.5;
  start.x = Eigen::VectorXd::LinSpaced(30, 0.0, 1.0);
  const std::uint64_t key = econe_stage_key(scene, start);
  EXPECT_EQ(econe_stage_key(scene, start), key);

  // The start, to the last bit of one number.
  BranchSample moved = start;
  moved.x[7] = std::nextafter(moved.x[7], 2.0);
  EXPECT_NE(econe_stage_key(scene, moved), key);
  moved = start;
  moved.parameter = std::nextafter(6.5, 7.0);
  EXPECT_NE(econe_stage_key(scene, moved), key);

  // Keys the stages read.
  Scene s = scene;
  s.continuation.phi_max = 7.5;
  EXPECT_NE(econe_stage_key(s, start), key);
  s = scene;
  s.study.skew_search_at = 7.1;
  EXPECT_NE(econe_stage_key(s, start), key);
  s = scene;
  s.study.ipopt_check = !s.study.ipopt_check;
  EXPECT_NE(econe_stage_key(s, start), key);
  s = scene;
  s.study.contact_stall_iterations = 8;
  EXPECT_NE(econe_stage_key(s, start), key);
  s = scene;
  s.study.contact_growth_pause = 6;
  EXPECT_NE(econe_stage_key(s, start), key);
  s = scene;
  s.study.contact_max_corrector_iterations = 15;
  EXPECT_NE(econe_stage_key(s, start), key);

  // Keys they do not: the output and the stages after 6; hard_contact_at goes point by point.
  s = scene;
  s.output.directory = "elsewhere";
  s.output.write_vtk = !s.output.write_vtk;
  s.study.compare_modes = {3, 4};
  s.study.wind_to = 12.5;
  s.study.wind_shapes_at = {9.0};
  s.study.hard_contact_at = {7.0};
  s.study.hard_contact_branches = {"skewed", "turned"};
  EXPECT_EQ(econe_stage_key(s, start), key);
}

}  // namespace
}  // namespace growshell
