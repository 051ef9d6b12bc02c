#pragma once
/// \file
/// The turn of an n-fold pattern about the growth axis over the material, as a field on the
/// control points: the mode that the axisymmetric continuum leaves free and a discrete disc
/// only nearly so (docs/continuation.md, "Known limits").

#include <Eigen/Core>
#include <vector>

#include "libshell/assembly/shell_model.hpp"

namespace growshell {

/// d/dalpha of Q(alpha) x(Q(alpha)^T X) at alpha = 0 (Q: rotation about the growth axis
/// through the model's growth centre): e_z x x - F (e_z x X), with the deformation gradient F
/// of each vertex fitted by least squares over its one-ring (zero at vertices with fewer than
/// two neighbours), plus the rigid velocity w + omega x (x - c) that makes it vanish at the
/// `pinned` dofs. The energy is invariant under rigid motions, so that sum is the neutral mode
/// of the pinned Hessian that an axisymmetric continuum would have: its discrete counterpart
/// is this field up to the O(mesh) error of F. Throws std::invalid_argument unless `pinned`
/// holds no dof or exactly six dofs that hold the rigid motions of x (as
/// rigid_motion_pinned_dofs returns them).
Eigen::VectorXd pattern_rotation(const ShellModel& model,
                                 const Eigen::Ref<const Eigen::VectorXd>& x,
                                 const std::vector<Eigen::Index>& pinned);

}  // namespace growshell
