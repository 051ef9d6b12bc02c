#pragma once
/// \file
/// The stability index of a cone state without the fold pattern's turn about the growth axis:
/// the number of negative eigenvalues of the shell's Hessian, rigid motions removed by six
/// pins, restricted to the states orthogonal to the turn (pattern_rotation), a mode that the
/// axisymmetric continuum leaves neutral and a discrete disc only nearly so
/// (docs/guide/cone_branch.md, "Stability index").
///
/// The inertia of the pinned Hessian at an equilibrium does not depend on which six dofs hold
/// the rigid motions, as long as they hold them. Pins chosen on the reference lose their lever
/// arm when the sheet deforms far: on the n = 2 cone the rim vertex pinned on a fold is carried
/// towards the axis as the fold pair closes, the spin about the axis is then held only by a
/// short lever, and it becomes a nearly free mode of the pinned Hessian that mixes with the
/// turn. Left alone, the count orthogonal to the turn field then reports a negative eigenvalue
/// that no mode of the sheet has. So the count re-chooses its pins on the state whenever the
/// given ones hold its rigid motions worse than a stated condition number.

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "core/parametrized_objective.hpp"
#include "libshell/assembly/shell_model.hpp"
#include "solvers/stability/hessian_negative_count.hpp"
#include "solvers/stability/symmetry_class_stability_index.hpp"

namespace growshell {

/// The pins for analysing the state x of `model` (its eigenpairs, its turn field): `pins` (six
/// rigid-motion pins, e.g. the trace's) while they hold the rigid motions of x with a
/// pinned_rigid_motion_condition up to max_pin_condition, else pins re-chosen on x
/// (well_conditioned_pins, anchored at the first pin, among the model's sheet vertices), so that
/// a rigid motion the trace's pins barely hold is not read as a soft mode of the sheet. Throws as
/// well_conditioned_pins.
std::vector<Eigen::Index> analysis_pins(const ShellModel& model,
                                        const Eigen::Ref<const Eigen::VectorXd>& x,
                                        const std::vector<Eigen::Index>& pins,
                                        double max_pin_condition);

class TurnFreeStabilityIndex {
 public:
  /// The largest pinned_rigid_motion_condition at which the given pins are kept.
  static constexpr double kDefaultMaxPinCondition = 100.0;

  /// `pins`: six rigid-motion pins (as rigid_motion_pinned_dofs returns them), e.g. those of
  /// the trace. `family` is the model's energy as a function of the excess angle; both it and
  /// `model` must outlive this object. Throws std::invalid_argument unless there are six pins
  /// and max_pin_condition >= 1 (as pinned_rigid_motion_condition measures it).
  TurnFreeStabilityIndex(const ParametrizedObjective& family, const ShellModel& model,
                         std::vector<Eigen::Index> pins,
                         double max_pin_condition = kDefaultMaxPinCondition);

  /// The index at the equilibrium x at excess angle phi_e (sets the family's parameter): the
  /// negative eigenvalues of the pinned Hessian orthogonal to the turn, or all of them where
  /// the state has no pattern to turn (a turn field below 1e-9 of the model's size). The pins
  /// are `pins` when they hold the rigid motions of x with a condition number up to
  /// max_pin_condition, else re-chosen on x (well_conditioned_pins, anchored at the first pin,
  /// among the model's sheet vertices). Throws as HessianNegativeCount.
  int at(const Eigen::Ref<const Eigen::VectorXd>& x, double phi_e);

  /// The pins of the last at() (the given ones before the first).
  const std::vector<Eigen::Index>& last_pins() const { return count_pins_; }

 private:
  const ParametrizedObjective& family_;
  const ShellModel& model_;
  std::vector<Eigen::Index> pins_;
  double max_pin_condition_;
  double size_ = 0.0;  ///< the reference's extent, the scale of a vanishing turn field
  std::vector<Eigen::Index> count_pins_;
  std::unique_ptr<HessianNegativeCount> count_;  ///< with count_pins_
};

/// The same index at a state x of `model` that has the symmetries of `index`'s group about the
/// coordinate planes and axes through the origin (a state of a trace in a symmetric subspace,
/// expanded in the subspace's frame: BranchSample::reduced_x), class by class: index.at(x,
/// phi_e), less one where the turn (pattern_rotation without pins, which lies in one class:
/// the one odd under both mirrors of the two-fold cone, the trivial one of a half turn) leaves
/// the count (SymmetryClassStabilityIndex::negative_orthogonal_to), and the full count where
/// the state has no pattern to turn. The rigid motions are held class by class at dofs chosen
/// on x, so no pin loses its lever arm. Throws as index.at and negative_orthogonal_to.
int turn_free_index_by_class(SymmetryClassStabilityIndex& index, const ShellModel& model,
                             const Eigen::Ref<const Eigen::VectorXd>& x, double phi_e);

}  // namespace growshell
