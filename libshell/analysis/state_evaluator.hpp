#pragma once
/// \file
/// The state of a sheet as a function of the material point: y(X), the current position of the
/// reference point X. Analyses that need the state between vertices (at a rotated material
/// point, along a fold) take such an evaluator, so that how it is computed can change behind
/// one function.

#include <Eigen/Core>
#include <functional>

#include "libshell/assembly/shell_model.hpp"

namespace growshell {

/// y(X): current position (m) of the material point X (m, in the reference plane; only its x
/// and y count).
using StateEvaluator = std::function<Eigen::Vector3d(const Eigen::Vector3d&)>;

/// y(X) of the state x (control points, vertex-major like ShellModel, m) of `model`, by
/// barycentric interpolation of the limit positions of the sheet vertices
/// (ShellModel::limit_positions) over the reference triangulation of the elements, with the
/// vertices at their reference limit positions. Exact at the sheet vertices; between them the
/// error is that of linear interpolation, O(spacing^2 |D^2 y|) (spacing = the local element
/// size), and O(spacing |Dy|) at a kink such as the apex of a cone. A point outside the
/// triangulation (between the rim polygon and the rim circle) is extrapolated linearly from
/// the nearest element triangle. It stands in for the exact limit surface
/// (evaluate_limit_surface) and can be swapped for it here without changing its callers.
/// The evaluator holds a copy of what it needs (not the model). Throws std::invalid_argument
/// if x does not have model.dimension() entries or holds a non-finite value.
StateEvaluator sheet_state_evaluator(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x);

}  // namespace growshell
