#pragma once
/// \file
/// Symmetric quadrature rules on the parameter triangle {v >= 0, w >= 0, v + w <= 1}.

#include <vector>

namespace growshell {

/// One quadrature point: parameter coordinates (v, w) and weight. The weights of a rule sum
/// to 1/2, the area of the parameter triangle.
struct TriangleQuadraturePoint {
  double v;
  double w;
  double weight;
};

/// Degrees of polynomial exactness for which a rule is available.
inline constexpr int kAvailableQuadratureDegrees[] = {1, 2, 4, 5, 6};

/// Returns a rule with positive weights, interior points, that integrates every polynomial of
/// total degree <= `degree` exactly: 1 point (degree 1), 3 (2), 6 (4), 7 (5), 12 (6) points
/// (Strang & Fix; Dunavant 1985). Degree 3 is served by the degree-4 rule.
/// Throws std::invalid_argument for a degree outside 1..6.
std::vector<TriangleQuadraturePoint> triangle_quadrature(int degree);

}  // namespace growshell
