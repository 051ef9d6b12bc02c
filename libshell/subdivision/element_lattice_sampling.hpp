#pragma once
/// \file
/// The limit positions at a lattice of points of every element, as one sparse linear map from
/// the control points: built once per mesh, applied to any state with a sparse product.
///
/// Evaluating a patch with an extraordinary corner subdivides it around the point
/// (loop_patch.hpp), which allocates and costs about 40 times a regular evaluation; the
/// analyses that sample the whole surface at every continuation step (smallest self-distance,
/// self-intersection, snapshots) spent most of their time there. The basis values at fixed
/// parameter points do not depend on the state, so they are evaluated once.

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "libshell/subdivision/element_patches.hpp"

namespace growshell {

/// The lattice points (v, w) = (i / n, j / n), i, j >= 0, i + j <= n, of every element of
/// `patches`, and the map from control positions to their limit positions.
class ElementLatticeSampling {
 public:
  /// Evaluates every element's basis at its (n + 1)(n + 2) / 2 lattice points (n >= 1), and the
  /// reference limit positions there from `reference_control` (one row per control vertex, m).
  /// Throws std::invalid_argument for n < 1, for a patch that refers to a vertex outside
  /// reference_control and, as evaluate_patch_basis, for a patch whose faces do not surround
  /// its corners.
  ElementLatticeSampling(const ElementPatches& patches,
                         const Eigen::Ref<const Eigen::MatrixX3d>& reference_control, int n);

  int subdivisions() const { return n_; }
  int points_per_element() const { return (n_ + 1) * (n_ + 2) / 2; }
  Eigen::Index num_elements() const { return num_elements_; }

  /// Row of lattice point (i, j) of element e in positions(): e * points_per_element() +
  /// i (n + 1) - i (i - 1) / 2 + j, i.e. element by element, i-major.
  Eigen::Index row(Eigen::Index e, int i, int j) const {
    return e * points_per_element() + i * (n_ + 1) - i * (i - 1) / 2 + j;
  }

  /// Limit positions (metres) at every lattice point for control positions `control` (one row
  /// per vertex), in the order of row(). Equal to evaluate_limit_surface(control, patch, i / n,
  /// j / n).position up to the order of summation (a few ulps).
  Eigen::MatrixX3d positions(const Eigen::Ref<const Eigen::MatrixX3d>& control) const;

  /// The same for a state x given as one vector, vertex-major (x[3 v + c], as ShellModel).
  Eigen::MatrixX3d state_positions(const Eigen::Ref<const Eigen::VectorXd>& x) const;

  /// The limit positions of the reference at every lattice point, computed once.
  const Eigen::MatrixX3d& reference_positions() const { return reference_; }

 private:
  int n_;
  Eigen::Index num_elements_;
  Eigen::Index num_vertices_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> basis_;  // lattice points x control points
  Eigen::MatrixX3d reference_;
};

}  // namespace growshell
