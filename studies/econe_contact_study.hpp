#pragma once
/// \file
/// The econe_contact study (the paper's Fig. 4 at one thickness): the two-fold cone through
/// self-contact, the skewed cone, and the critical excess angle phi_e^crit both ways.
///
///  1. DIR/cone: the cone_branch study of the scene without contact
///  (studies/cone_branch_study.hpp),
///     from the flat sheet up to its first contact: a gap equal to the contact distance between
///     parts of the sheet farther apart in the reference than physics.contact_exclusion_radius.
///  2. DIR/symmetric: from the cone's last state, the symmetric branch with the contact penalty
///     (solvers/contact/contact_branch.hpp), among the states with the folds' mirrors, up to
///     continuation.phi_max, its stability index counted in the full space without the fold
///     pattern's turn: its first contact and its loss of stability (phi_e^crit by stability).
///  3. DIR/skewed: the skewed cone, found by relaxing the symmetric state at
///     study.skew_search_at pushed along its lowest modes, traced down to its lower end and up
///     to continuation.phi_max; the relaxed state solved again by Ipopt under the hard
///     constraints gap >= contact distance (study.ipopt_check).
///  4. The energy crossing of the two branches where the skewed cone is stable: phi_e^crit by
///     energy. DIR/results.json holds the key values.
///
/// Each of DIR/cone, DIR/symmetric and DIR/skewed is a branch record (studies/branch_record.hpp).
/// Resuming goes on with stage 1 from its last committed state; stages 2-4 then run again from
/// the cone's last state, their records started afresh. docs/guide/econe_contact.md is the
/// user's page.

#include <string>

#include "libshell/io/scene.hpp"
#include "studies/study_directory.hpp"
#include "studies/study_progress.hpp"
#include "studies/study_results.hpp"

namespace growshell {

/// The contact-free cone_branch scene of stage 1: `scene` with study.kind cone_branch, stopping
/// at first contact, writing into DIR/cone.
Scene econe_contact_cone_scene(const Scene& scene);

/// "cone/record.json": the record of the study's first stage, whose presence in DIR means the
/// study has begun and can be resumed (check_econe_contact_directory requires it to resume).
std::string econe_contact_record_file();

/// Throws std::invalid_argument, naming the directory and what to do, if the study may not use
/// `directory` under `existing` (check_output_directory; resumable where DIR/cone holds a
/// branch record). Writes nothing.
void check_econe_contact_directory(const std::string& directory, ExistingOutput existing);

/// Runs the study of `scene` (study.kind econe_contact) into scene.output.directory, each log
/// line to `progress`, and writes DIR/scene.json, the three branch records and DIR/results.json.
/// Validates the scene, the directory and the model before writing anything: throws
/// std::invalid_argument naming the problem (e.g. a ring, which has no apex to start a cone
/// from flat, is accepted; a mode other than 2 is not).
EconeContactResults run_econe_contact_study(const Scene& scene, ExistingOutput existing,
                                            const StudyProgress& progress = {});

}  // namespace growshell
