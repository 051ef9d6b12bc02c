#pragma once
/// \file
/// The state of a sheet as a function of the material point: y(X), the current position of the
/// reference point X. Analyses that need the state between vertices (at a rotated material
/// point, along a fold) take such an evaluator, so that how it is computed can change behind
/// one function.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>

#include "libshell/assembly/shell_model.hpp"

namespace growshell {

/// y(X): current position (m) of the material point X (m, in the reference plane; only its x
/// and y count).
using StateEvaluator = std::function<Eigen::Vector3d(const Eigen::Vector3d&)>;

/// y(X) of the state x (control points, vertex-major like ShellModel, m) of `model` on its
/// exact limit surface: the element and parameter (v, w) whose reference limit point is X are
/// found by Newton's method on the reference limit map (the reference sheet is planar), started
/// from the barycentric coordinates of X in the triangle of the element's reference limit
/// vertices (located with a grid of buckets), and y is the current limit surface there
/// (evaluate_limit_surface), exact to the search's tolerance of 1e-13 of the sheet's extent. So
/// y(X) is the same material point however the mesh is laid out, which is what a symmetry
/// measure that maps material points onto each other needs. A point outside the reference limit
/// surface (between the rim's limit curve and the rim circle) gets the first-order continuation
/// y + (dy/d(v, w)) (dX/d(v, w))^-1 dX from the nearest point of the nearest element. The
/// evaluator holds a copy of what it needs (not the model). Throws std::invalid_argument if x
/// does not have model.dimension() entries or holds a non-finite value.
StateEvaluator sheet_state_evaluator(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x);

/// y at fixed material points, for any state: the points are located once, as
/// sheet_state_evaluator locates them, and the limit surface (and its first-order continuation
/// beyond the rim) is linear in the control points, so each state costs one sparse product.
/// For an analysis that maps the same material points at every sample (the quarter-turned
/// sheet vertices of the S4 defect on a mesh without the quarter turn), where the evaluator
/// would search for each point again.
class MaterialPointSampling {
 public:
  /// Locates `points` (m, one per row; only x and y count) on `model`'s reference. Throws
  /// std::invalid_argument for a non-finite point or a model without elements.
  MaterialPointSampling(const ShellModel& model, const Eigen::Ref<const Eigen::MatrixX3d>& points);

  /// y at the points (one row each, m) for the state x of the model: equal to
  /// sheet_state_evaluator(model, x) at each point up to the order of summation. Throws
  /// std::invalid_argument if x does not have the model's dimension.
  Eigen::MatrixX3d positions(const Eigen::Ref<const Eigen::VectorXd>& x) const;

  Eigen::Index size() const { return basis_.rows(); }

 private:
  Eigen::Index dimension_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> basis_;  // points x control vertices
};

}  // namespace growshell
