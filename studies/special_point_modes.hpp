#pragma once
/// \file
/// The lowest eigenpairs of the pinned Hessian at a special point of a branch, and how much
/// each mode is the nearly free turn of the fold pattern (pattern_rotation): a special point
/// whose critical mode is that turn (overlap near 1) is the discrete disc's orientation mode,
/// not a bifurcation of the continuum problem (docs/continuation.md, "Known limits").

#include <Eigen/Core>
#include <vector>

#include "libshell/assembly/shell_model.hpp"
#include "solvers/stability/lowest_eigenpairs.hpp"

namespace growshell {

/// Eigenpairs at a special point and their overlap with the pattern's turn.
struct SpecialPointModes {
  Eigenpairs pairs;  ///< the `count` lowest, ascending (lowest_eigenpairs)
  /// |cos| of the angle between each mode and pattern_rotation at the point, in [0, 1].
  std::vector<double> orientation_overlap;
};

/// The `count` (>= 1) lowest eigenpairs of the Hessian of `model` at excess angle phi_e and
/// state x with the `pinned` dofs removed, and their orientation overlaps. Throws as
/// lowest_eigenpairs.
SpecialPointModes special_point_modes(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                                      double phi_e, const std::vector<Eigen::Index>& pinned,
                                      int count);

/// The state x displaced along `mode` by `amplitude` (m) at the mode's largest entry: a mode
/// shape to look at.
Eigen::VectorXd displaced_along_mode(const Eigen::Ref<const Eigen::VectorXd>& x,
                                     const Eigen::Ref<const Eigen::VectorXd>& mode,
                                     double amplitude);

}  // namespace growshell
