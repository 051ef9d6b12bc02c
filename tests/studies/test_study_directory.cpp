#include "studies/study_directory.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "studies/branch_record.hpp"
#include "tests/studies/scratch_directory.hpp"
#include "tests/support/error_message.hpp"

namespace growshell {
namespace {

using StudyDirectory = testing::ScratchDirectoryTest;

using test_support::error_of;

TEST_F(StudyDirectory, RefusesANonEmptyDirectoryUnlessToldWhatToDo) {
  const std::string out = path("out");
  for (ExistingOutput e :
       {ExistingOutput::Refuse, ExistingOutput::Resume, ExistingOutput::Overwrite})
    EXPECT_NO_THROW(check_study_directory(out, e));  // missing
  std::filesystem::create_directories(out);
  EXPECT_NO_THROW(check_study_directory(out, ExistingOutput::Refuse));  // empty
  write(out + "/branch.csv", "phi_e\n");
  const std::string refused = error_of([&] { check_study_directory(out, ExistingOutput::Refuse); });
  EXPECT_NE(refused.find("'" + out + "' is not empty"), std::string::npos) << refused;
  EXPECT_NE(refused.find("--resume"), std::string::npos) << refused;
  EXPECT_NE(refused.find("--overwrite"), std::string::npos) << refused;
  EXPECT_NO_THROW(check_study_directory(out, ExistingOutput::Overwrite));
  // Resume needs a record to resume.
  EXPECT_NE(
      error_of([&] { check_study_directory(out, ExistingOutput::Resume); }).find("record.json"),
      std::string::npos);
  BranchRecord(out, {"phi_e"}, BranchRecord::Start::Fresh);
  EXPECT_NO_THROW(check_study_directory(out, ExistingOutput::Resume));
  // A file is no directory.
  write(path("file"), "x");
  EXPECT_NE(error_of([&] {
              check_study_directory(path("file"), ExistingOutput::Overwrite);
            }).find("is not a directory"),
            std::string::npos);
}

TEST_F(StudyDirectory, AResumedSceneMayChangeOnlyWhereTheTraceEnds) {
  Scene recorded = default_scene();
  recorded.thickness = ConstantThickness{0.04};
  write(path("scene.json"), scene_to_json(recorded));
  Scene s = recorded;
  s.continuation.phi_max = 7.6;
  s.output.directory = "elsewhere";
  s.study.through_contact = true;
  s.study.eigenmodes = 0;
  EXPECT_NO_THROW(check_resumable_scene(dir_.string(), s));
  s.study.tolerance = 1e-5;
  const std::string message = error_of([&] { check_resumable_scene(dir_.string(), s); });
  EXPECT_NE(message.find("study.tolerance = 1e-06, this scene 1e-05"), std::string::npos)
      << message;
  s = recorded;
  s.thickness = ConstantThickness{0.02};
  EXPECT_NE(error_of([&] { check_resumable_scene(dir_.string(), s); }).find("thickness = 0.04"),
            std::string::npos);
  // No recorded scene: read_scene's error, naming the file.
  EXPECT_NE(error_of([&] { check_resumable_scene(path("none"), recorded); }).find("scene.json"),
            std::string::npos);
}

}  // namespace
}  // namespace growshell
