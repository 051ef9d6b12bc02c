#pragma once
/// \file
/// The cone_branch study: the flat sheet grows along its flat branch to the branch point whose
/// critical mode has n folds (continuation.mode), switches onto the n-fold cone born there and
/// follows it by pseudo-arclength continuation, through folds, stable or not, up to
/// continuation.phi_max or first contact. Along the way it locates the special points
/// (branch points and folds, with the lowest eigenpairs there) and the events (contact at gap
/// = contact distance, midsurface_contact, eb_max, symmetry_lost), measures every sample
/// (studies/cone_sample_measures.hpp), keeps the branch record (studies/branch_record.hpp) and
/// ends with DIR/results.json (studies/study_results.hpp). docs/guide/cone_branch.md is the
/// user's page; `growshell run` and trace_disc are its programs.

#include <string>

#include "libshell/io/scene.hpp"
#include "solvers/continuation/pseudo_arclength.hpp"
#include "studies/study_progress.hpp"
#include "studies/study_results.hpp"

namespace growshell {

/// Where the study's trace starts.
enum class ConeBranchStart {
  /// From the flat sheet (a fresh record: an earlier record in the directory is replaced).
  Flat,
  /// From the saved state `resume_file` (any states/point_NNNNN.state), in the direction of
  /// continuation.direction (forward: increasing phi_e). The record in the directory is
  /// continued from its last commit and the start is recorded again as the first new row
  /// (trace_disc --resume).
  SavedState,
  /// From the last state the record in the directory committed, in the direction the trace
  /// had there: the record continues as if the trace had never stopped (no row is repeated,
  /// the arclength goes on). The scene must fit the recorded one (check_resumable_scene). A
  /// directory without a record starts from flat (growshell run --resume).
  LastState,
};

/// Settings of the study. Those that change its results are scene keys (study.*, read by
/// cone_branch_study_options); the rest say where it starts.
struct ConeBranchStudyOptions {
  /// Corrector force tolerance relative to Y h^3 / R (> 0).
  double tolerance = 1e-6;
  /// Largest angle (rad) between successive tangents of an accepted step, in (0, pi).
  double max_tangent_angle = 0.3;
  /// The sheet within this radius (m, >= 0) of the growth centre is left out of the gap and
  /// the mid-surface contact test.
  double core_radius = 0.0;
  /// Lowest eigenpairs computed at each special point (>= 0; 0 = none), written to
  /// events.json with their orientation overlap and as VTK mode shapes.
  int eigenmodes = 2;
  /// Trace the cone among the states with its mirrors (falls back to the full space, with a
  /// note in the log, where the mesh or the start lacks them).
  bool symmetric_subspace = true;
  /// On the cone, count the stability index (n_negative, and so the special points) on the
  /// hyperplane orthogonal to the pattern's turn (studies/pattern_rotation.hpp,
  /// HessianNegativeCount::negative_orthogonal_to); on an axisymmetric state, which has no
  /// pattern to turn, the plain count. The flat branch always takes the plain count.
  bool index_excludes_pattern_turn = true;
  /// In the full space, hold the n-fold pattern's orientation with a phase condition
  /// (pattern_phase_functional, trace_branch_with_phase_condition); branch.csv's phase_force
  /// is the multiplier's force (N), NaN where there is none.
  bool phase_condition = false;
  /// S4 defect (> 0) above which symmetry_lost is reported (two-fold cone only).
  double symmetry_threshold = 1e-3;
  /// Go on past the first contact instead of stopping there.
  bool through_contact = false;
  ConeBranchStart start = ConeBranchStart::Flat;
  /// The saved state of ConeBranchStart::SavedState.
  std::string resume_file;
};

/// The options the scene's study section sets (start Flat).
ConeBranchStudyOptions cone_branch_study_options(const Scene& scene);

/// What a finished study returns.
struct ConeBranchStudy {
  /// As written to results.json (results.completed: the trace reached phi_max or stopped at
  /// contact; results.end says why it ended).
  ConeBranchResults results;
  /// False if the flat branch had no branch point of the wanted mode (nothing was traced on
  /// the cone; results.end says why).
  bool entered_cone = false;
  TraceCost cost;        ///< flat branch and cone
  int steps = 0;         ///< accepted steps on the cone
  int failed_steps = 0;  ///< halved steps on the cone
};

/// Runs the cone_branch study of `scene` with `options` into `out_dir` (created if missing)
/// and writes there scene.json (the scene with output.directory = out_dir), the branch record
/// (branch.csv, events.json, states/, branch.pvd with VTK snapshots every
/// output.snapshot_every samples and at events, record.json), the mode shapes at special
/// points (special_K_mode_M.vtu), last.vtu, cost.json and results.json. Each log line goes
/// to `progress`.
///
/// Validates the scene and the options and builds the model before it writes anything: a bad
/// setting throws std::invalid_argument naming it, a mesh that cannot be built MeshError, a
/// scene that cannot resume the recorded study std::invalid_argument naming the key; a
/// missing or unfitting saved state throws std::runtime_error naming the file.
ConeBranchStudy run_cone_branch_study(const Scene& scene, const ConeBranchStudyOptions& options,
                                      const std::string& out_dir,
                                      const StudyProgress& progress = {});

}  // namespace growshell
