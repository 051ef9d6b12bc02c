#pragma once
/// \file
/// The eigenpairs of H v = lambda M v on the M-orthogonal complement of the rigid motions,
/// from those computed with rigid-motion pins.
///
/// Pinning dofs removes the rigid motions, but a pinned mode is the sheet's mode shifted by the
/// rigid motion that makes it vanish at the pins; the shift adds to its norm v^T M v and leaves
/// v^T H v unchanged (H annihilates rigid motions at an equilibrium), so a pinned eigenvalue lies
/// nearer zero than the sheet's. The sheet's eigenpairs are those of H v = lambda M_perp v on the
/// pinned space, with M_perp = M - M R (R^T M R)^+ R^T M the mass of v less its M-orthogonal
/// rigid part (R the rigid velocity fields). rigid_free_eigenpairs solves that problem by
/// Rayleigh-Ritz on the span of pinned eigenvectors: exact when they span the pinned space, and
/// otherwise upper bounds that converge as more pinned modes are given.

#include <Eigen/Core>

#include "solvers/stability/lowest_eigenpairs.hpp"

namespace growshell {

/// Eigenpairs free of rigid motion.
struct RigidFreeEigenpairs {
  Eigen::VectorXd values;   ///< ascending, units of H per unit mass
  /// Columns in the order of `values`: M-orthogonal to every rigid field and to each other,
  /// M-normalised (v^T M v = 1).
  Eigen::MatrixXd vectors;
};

/// The `count` lowest eigenpairs of H v = lambda M_perp v by Rayleigh-Ritz on the span of
/// `pinned`'s vectors (M-orthonormal, zero at the pins, V^T H V = diag(pinned.values), as
/// lowest_mass_normalized_eigenpairs returns them), with M = diag(dof_mass) and the rigid
/// fields as the columns of `rigid` (any number; fields that are combinations of the others, or
/// vanish, drop out). The vectors returned are the modes less their rigid part. Throws
/// std::invalid_argument for mismatched sizes or count < 1, and std::runtime_error if the small
/// generalised eigenproblem fails (the pinned vectors do not hold the rigid motions).
RigidFreeEigenpairs rigid_free_eigenpairs(const Eigenpairs& pinned, const Eigen::MatrixXd& rigid,
                                          const Eigen::VectorXd& dof_mass, int count);

}  // namespace growshell
