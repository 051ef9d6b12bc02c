#pragma once
/// \file
/// The distance from a point of the sheet to the limit surface of a set of elements, with its
/// exact gradient and Hessian in the control points: a contact gap whose level sets are as
/// smooth as the surface itself (C2 inside regular regions, C1 everywhere), where the distance
/// to the piecewise-flat contact proxy (point_triangle_distance.hpp) bends around the proxy's
/// edges with a curvature of one over the distance.
///
/// The point is a fixed linear combination of control points, p = sum_i w_i X_i (a sheet
/// vertex's limit position, or any proxy vertex: a row of ContactProxy::map). Its closest
/// point on the surface of the candidate elements is x(xi*) = sum_a N_a(xi*) X_a: each
/// element is searched by closest_limit_point from its centroid (a search that does not
/// converge is left out) and the lowest distance found wins (among values of D equal to a
/// relative 1e-12, a minimiser free inside its element before one held on a side, then the
/// lower element index); elements whose control points' bounding box lies farther than the
/// best distance found (the surface lies in their convex hull) are not searched. With r = p -
/// x(xi*) and D = |r|^2 / 2 = min over xi:
///   - the gradient is the partial one at xi* (xi* is a minimiser): dD/dX_j = c_j r, with
///     c_j = w_j - N_j(xi*) the weight of control point j in r;
///   - the Hessian adds the change of xi*: d2D = J^T J - B^T A^-1 B, where J = dr/dX
///     (c_j times the identity), A = a_ab - r . x_ab is d2D/dxi2 and
///     B_a = d2D/dxi_a dX_j = -(c_j x_a + N_j,a r) (x_a = dx/dxi_a). Where the minimiser lies on
///     a side of the candidate set's parameter triangle (the sheet's edge, or a candidate set
///     too small), xi* moves along that side only, and A and B are restricted to it;
///   - the distance d = |r| = sqrt(2 D) has dd = dD / d and d2d = (d2D - dd dd^T) / d.
/// Inside a regular region the surface is C2 and the minimiser unique near a point closer
/// than the surface's smallest radius of curvature, so d is C2 there.

#include <Eigen/Core>
#include <vector>

#include "libshell/subdivision/element_patches.hpp"
#include "libshell/subdivision/limit_surface.hpp"

namespace growshell {

/// A point of the sheet as a combination of control points: p = sum_k weight[k] X_vertex[k].
struct ControlPointCombination {
  std::vector<int> vertex;
  std::vector<double> weight;
};

/// Result of limit_surface_distance.
struct LimitSurfaceDistance {
  double distance = 0.0;                             ///< |p - x(xi*)| (m)
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   ///< p (m)
  Eigen::Vector3d closest = Eigen::Vector3d::Zero(); ///< x(xi*) (m)
  int element = -1;                                  ///< element of xi*
  Eigen::Vector2d parameter = Eigen::Vector2d::Zero(); ///< xi* = (v, w) in that element
  int active = 0;  ///< ParameterSide bits of the sides xi* lies on and is held by
  /// The control vertices the distance depends on: the point's, then the element's that are
  /// not the point's. Unknowns 3 k + c (c = x, y, z) of the derivatives below.
  std::vector<int> vertices;
  Eigen::VectorXd gradient;  ///< dd/dX (dimensionless), 3 entries per vertex
  Eigen::MatrixXd hessian;   ///< d2d/dX2 (1/m), empty unless requested
};

/// The distance from `point` (weights into `positions`, one row per control vertex, m) to the
/// limit surface of the elements `candidates` of `patches` (e.g. element_neighbourhoods'),
/// each element searched from its centroid. The Hessian is formed if `with_hessian`. Throws
/// std::invalid_argument naming the problem for an empty candidate list, an element or vertex
/// index out of range,
/// weights of another length than the vertices, or a non-finite position;
/// std::domain_error if the point lies on the surface (d at most 1e-12 of its coordinates, at
/// the rounding of the positions, where d is not differentiable),
/// if no candidate's search converged, or if the Hessian is asked for at a point whose closest
/// point is degenerate (A not positive definite along the free directions: the point at or
/// beyond a focal point of the surface).
LimitSurfaceDistance limit_surface_distance(const ControlPointRows& positions,
                                            const ElementPatches& patches,
                                            const ControlPointCombination& point,
                                            const std::vector<int>& candidates, bool with_hessian);

}  // namespace growshell
