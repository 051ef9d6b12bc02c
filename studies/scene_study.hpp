#pragma once
/// \file
/// The study a scene names (study.kind), run into a directory: the one entry point that the
/// driver's `run` and `sweep` share, so that a study runs the same way alone or as a point of
/// a sweep.

#include <string>

#include "libshell/io/scene.hpp"
#include "studies/study_directory.hpp"
#include "studies/study_progress.hpp"

namespace growshell {

/// What a study run returns.
struct SceneStudyOutcome {
  /// The study's trace reached its end (results.json "completed").
  bool completed = false;
  /// Why it ended (results.json "end").
  std::string end;
};

/// Throws std::invalid_argument, naming the directory and what to do, if the study of `scene`
/// may not write into scene.output.directory under `existing`: check_study_directory for
/// cone_branch, check_thickness_series_directory for thickness_series,
/// check_econe_contact_directory for econe_contact, check_key_sweep_directory for series.
/// Writes nothing.
void check_scene_study_directory(const Scene& scene, ExistingOutput existing);

/// The file, relative to scene.output.directory, whose presence means that a run of the study
/// of `scene` has begun and can be resumed: record.json (cone_branch), cone/record.json
/// (econe_contact), sweep_plan.json (thickness_series, series). A sweep resumes a point that
/// has it and no results.json.
std::string scene_study_record_file(const Scene& scene);

/// Validates `scene`, checks scene.output.directory under `existing`
/// (check_scene_study_directory), and runs the study scene.study.kind names there: from the start, or (Resume) on from the
/// last state the recorded study committed. Writes what the study writes (for cone_branch,
/// run_cone_branch_study; for thickness_series, run_thickness_series_study; for econe_contact,
/// run_econe_contact_study), never the figure. Throws, before writing anything, as
/// validate_scene and check_study_directory for bad input, and as the study's runner.
SceneStudyOutcome run_scene_study(const Scene& scene, ExistingOutput existing,
                                  const StudyProgress& progress = {});

}  // namespace growshell
