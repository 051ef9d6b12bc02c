#pragma once
/// \file
/// The output directory of a study: whether a study may write into it, and whether a
/// recorded study there may be resumed with a given scene. Nothing here writes.

#include <string>

#include "libshell/io/scene.hpp"

namespace growshell {

/// What to do with a directory that already holds files.
enum class ExistingOutput {
  Refuse,     ///< refuse it (the default: an earlier study is never lost by accident)
  Resume,     ///< continue the study recorded there from its last complete saved state
  Overwrite,  ///< start a new study there, replacing the earlier study's record
};

/// Throws std::invalid_argument, naming the directory and what to do, if a run may not write
/// into `directory` under `existing`: a path that exists and is not a directory; a non-empty
/// directory under Refuse; a non-empty directory without the file `record_file` (what makes
/// it resumable) under Resume. `recorded` names what is recorded there in the messages
/// ("study", "series"). A missing or empty directory is always fine.
void check_output_directory(const std::string& directory, ExistingOutput existing,
                            const std::string& recorded, const std::string& record_file);

/// check_output_directory for a study with a branch record: a non-empty directory without
/// record.json cannot be resumed.
void check_study_directory(const std::string& directory, ExistingOutput existing);

/// Throws std::invalid_argument, naming the first key that differs, unless `scene` may
/// continue the study whose scene `directory`/scene.json holds: every key must be equal except
/// those that do not change the states already traced (continuation.phi_start, continuation.phi_min,
/// continuation.phi_max, output.*, study.through_contact, study.eigenmodes). Throws as
/// read_scene if scene.json is missing or invalid.
void check_resumable_scene(const std::string& directory, const Scene& scene);

}  // namespace growshell
