#include "studies/thickness_series_study.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "studies/parameter_sweep.hpp"
#include "tests/studies/scratch_directory.hpp"
#include "tests/support/error_message.hpp"

namespace growshell {
namespace {

using ThicknessSeries = testing::ScratchDirectoryTest;

ThicknessSeriesPoint point(double h, const std::string& status, double c2, double phi_max) {
  ThicknessSeriesPoint p;
  p.thickness = h;
  p.directory = "point_" + std::to_string(static_cast<int>(1000 * h));
  p.status = status;
  p.phi_branch = c2 * h * h;
  p.phi_max = phi_max;
  p.eb_hat_max = 4.0;
  p.unknowns = 100;
  return p;
}

TEST(ThicknessSeriesSummary, FitsBothLawsAndGivesC2) {
  // phi_branch = c2 h^2 with c2 from 10.5 to 10.7, phi_max = 2.57 + 3.6 h^0.28 exactly.
  std::vector<ThicknessSeriesPoint> points;
  const std::vector<double> h = {0.04, 0.02, 0.01}, c2 = {10.5, 10.6, 10.7};
  for (std::size_t i = 0; i < h.size(); ++i)
    points.push_back(point(h[i], "completed", c2[i], 2.57 + 3.6 * std::pow(h[i], 0.28)));
  const ThicknessSeriesResults r = summarize_thickness_series(points, 1.0, 2.57);
  EXPECT_TRUE(r.completed);
  EXPECT_EQ(r.end, "completed");
  ASSERT_TRUE(r.c2_mean && r.c2_min && r.c2_max);
  EXPECT_NEAR(*r.c2_mean, 10.6, 1e-12);
  EXPECT_NEAR(*r.c2_min, 10.5, 1e-12);
  EXPECT_NEAR(*r.c2_max, 10.7, 1e-12);
  ASSERT_TRUE(r.phi_max_fit.has_value());
  EXPECT_NEAR(r.phi_max_fit->exponent, 0.28, 1e-12);
  EXPECT_NEAR(r.phi_max_fit->amplitude, 3.6, 1e-11);
  ASSERT_TRUE(r.phi_branch_fit.has_value());
  // c2 drifts by 2 % over a factor 4 in h: the exponent is 2 - ln(10.7 / 10.5) / ln 4 (exact
  // for the outer points; the middle one, 10.6 against their geometric mean 10.5995, moves it
  // by less than 1e-4).
  EXPECT_NEAR(r.phi_branch_fit->exponent, 2.0 - std::log(10.7 / 10.5) / std::log(4.0), 1e-4);
  // On a disc of radius 2 the same angles mean c2 four times as large (phi_c = c2 h^2 / R^2).
  EXPECT_NEAR(*summarize_thickness_series(points, 2.0, 2.57).c2_mean, 4 * 10.6, 1e-11);

  const auto j = nlohmann::json::parse(thickness_series_results_json(r));
  EXPECT_EQ(j["study"], "thickness_series");
  EXPECT_EQ(j["points"].size(), 3u);
  EXPECT_EQ(j["points"][0]["branch_csv"], points[0].directory + "/branch.csv");
  EXPECT_EQ(j["phi_max_fit"]["limit"], 2.57);
  EXPECT_EQ(j["phi_max_fit"]["points"], 3);
}

TEST(ThicknessSeriesSummary, PointsThatDidNotCompleteAreNamedAndLeftOutOfThePhiMaxFit) {
  std::vector<ThicknessSeriesPoint> points = {point(0.04, "completed", 10.6, 4.07),
                                              point(0.02, "ended_early", 10.6, 3.7),
                                              point(0.01, "completed", 10.6, 3.57)};
  points[1].end = "step below min_step at parameter 3.7";
  ThicknessSeriesPoint failed;
  failed.thickness = 0.005;
  failed.directory = "point_003";
  failed.status = "failed";
  failed.end = "mesh error";
  points.push_back(failed);
  const ThicknessSeriesResults r = summarize_thickness_series(points, 1.0, 2.57);
  EXPECT_FALSE(r.completed);
  EXPECT_NE(r.end.find("h = 0.02 ended_early (step below min_step"), std::string::npos);
  EXPECT_NE(r.end.find("h = 0.005 failed (mesh error)"), std::string::npos);
  ASSERT_TRUE(r.phi_max_fit.has_value());
  EXPECT_EQ(r.phi_max_fit->points, 2);     // the early end's phi_max is where it got to
  EXPECT_EQ(r.phi_branch_fit->points, 3);  // its first branch point stands
  const std::string csv = thickness_series_csv(r);
  EXPECT_NE(csv.find("\n0.005,failed,,,,,\n"), std::string::npos) << csv;
}

TEST_F(ThicknessSeries, RefusesADirectoryItMayNotUseBeforeWritingAnything) {
  const std::string dir = path("series");
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/other.txt") << "x";
  using test_support::error_of;
  EXPECT_NE(error_of([&] { check_thickness_series_directory(dir, ExistingOutput::Refuse); })
                .find("not empty"),
            std::string::npos);
  EXPECT_NE(error_of([&] { check_thickness_series_directory(dir, ExistingOutput::Resume); })
                .find("sweep_plan.json"),
            std::string::npos);
  EXPECT_NO_THROW(check_thickness_series_directory(dir, ExistingOutput::Overwrite));
  EXPECT_NO_THROW(check_thickness_series_directory(path("missing"), ExistingOutput::Refuse));
}

TEST(ThicknessSeriesScene, TracesTheConeBranchStudyAndCannotItselfBeSwept) {
  Scene scene = default_scene();
  scene.study.kind = StudyKind::ThicknessSeries;
  scene.study.thicknesses = {0.04, 0.02};
  const Scene base = thickness_series_base_scene(scene);
  EXPECT_EQ(base.study.kind, StudyKind::ConeBranch);
  EXPECT_TRUE(base.study.thicknesses.empty());
  EXPECT_NO_THROW(validate_scene(base));
  const std::vector<SweepPoint> points = sweep_points({SweepParameter{"thickness", {"0.03"}}});
  EXPECT_NE(test_support::error_of([&] { sweep_point_scene(scene, points[0], "dir"); })
                .find("cannot be swept"),
            std::string::npos);
}

}  // namespace
}  // namespace growshell
