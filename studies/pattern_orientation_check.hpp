#pragma once
/// \file
/// Does the answer depend on where the fold pattern sits against the mesh? The traced cone
/// (folds on the mesh's mirror lines, as the mirror subspace keeps them) is turned over the
/// material by given angles (transfer_state), relaxed at the same excess angle with the
/// contact penalty, and compared with the traced state: energy, S4 defect, where the pattern
/// settles, its softest modes, and where on the sheet the energy changed. The axisymmetric
/// continuum gives every turn the same energy and symmetry; a mesh gives them only nearly. A
/// turned state that is lower by more than the effect being measured, or that breaks a symmetry
/// the traced state keeps, shows a result that the mesh, not the sheet, decides
/// (docs/results.md, "The apex core against the mesh").

#include <Eigen/Core>
#include <string>
#include <vector>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "libshell/io/scene.hpp"
#include "solvers/contact/contact_branch.hpp"
#include "solvers/newton/newton_solver.hpp"

namespace growshell {

/// Settings of check_pattern_orientation.
struct PatternOrientationCheckOptions {
  /// Turns of the pattern over the material (rad), each relaxed from the traced state.
  std::vector<double> turns;
  /// The penalty (contact distance, exclusion radius, stiffness, margin, pair selection) that
  /// keeps the relaxed sheet from passing through itself; its step fields are unused.
  ContactBranchOptions contact;
  /// The minimisation (relax_with_contact); its max_step_inf_norm bounds each Newton step.
  NewtonOptions relaxation;
  /// Energy differences are split at this reference radius about the growth centre (m, > 0):
  /// the apex core inside, the cone outside.
  double core_radius = 0.0;
};

/// The check as the studies run it on `scene`: the turns of study.orientation_check_turns; the
/// econe_contact study's penalty (contact distance and exclusion radius from the scene,
/// stiffness study.penalty_stiffness_factor Y l^2 / h with l the spacing of `proxy`, margin h,
/// rigid-motion pins re-chosen above a condition number of 20); the relaxation to
/// study.tolerance Y h^3 / R in force with the decrement test at 1e-6 Y h^3, each Newton step
/// moving no dof by more than h / 4, up to 1000 steps; the core radius h.
PatternOrientationCheckOptions scene_orientation_check_options(const Scene& scene,
                                                               const ShellModel& model,
                                                               const ContactProxy& proxy);

/// One turned and relaxed state.
struct TurnedPatternState {
  double turn = 0.0;  ///< rad, as asked
  bool converged = false;
  std::string message;  ///< why the relaxation failed, if it did
  Eigen::VectorXd x;    ///< the relaxed state (the last iterate if it failed)
  /// Where its up-fold settled (rad, reference polar angle; fold_directions), and the traced
  /// state's.
  double fold_angle = 0.0;
  double energy = 0.0;      ///< E_s + E_b + P (J)
  double stretching = 0.0;  ///< J
  double bending = 0.0;     ///< J
  double s4_defect = 0.0;   ///< cone_symmetry's S4 defect (relative to R)
  double chord_up = 0.0, chord_down = 0.0;
  /// (energy - traced energy) / traced energy.
  double energy_relative = 0.0;
  /// The elastic energy change inside and outside core_radius (J): where the difference lies.
  double energy_change_core = 0.0, energy_change_outside = 0.0;
  double lowest_eigenvalue = 0.0;  ///< of the penalised Hessian with the pins held (N/m)
  int turn_free_index = 0;         ///< TurnFreeStabilityIndex at the state
};

/// The check at one state.
struct PatternOrientationCheck {
  double phi_e = 0.0;
  double energy = 0.0;      ///< the traced state's E_s + E_b + P (J)
  double s4_defect = 0.0;   ///< the traced state's
  double fold_angle = 0.0;  ///< the traced state's up-fold (rad)
  std::vector<TurnedPatternState> turned;
  /// The largest |energy_relative| over the converged turned states; 0 if none converged.
  double largest_energy_change() const;
  /// The lowest energy_relative (negative: a turned state lies below the traced one).
  double lowest_energy_relative() const;
};

/// Turns the two-fold (S4-measurable) state x at phi_e of `model` by each of options.turns,
/// relaxes it with the penalty on `proxy` holding rigid-motion pins (`pins`, six dofs,
/// re-chosen on the turned state where they lose their lever arm), and measures both. A turn
/// whose relaxation fails is reported with converged = false, not thrown. Throws
/// std::invalid_argument for a state of the wrong size, no turns, a non-finite turn or a
/// core_radius that is not > 0.
PatternOrientationCheck check_pattern_orientation(const ShellModel& model,
                                                  const ContactProxy& proxy,
                                                  const Eigen::Ref<const Eigen::VectorXd>& x,
                                                  double phi_e,
                                                  const std::vector<Eigen::Index>& pins,
                                                  const PatternOrientationCheckOptions& options);

}  // namespace growshell
