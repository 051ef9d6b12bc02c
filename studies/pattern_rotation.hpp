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
/// of each vertex fitted by least squares over its one-ring; zero at vertices with fewer than
/// two neighbours and at the `pinned` dofs.
Eigen::VectorXd pattern_rotation(const ShellModel& model,
                                 const Eigen::Ref<const Eigen::VectorXd>& x,
                                 const std::vector<Eigen::Index>& pinned);

}  // namespace growshell
