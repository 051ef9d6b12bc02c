// parameter_sweep: KEY=V1,V2 parsing (commas inside brackets kept), the cartesian product in
// order, point scenes validated with the point named, the plan a resume must match, and the
// summaries (sweep.json, sweep.csv) with pending, completed and failed points.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "studies/parameter_sweep.hpp"
#include "studies/scene_study.hpp"
#include "studies/scratch_directory.hpp"
#include "tests/support/error_message.hpp"

namespace growshell {
namespace {

namespace fs = std::filesystem;
using test_support::error_of;
using ParameterSweepFiles = testing::ScratchDirectoryTest;

TEST(ParameterSweep, ParsesKeyAndValuesKeepingCommasInsideBrackets) {
  const SweepParameter p = parse_sweep_parameter("thickness=0.04,0.02,0.01");
  EXPECT_EQ(p.key, "thickness");
  EXPECT_EQ(p.values, (std::vector<std::string>{"0.04", "0.02", "0.01"}));
  const SweepParameter c = parse_sweep_parameter("growth.center=[0,0],[0.1,0]");
  EXPECT_EQ(c.values, (std::vector<std::string>{"[0,0]", "[0.1,0]"}));
  EXPECT_EQ(parse_sweep_parameter("mesh.family=gmsh").values, std::vector<std::string>{"gmsh"});
  EXPECT_NE(error_of([] { parse_sweep_parameter("thickness"); }).find("no '='"), std::string::npos);
  EXPECT_NE(error_of([] { parse_sweep_parameter("=0.1"); }).find("no key"), std::string::npos);
  EXPECT_NE(error_of([] { parse_sweep_parameter("thickness=0.1,,0.2"); }).find("empty value"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_sweep_parameter("thickness="); }).find("empty value"),
            std::string::npos);
}

TEST(ParameterSweep, PointsAreTheProductWithTheFirstParameterSlowest) {
  const std::vector<SweepPoint> points = sweep_points(
      {parse_sweep_parameter("mesh.family=rings,gmsh"), parse_sweep_parameter("thickness=1,2,3")});
  ASSERT_EQ(points.size(), 6u);
  EXPECT_EQ(points[0].settings[0].second, "rings");
  EXPECT_EQ(points[0].settings[1].second, "1");
  EXPECT_EQ(points[2].settings[1].second, "3");
  EXPECT_EQ(points[3].settings[0].second, "gmsh");
  EXPECT_EQ(points[3].settings[1].second, "1");
  EXPECT_EQ(points[5].directory, "point_005");
  EXPECT_EQ(points[5].index, 5);
  EXPECT_THROW(sweep_points({}), std::invalid_argument);
  EXPECT_NE(error_of([] {
              sweep_points({parse_sweep_parameter("thickness=1"), parse_sweep_parameter("thickness=2")});
            }).find("thickness is given twice"),
            std::string::npos);
}

TEST(ParameterSweep, APointSceneHasItsSettingsAndDirectoryAndNamesItsBadValue) {
  const std::vector<SweepPoint> points = sweep_points({parse_sweep_parameter("thickness=0.03,-1")});
  const Scene scene = sweep_point_scene(default_scene(), points[0], "/tmp/sweep");
  EXPECT_EQ(std::get<ConstantThickness>(scene.thickness).value, 0.03);
  EXPECT_EQ(scene.output.directory, "/tmp/sweep/point_000");
  EXPECT_EQ(error_of([&] { sweep_point_scene(default_scene(), points[1], "/tmp/sweep"); }),
            "sweep point point_001 (thickness=-1): thickness = -1 must be finite and > 0");
  const std::vector<SweepPoint> unknown = sweep_points({parse_sweep_parameter("mesh.ringz=3")});
  EXPECT_NE(error_of([&] { sweep_point_scene(default_scene(), unknown[0], "/tmp/sweep"); })
                .find("sweep point point_000 (mesh.ringz=3): unknown key 'mesh.ringz'"),
            std::string::npos);
}

TEST_F(ParameterSweepFiles, OpeningRefusesBadValuesUsedDirectoriesAndOtherPlans) {
  const std::string dir = path("sweep");
  const std::vector<SweepParameter> bad{parse_sweep_parameter("thickness=0.03,-1")};
  EXPECT_THROW(open_sweep_directory(dir, default_scene(), bad, ExistingOutput::Refuse),
               std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir));  // refused before anything was written
  const std::vector<SweepParameter> good{parse_sweep_parameter("thickness=0.03,0.04")};
  open_sweep_directory(dir, default_scene(), good, ExistingOutput::Refuse);
  EXPECT_TRUE(fs::exists(fs::path(dir) / "sweep_plan.json"));
  EXPECT_NE(error_of([&] { open_sweep_directory(dir, default_scene(), good, ExistingOutput::Refuse); })
                .find("is not empty"),
            std::string::npos);
  EXPECT_NO_THROW(open_sweep_directory(dir, default_scene(), good, ExistingOutput::Resume));
  const std::vector<SweepParameter> other{parse_sweep_parameter("thickness=0.03,0.05")};
  EXPECT_NE(error_of([&] { open_sweep_directory(dir, default_scene(), other, ExistingOutput::Resume); })
                .find("parameters differ"),
            std::string::npos);
  // Where the sweep was started from (its base's output.directory) is not part of the plan.
  Scene elsewhere = default_scene();
  elsewhere.output.directory = "/somewhere/else";
  EXPECT_NO_THROW(open_sweep_directory(dir, elsewhere, good, ExistingOutput::Resume));
  Scene changed = default_scene();
  changed.continuation.phi_max = 5.0;
  EXPECT_NE(error_of([&] { open_sweep_directory(dir, changed, good, ExistingOutput::Resume); })
                .find("/continuation/phi_max"),
            std::string::npos);
  // Overwrite removes the earlier sweep's points and plan, nothing else.
  fs::create_directories(fs::path(dir) / "point_000");
  std::ofstream(fs::path(dir) / "notes.txt") << "mine\n";
  open_sweep_directory(dir, changed, other, ExistingOutput::Overwrite);
  EXPECT_FALSE(fs::exists(fs::path(dir) / "point_000"));
  EXPECT_TRUE(fs::exists(fs::path(dir) / "notes.txt"));
  EXPECT_NO_THROW(open_sweep_directory(dir, changed, other, ExistingOutput::Resume));
}

TEST(SceneStudyRecord, EachStudyNamesTheFileThatMakesItResumable) {
  Scene s = default_scene();
  EXPECT_EQ(scene_study_record_file(s), "record.json");
  s.study.kind = StudyKind::EconeContact;
  EXPECT_EQ(scene_study_record_file(s), "cone/record.json");
  s.study.kind = StudyKind::ThicknessSeries;
  EXPECT_EQ(scene_study_record_file(s), "sweep_plan.json");
  s.study.kind = StudyKind::Series;
  EXPECT_EQ(scene_study_record_file(s), "sweep_plan.json");
}

// A killed econe_contact point keeps its record in point_NNN/cone/: the sweep resumes it (here
// the record is not one, so the resume fails and says so) instead of running it afresh over
// what it had traced.
TEST_F(ParameterSweepFiles, AnEconeContactPointWithARecordIsResumedNotRestarted) {
  Scene base = default_scene();
  base.study.kind = StudyKind::EconeContact;
  const std::vector<SweepParameter> parameters{parse_sweep_parameter("thickness=0.04")};
  const SweepPoint point = sweep_points(parameters).front();
  const Scene scene = sweep_point_scene(base, point, path("sweep"));
  const fs::path cone = fs::path(scene.output.directory) / "cone";
  fs::create_directories(cone);
  std::ofstream(cone / "record.json") << "not a record\n";
  const SweepPointResult r = run_sweep_point(scene);
  EXPECT_EQ(r.status, SweepPointResult::Status::Failed);
  EXPECT_NE(r.reason.find("scene.json"), std::string::npos) << r.reason;
  std::ifstream in(cone / "record.json");
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(first, "not a record");
}

TEST_F(ParameterSweepFiles, APlanWrittenBeforeAKeyExistedResumesWithThatKeysDefault) {
  const std::string dir = path("sweep");
  const std::vector<SweepParameter> good{parse_sweep_parameter("thickness=0.03,0.04")};
  open_sweep_directory(dir, default_scene(), good, ExistingOutput::Refuse);
  // Remove a key from the recorded base scene, as a plan of an older version lacks it.
  const fs::path plan_file = fs::path(dir) / "sweep_plan.json";
  nlohmann::json plan = nlohmann::json::parse(std::ifstream(plan_file));
  ASSERT_EQ(plan["base_scene"]["growth"].erase("smoothing_radius"), 1u);
  std::ofstream(plan_file) << plan.dump(2);
  EXPECT_NO_THROW(open_sweep_directory(dir, default_scene(), good, ExistingOutput::Resume));
  Scene smoothed = default_scene();
  smoothed.growth.smoothing_radius = 0.01;
  EXPECT_NE(error_of([&] { open_sweep_directory(dir, smoothed, good, ExistingOutput::Resume); })
                .find("/growth/smoothing_radius"),
            std::string::npos);
}

TEST_F(ParameterSweepFiles, SummariesHoldEveryPointWithItsStatusAndScalarResults) {
  const std::string dir = path("");
  const std::vector<SweepParameter> parameters{parse_sweep_parameter("thickness=0.04,0.02,0.01")};
  const std::vector<SweepPoint> points = sweep_points(parameters);
  std::vector<std::optional<SweepPointResult>> results(3);
  results[0] = SweepPointResult{SweepPointResult::Status::Completed, "reached the bound",
                                R"({"study": "cone_branch", "thickness": 0.04, "mesh": {"family": "rings", "unknowns": 12},
                                    "phi_max": 4.06, "phi_kiss": null, "end": "a, b"})"};
  results[1] = SweepPointResult{SweepPointResult::Status::Failed, "cannot open mesh", ""};
  write_sweep_summary(dir, parameters, points, results);
  const std::string json = read(path("sweep.json"));
  EXPECT_NE(json.find("\"status\": \"completed\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"status\": \"failed\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"status\": \"pending\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"reason\": \"cannot open mesh\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"thickness\": 0.02"), std::string::npos) << json;  // a number, not text
  const std::string csv = read(path("sweep.csv"));
  EXPECT_EQ(csv,
            "index,directory,thickness,status,study,mesh.family,mesh.unknowns,phi_max,phi_kiss,end\n"
            "0,point_000,0.04,completed,cone_branch,rings,12,4.06,,\"a, b\"\n"
            "1,point_001,0.02,failed,,,,,,\n"
            "2,point_002,0.01,pending,,,,,,\n");
}

}  // namespace
}  // namespace growshell
