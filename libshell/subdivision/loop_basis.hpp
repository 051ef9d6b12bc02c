#pragma once
/// \file
/// The 12 quartic box-spline basis functions of a regular Loop subdivision patch.
///
/// A regular patch is a triangle whose three corners have valence 6. Its limit surface is
///   x(v, w) = sum_i N_i(v, w) x_i,   i = 0..11,
/// over the parameter triangle {v >= 0, w >= 0, v + w <= 1}, with u = 1 - v - w.
/// Control point numbering (0-based; Cirak, Ortiz & Schroeder 2000 number them 1..12):
///
///         0   1
///       2   3   4
///     5   6   7   8
///       9   10  11
///
/// The element triangle is (3, 6, 7): node 3 sits at u = 1, node 6 at v = 1, node 7 at w = 1.
/// The formulas are Stam's (1998) expansion of the three-direction quartic box spline.

#include <Eigen/Core>

namespace growshell {

/// Values and parametric derivatives of the 12 basis functions at one point (v, w).
/// Columns of `first`: d/dv, d/dw. Columns of `second`: d2/dv2, d2/dw2, d2/dvdw.
struct LoopBasisValues {
  Eigen::Matrix<double, 12, 1> value;
  Eigen::Matrix<double, 12, 2> first;
  Eigen::Matrix<double, 12, 3> second;
};

/// Evaluates the regular-patch basis at parameter point (v, w) of the element triangle.
/// Exact (polynomial) for any (v, w); meaningful inside the triangle.
LoopBasisValues evaluate_regular_loop_basis(double v, double w);

/// Loop limit-position weights of a valence-6 vertex: 1/2 for the vertex, 1/12 for each of
/// its six neighbours.
inline constexpr double kRegularLimitCentreWeight = 0.5;
inline constexpr double kRegularLimitNeighbourWeight = 1.0 / 12.0;

}  // namespace growshell
