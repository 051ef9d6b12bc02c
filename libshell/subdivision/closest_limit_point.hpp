#pragma once
/// \file
/// The point of one element's limit surface closest to a given point in space: the minimiser
/// of D(v, w) = |p - x(v, w)|^2 / 2 over the element's parameter triangle
/// {v >= 0, w >= 0, v + w <= 1} (loop_patch.hpp).
///
/// Method: Newton's method on D with an active set for the triangle's three sides. In the
/// parameters, dD = -r . x_a (r = p - x, x_a = dx/dv, dx/dw) and
/// d2D = a_ab - r . x_ab (the metric less the normal distance times the curvature). Where
/// d2D is not positive definite in the free directions (a point beyond a focal point of the
/// surface, or far from the element) the step is the Gauss-Newton one, a_ab^-1 times the
/// gradient, which always descends. Steps are cut back to the triangle and halved until D
/// falls (Armijo, allowing for the rounding of D, below which Newton's last decreases lie). A side is active where the point lies on it and the descent direction
/// points out of the triangle (by more than the gradient tolerance below, so that a minimiser
/// on a side with a gradient zero to rounding counts as free); the step then runs along the
/// side, and at a corner with both
/// sides active it is zero. Converged when the step in (v, w) is below 1e-14 (with a Newton
/// step, D is then at its minimum to rounding), or when no step lowers D and the gradient in
/// the free directions is below 1e-13 of |x_a| |r| + |x_a|^2 (parameters are of order one).
///
/// The minimiser is that of this element's polynomial piece only: where it lies on a side of
/// the triangle, the closest point of the whole surface may lie in the neighbouring element
/// (limit_surface_distance.hpp searches a set of elements).

#include <Eigen/Core>

#include "libshell/subdivision/limit_surface.hpp"
#include "libshell/subdivision/loop_patch.hpp"

namespace growshell {

/// Bits of ClosestLimitPoint::active: the sides of the parameter triangle the point lies on
/// with the descent direction pointing out of the triangle.
enum ParameterSide : int {
  kSideV0 = 1,   ///< v = 0 (the side from corner a to corner c)
  kSideW0 = 2,   ///< w = 0 (from a to b)
  kSideU0 = 4,   ///< v + w = 1 (from b to c)
};

/// Result of closest_limit_point.
struct ClosestLimitPoint {
  Eigen::Vector2d parameter = Eigen::Vector2d::Zero();  ///< (v, w) of the closest point
  Eigen::Vector3d position = Eigen::Vector3d::Zero();   ///< x(v, w) (m)
  double half_squared_distance = 0.0;                   ///< D = |p - x|^2 / 2 (m^2)
  int active = 0;         ///< ParameterSide bits: sides that bound the minimiser
  int iterations = 0;     ///< Newton iterations
  bool converged = false; ///< false if the iteration limit (50) was reached first
};

/// The closest point to `point` (m) on the limit surface of `patch` (vertex indices into
/// `positions`, one row per control vertex, m), starting from parameter `start` (clamped into
/// the triangle). Deterministic. Throws std::invalid_argument for a non-finite point or start,
/// and whatever evaluate_patch_basis throws.
ClosestLimitPoint closest_limit_point(const ControlPointRows& positions, const LoopPatch& patch,
                                      const Eigen::Ref<const Eigen::Vector3d>& point,
                                      const Eigen::Ref<const Eigen::Vector2d>& start);

/// The parameter (v, w) of the triangle point nearest to (v, w) in the parameter plane's own
/// Euclidean metric (a projection onto the closed triangle).
Eigen::Vector2d clamp_to_parameter_triangle(const Eigen::Ref<const Eigen::Vector2d>& parameter);

}  // namespace growshell
