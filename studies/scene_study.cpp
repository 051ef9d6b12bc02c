#include "studies/scene_study.hpp"

#include <stdexcept>

#include "studies/cone_branch_study.hpp"

namespace growshell {

SceneStudyOutcome run_scene_study(const Scene& scene, ExistingOutput existing,
                                  const StudyProgress& progress) {
  validate_scene(scene);
  const std::string& dir = scene.output.directory;
  check_study_directory(dir, existing);
  switch (scene.study.kind) {
    case StudyKind::ConeBranch: {
      ConeBranchStudyOptions options = cone_branch_study_options(scene);
      if (existing == ExistingOutput::Resume) options.start = ConeBranchStart::LastState;
      const ConeBranchStudy study = run_cone_branch_study(scene, options, dir, progress);
      return {study.results.completed, study.results.end};
    }
  }
  throw std::logic_error("run_scene_study: a study kind without a runner");
}

}  // namespace growshell
