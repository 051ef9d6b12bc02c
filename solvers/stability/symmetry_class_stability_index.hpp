#pragma once
/// \file
/// The stability index of a symmetric state class by class: at a state with the symmetries of
/// a group of commuting involutions (the two mirrors of the two-fold cone, a half turn), the
/// Hessian of an energy the group leaves invariant is block-diagonal over the group's symmetry
/// classes (vertex_symmetry_group.hpp), so its negative eigenvalues are those of the blocks
/// Q_c^T H Q_c, each with the rigid motions that lie in its class pinned. For the two mirrors
/// that is four factorisations of a quarter of the unknowns each instead of one of all of them,
/// and the count per class says which symmetry each unstable mode breaks. For an energy that
/// breaks the symmetry slightly (a contact pair set chosen with index tie-breaks) the blocks are
/// those of the symmetrised energy, the one whose equilibria a trace in the symmetric subspace
/// follows (symmetric_subspace_family.hpp).

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "core/parametrized_objective.hpp"
#include "solvers/stability/vertex_symmetry_group.hpp"

namespace growshell {

class SymmetryClassStabilityIndex {
 public:
  /// Holds a reference to `family` (it must outlive this object); analyses each class's block
  /// once. Throws std::invalid_argument if the family is not of the group's 3 n unknowns, and
  /// as VertexSymmetryGroup::splitting_characters if the group's classes do not split the
  /// space.
  SymmetryClassStabilityIndex(const ParametrizedObjective& family,
                              const VertexSymmetryGroup& group);
  ~SymmetryClassStabilityIndex();
  SymmetryClassStabilityIndex(const SymmetryClassStabilityIndex&) = delete;
  SymmetryClassStabilityIndex& operator=(const SymmetryClassStabilityIndex&) = delete;

  /// Negative eigenvalues of the Hessian at (x, lambda) without its rigid motions: the sum
  /// over the classes of those of Q_c^T H Q_c with the class's rigid motions at x pinned
  /// (subspace_rigid_motions). At an equilibrium this is the count of the Hessian with any six
  /// dofs that hold the rigid motions fixed (HessianNegativeCount). Throws
  /// std::invalid_argument if x has the wrong size or lies off the group's symmetric subspace
  /// by more than 1e-9 of its extent, and std::runtime_error (naming the class) if a block is
  /// not finite or singular.
  int at(const Eigen::Ref<const Eigen::VectorXd>& x, double lambda);

  /// After at(): the count restricted to the states orthogonal to `direction` (full,
  /// vertex-major; e.g. the fold pattern's turn), which must lie in one class: the part d of
  /// it in that class, moved by the class's rigid motions so that it vanishes at the class's
  /// pins, gives that class's count less one if d^T H_c^{-1} d < 0
  /// (HessianNegativeCount::negative_orthogonal_to). Throws std::logic_error before at(),
  /// std::invalid_argument for a wrong size, a direction that is not finite, vanishes on the
  /// free dofs, or has parts in two classes (the smaller above 1e-6 of the larger), and
  /// std::runtime_error if d^T H_c^{-1} d is zero or not finite.
  int negative_orthogonal_to(const Eigen::Ref<const Eigen::VectorXd>& direction) const;

  /// The characters of the classes (signs on the group's generators, the trivial one first).
  const std::vector<std::vector<int>>& characters() const { return characters_; }
  /// Negative eigenvalues of each class's block at the last at(), in the order of
  /// characters(); empty before the first.
  const std::vector<int>& class_negatives() const { return class_negatives_; }
  /// Reduced dimension of each class, in the order of characters().
  std::vector<Eigen::Index> class_dimensions() const;

 private:
  struct ClassBlock;
  const ParametrizedObjective& family_;
  Eigen::SparseMatrix<double> symmetric_basis_;  ///< of the trivial class: the symmetry check
  Eigen::SparseMatrix<double> hessian_;          ///< the full Hessian of the last at()
  std::vector<std::vector<int>> characters_;
  std::vector<std::unique_ptr<ClassBlock>> blocks_;
  std::vector<int> class_negatives_;
};

}  // namespace growshell
