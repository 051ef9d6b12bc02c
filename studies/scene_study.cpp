#include "studies/scene_study.hpp"

#include <stdexcept>

#include "studies/branch_record.hpp"
#include "studies/cone_branch_study.hpp"
#include "studies/econe_contact_study.hpp"
#include "studies/parameter_sweep.hpp"
#include "studies/series_study.hpp"
#include "studies/thickness_series_study.hpp"

namespace growshell {

void check_scene_study_directory(const Scene& scene, ExistingOutput existing) {
  switch (scene.study.kind) {
    case StudyKind::ConeBranch:
      check_study_directory(scene.output.directory, existing);
      return;
    case StudyKind::ThicknessSeries:
      check_thickness_series_directory(scene.output.directory, existing);
      return;
    case StudyKind::EconeContact:
      check_econe_contact_directory(scene.output.directory, existing);
      return;
    case StudyKind::Series:
      check_key_sweep_directory(scene.output.directory, existing);
      return;
  }
  throw std::logic_error("check_scene_study_directory: a study kind without a directory check");
}

std::string scene_study_record_file(const Scene& scene) {
  switch (scene.study.kind) {
    case StudyKind::ConeBranch:
      return BranchRecord::kRecordFileName;
    case StudyKind::EconeContact:
      return econe_contact_record_file();
    case StudyKind::ThicknessSeries:
    case StudyKind::Series:
      return "sweep_plan.json";
  }
  throw std::logic_error("scene_study_record_file: a study kind without a record");
}

SceneStudyOutcome run_scene_study(const Scene& scene, ExistingOutput existing,
                                  const StudyProgress& progress) {
  validate_scene(scene);
  const std::string& dir = scene.output.directory;
  check_scene_study_directory(scene, existing);
  switch (scene.study.kind) {
    case StudyKind::ConeBranch: {
      ConeBranchStudyOptions options = cone_branch_study_options(scene);
      if (existing == ExistingOutput::Resume) options.start = ConeBranchStart::LastState;
      const ConeBranchStudy study = run_cone_branch_study(scene, options, dir, progress);
      return {study.results.completed, study.results.end};
    }
    case StudyKind::ThicknessSeries: {
      const ThicknessSeriesResults series = run_thickness_series_study(scene, existing, progress);
      return {series.completed, series.end};
    }
    case StudyKind::EconeContact: {
      const EconeContactResults results = run_econe_contact_study(scene, existing, progress);
      return {results.completed, results.end};
    }
    case StudyKind::Series: {
      const SeriesResults results = run_series_study(scene, existing, progress);
      return {results.completed, results.end};
    }
  }
  throw std::logic_error("run_scene_study: a study kind without a runner");
}

}  // namespace growshell
