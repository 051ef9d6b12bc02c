#pragma once
/// \file
/// The element size field of the graded disc meshes: proportional to the distance from the
/// centre (apex), with a floor in the core and an optional cap.

#include <limits>
#include <string>

namespace growshell {

/// Target element size s(r) = clamp(slope r, floor, max) at distance r from the centre (m).
struct RadialSize {
  /// c (> 0, dimensionless): s = c r between the floor and the cap (a log-polar region).
  double slope = 0.25;
  /// s_min (> 0, m): the size in the core r < s_min / c, e.g. h / 2 for a core of radius ~h.
  double floor = 0.01;
  /// s_max (>= floor, m, may be +infinity): the largest size.
  double max = std::numeric_limits<double>::infinity();
};

/// s(r) = min(max(slope r, floor), max) in metres, for r >= 0 (m).
double radial_size(const RadialSize& size, double r);

/// Throws MeshError naming `caller` and the offending field unless slope and floor are finite
/// and > 0 and max >= floor (max may be +infinity).
void check_radial_size(const RadialSize& size, const std::string& caller);

/// The size coordinate u(r) = integral_0^r dr' / s(r') (dimensionless): the number of elements
/// of size s that fit along a radius up to r. Continuous and strictly increasing.
double radial_size_coordinate(const RadialSize& size, double r);

/// The inverse of radial_size_coordinate: the r >= 0 (m) with u(r) = u, for u >= 0.
double radius_at_size_coordinate(const RadialSize& size, double u);

}  // namespace growshell
