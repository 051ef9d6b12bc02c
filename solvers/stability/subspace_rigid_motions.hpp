#pragma once
/// \file
/// The rigid motions of a state that lie in a subspace of states (a symmetry class:
/// vertex_symmetry_group.hpp), and the subspace's dofs that hold them: what pins the rigid
/// motions of a Hessian restricted to that subspace and nothing else.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace growshell {

struct SubspaceRigidMotions {
  /// Reduced dofs (sorted) whose pinning removes the rigid motions in the subspace.
  std::vector<Eigen::Index> pins;
  /// Orthonormal reduced coordinates (m x k) of those rigid motions; k = pins.size().
  Eigen::MatrixXd motions;
};

/// For the orthonormal basis Q (3 n x m) of a subspace that the group's symmetries map into
/// itself, and the state x (full, vertex-major): the parts Q^T r of the six unit rigid
/// velocity fields r at x (translations, rotations about the origin, which the symmetries fix)
/// span k dimensions (singular values above 1e-3; e.g. k = 1 for the states with both mirrors
/// through the z-axis: the translation along z), and k reduced dofs are chosen by column-pivoted
/// Gram-Schmidt on that basis (largest components first, ties within a relative 1e-6 to the
/// lowest index: the same dofs at every state of a branch, not whichever round-off favours).
/// Throws std::invalid_argument unless x has Q.rows() entries.
SubspaceRigidMotions subspace_rigid_motions(const Eigen::SparseMatrix<double>& basis,
                                            const Eigen::Ref<const Eigen::VectorXd>& x);

}  // namespace growshell
