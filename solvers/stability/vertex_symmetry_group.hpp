#pragma once
/// \file
/// The group that some vertex symmetries (mirrors and half turns about coordinate planes and
/// axes, libshell/mesh/vertex_symmetry.hpp) generate, acting on vertex-major states
/// (dof 3 v + c) by (T_g x)_{image[v]} = S_g x_v, and its symmetry classes: for a character
/// chi of the group (a sign for each element, multiplicative), the states with
/// T_g x = chi(g) x. The class of the trivial character is the symmetric subspace a symmetric
/// branch is traced in; for a group of commuting involutions (the two mirrors of the two-fold
/// cone, a half turn) the classes of all its characters split the whole space, and the Hessian
/// of an invariant energy at a symmetric state is block-diagonal over them (docs/continuation.md,
/// "Symmetric subspace").

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "libshell/mesh/vertex_symmetry.hpp"

namespace growshell {

class VertexSymmetryGroup {
 public:
  /// The closure of `generators` under composition. Throws std::invalid_argument naming the
  /// generator if one is for another vertex count, is not a permutation or has a sign other
  /// than +1 or -1, and if the group has more than 64 elements.
  VertexSymmetryGroup(Eigen::Index vertex_count, std::vector<VertexSymmetry> generators);

  Eigen::Index vertex_count() const { return vertex_count_; }
  const std::vector<VertexSymmetry>& generators() const { return generators_; }
  int order() const { return static_cast<int>(elements_.size()); }

  /// Whether the signs (one per generator, each +1 or -1) extend to a character: chi(s g) =
  /// chi(s) chi(g) for every element g and generator s. All +1 always does.
  bool is_character(const std::vector<int>& generator_signs) const;

  /// Orthonormal basis (3 n x m, one column per dof orbit that the character does not cancel:
  /// the normalised sum of chi(g) T_g e_dof over the group) of the class of the character
  /// with `generator_signs`. Each row has at most one nonzero. Throws std::invalid_argument
  /// for a wrong count of signs, a sign other than +1 or -1, or signs that are no character.
  Eigen::SparseMatrix<double> class_basis(const std::vector<int>& generator_signs) const;

  /// The characters (as generator signs) whose classes split the whole space, the trivial one
  /// first: every sign pattern, for 2^k elements of k commuting involutions. Throws
  /// std::invalid_argument unless the group is of that kind (a generator that is not an
  /// involution, two that do not commute, or one that the others generate): its classes
  /// would then not span the space.
  std::vector<std::vector<int>> splitting_characters() const;
  /// Whether splitting_characters() would succeed (the group is of commuting, independent
  /// involutions).
  bool classes_split_space() const;

 private:
  /// chi(g) of each element for the given generator signs, from the word the closure found for
  /// it (a character only if is_character).
  std::vector<int> word_signs(const std::vector<int>& generator_signs) const;
  /// Why the classes do not split the space ("" if they do): see splitting_characters.
  std::string why_classes_do_not_split() const;

  Eigen::Index vertex_count_ = 0;
  std::vector<VertexSymmetry> generators_;
  std::vector<VertexSymmetry> elements_;      ///< the identity first
  std::vector<unsigned> words_;               ///< per element: the generators of one word for it
  std::vector<std::vector<int>> products_;    ///< products_[g][s]: the element s after g
};

}  // namespace growshell
