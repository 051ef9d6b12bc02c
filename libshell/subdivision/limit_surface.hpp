#pragma once
/// \file
/// Evaluation of the limit surface of a Loop patch: position, tangents, second derivatives,
/// unit normal and curvatures.

#include <Eigen/Core>
#include <array>

#include "libshell/subdivision/loop_patch.hpp"

namespace growshell {

/// The limit surface at one parameter point of one element (SI units, metres).
struct LimitSurfacePoint {
  Eigen::Vector3d position;
  Eigen::Matrix<double, 3, 2> tangents;  ///< [a_1 a_2] = dx/dv, dx/dw
  Eigen::Matrix<double, 3, 3> second;    ///< [a_11 a_22 a_12]
  Eigen::Vector3d normal;                ///< (a_1 x a_2) / |a_1 x a_2|
  Eigen::Matrix2d metric;                ///< a_ab
  Eigen::Matrix2d curvature_tensor;      ///< b_ab = a_ab . n (covariant, 1/m times m^2)
  double mean_curvature;      ///< H = tr(a^-1 b) / 2, sign from the normal (1/m)
  double gaussian_curvature;  ///< K = det b / det a (1/m^2)
};

/// Control points, one row per vertex (m): a MatrixX3d, or the rows of a vertex-major state
/// vector x (x[3 v + c]) seen through control_point_rows, without a copy.
using ControlPointRows =
    Eigen::Ref<const Eigen::MatrixX3d, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;

/// The vertex-major state `x` (x[3 v + c], 3 entries per vertex) as rows of control points: a
/// view of x's storage, valid while x is.
inline Eigen::Map<const Eigen::MatrixX3d, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>
control_point_rows(const Eigen::Ref<const Eigen::VectorXd>& x) {
  return {x.data(), x.size() / 3, 3, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(1, 3)};
}

/// Evaluates the limit surface of `patch` (vertex indices into `positions`, one row per vertex)
/// at parameter (v, w) of the element triangle (see evaluate_patch_basis for what this means at
/// an extraordinary corner).
LimitSurfacePoint evaluate_limit_surface(const ControlPointRows& positions, const LoopPatch& patch,
                                         double v, double w);

/// The same from a basis already evaluated at the point (`basis` of `patch`).
LimitSurfacePoint evaluate_limit_surface(const ControlPointRows& positions, const LoopPatch& patch,
                                         const PatchBasis& basis);

}  // namespace growshell
