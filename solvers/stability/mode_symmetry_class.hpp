#pragma once
/// \file
/// Which symmetry class of a group of commuting involutions (vertex_symmetry_group.hpp) a
/// vector lies in. At a symmetric state of an invariant energy the Hessian is block-diagonal
/// over the classes, so each eigenmode of a simple eigenvalue lies in one of them; a mode in a
/// class whose character is -1 on some generator s satisfies T_s v = -v, so the states
/// x + a v and x - a v of a symmetric x are images of each other under s.

#include <Eigen/Core>
#include <vector>

#include "solvers/stability/vertex_symmetry_group.hpp"

namespace growshell {

/// The class that holds the largest part of a vector.
struct ModeSymmetryClass {
  /// The class's character, one sign per generator of the group (all +1: the symmetric states).
  std::vector<int> generator_signs;
  /// |P v|² / |v|², P the orthogonal projection onto that class: 1 for a vector in it.
  double weight = 0.0;
  /// Whether the character is the trivial one (the vector is symmetric, not odd under any
  /// generator).
  bool trivial() const;
  /// The first generator on which the character is -1 (T_s v = -v for a vector in the class),
  /// or -1 for the trivial class.
  int odd_generator() const;
};

/// The class of `group` (whose classes must split the space:
/// VertexSymmetryGroup::classes_split_space) holding the largest part of v's squared norm.
/// Throws std::invalid_argument if the classes do not split the space, v has another size than
/// 3 × the group's vertex count, or v is zero or not finite.
ModeSymmetryClass mode_symmetry_class(const VertexSymmetryGroup& group,
                                      const Eigen::Ref<const Eigen::VectorXd>& v);

}  // namespace growshell
