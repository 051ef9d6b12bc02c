// The series study's summaries (results.json, series.csv) on hand-made points, its base
// scene, and its refusals; the study run end to end on the paper's Table 1 scene:
// tests/programs/run_growshell_table1_rings.cmake.
#include "studies/series_study.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/support/error_message.hpp"

namespace growshell {
namespace {

SeriesResults two_points() {
  SeriesResults r;
  r.key = "geometry.inner_radius";
  r.of = "cone_branch";
  r.report = {"phi_gap_h", "phi_kiss"};
  SeriesPoint a;
  a.value = 0.1;
  a.directory = "point_000";
  a.status = "completed";
  a.end = "reached the parameter bound";
  a.unknowns = 4992;
  a.reported = {7.2914258689800295, 7.34898};
  SeriesPoint b;
  b.value = 0.5;
  b.directory = "point_001";
  b.status = "ended_early";
  b.end = "step below min_step";
  b.reported = {8.3104, std::nullopt};
  r.points = {a, b};
  r.completed = false;
  r.end = "geometry.inner_radius = 0.5 ended_early (step below min_step)";
  r.wall_seconds = 12.5;
  return r;
}

TEST(SeriesSummary, ResultsJsonHoldsEachPointsReportedValues) {
  const auto j = nlohmann::ordered_json::parse(series_results_json(two_points()));
  EXPECT_EQ(j["study"], "series");
  EXPECT_EQ(j["of"], "cone_branch");
  EXPECT_EQ(j["key"], "geometry.inner_radius");
  EXPECT_EQ(j["report"].size(), 2u);
  ASSERT_EQ(j["points"].size(), 2u);
  EXPECT_EQ(j["points"][0]["value"].get<double>(), 0.1);
  // Numbers round-trip exactly.
  EXPECT_EQ(j["points"][0]["phi_gap_h"].get<double>(), 7.2914258689800295);
  EXPECT_EQ(j["points"][0]["unknowns"].get<long long>(), 4992);
  EXPECT_EQ(j["points"][0]["results"], "point_000/results.json");
  EXPECT_TRUE(j["points"][1]["phi_kiss"].is_null());
  EXPECT_TRUE(j["points"][1]["unknowns"].is_null());
  EXPECT_EQ(j["points"][1]["status"], "ended_early");
  EXPECT_FALSE(j["completed"].get<bool>());
  EXPECT_EQ(j["wall_seconds"].get<double>(), 12.5);
}

TEST(SeriesSummary, CsvHasTheKeyTheStatusAndTheReportedColumns) {
  EXPECT_EQ(series_csv(two_points()),
            "geometry.inner_radius,status,unknowns,phi_gap_h,phi_kiss\n"
            "0.1,completed,4992,7.2914258689800295,7.34898\n"
            "0.5,ended_early,,8.3104,\n");
}

TEST(SeriesStudy, BaseSceneIsThePointsStudyWithoutTheSeriesKeys) {
  Scene s = default_scene();
  apply_override(s, "study.kind", "series");
  apply_override(s, "study.series_key", "thickness");
  apply_override(s, "study.series_values", "[0.04,0.02]");
  apply_override(s, "study.series_of", "econe_contact");
  apply_override(s, "study.series_report", "[\"phi_kiss\"]");
  validate_scene(s);
  const Scene base = series_base_scene(s);
  EXPECT_EQ(base.study.kind, StudyKind::EconeContact);
  EXPECT_TRUE(base.study.series_key.empty());
  EXPECT_TRUE(base.study.series_values.empty());
  EXPECT_TRUE(base.study.series_report.empty());
  EXPECT_NO_THROW(validate_scene(base));
  // The rest of the scene is the series scene's.
  EXPECT_EQ(base.thickness.index(), s.thickness.index());
  EXPECT_EQ(base.continuation.phi_max, s.continuation.phi_max);
}

TEST(SeriesStudy, RefusesAnotherStudysScene) {
  const std::string error = test_support::error_of(
      [] { run_series_study(default_scene(), ExistingOutput::Refuse); });
  EXPECT_NE(error.find("not series"), std::string::npos) << error;
}

}  // namespace
}  // namespace growshell
