#pragma once
/// \file
/// A state of one mesh carried onto another, optionally turned about the growth axis over the
/// material: the starting guess from which Newton's method finds the same equilibrium on a
/// mesh that shares no structure with the first (a convergence study, a second mesh family),
/// or the same state with its pattern placed elsewhere against the mesh (an orientation test).

#include <Eigen/Core>

#include "libshell/assembly/shell_model.hpp"

namespace growshell {

/// The state x of `from` (control points, vertex-major, m) carried onto `to`: every control
/// point of `to`, ghosts included, at reference position X goes to Q y(c + Q^T (X - c)), with y
/// the current limit surface of x as a function of the material point (sheet_state_evaluator),
/// Q the rotation by `turn` (rad) about the z axis and c the growth centre of `to`. So the
/// pattern of x is turned by `turn` over the material, and the sheet as a whole by the same
/// angle in space (a rigid motion, which the energy does not see).
///
/// Exact for affine states (the Loop limit surface reproduces them); otherwise the control
/// points are placed on the limit surface of x, which differs from the control points of the
/// nearest state of `to` by the subdivision's smoothing, O(l^2 curvature) for elements of size
/// l: a starting point for Newton's method, not an equilibrium. Both models must describe the
/// same reference sheet (the same disc or ring); a control point outside it (a ghost) takes the
/// first-order continuation of the nearest element. Throws std::invalid_argument if x does not
/// have from.dimension() entries, holds a non-finite value, or `turn` is not finite.
Eigen::VectorXd transfer_state(const ShellModel& from, const Eigen::Ref<const Eigen::VectorXd>& x,
                               const ShellModel& to, double turn = 0.0);

}  // namespace growshell
