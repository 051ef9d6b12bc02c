#pragma once
// The exact closest point on the paraboloid z = a ((x - x0)^2 + y^2) + shift, the limit surface
// that a regular Loop control net sampled from a quadratic reproduces (the tests of the
// closest point and of the distance to the limit surface).

#include <Eigen/Core>

namespace growshell::test_support {

/// The foot of p on the paraboloid: in the plane through the axis and p, the root of
/// (rho - rho_p) + 2 a rho (a rho^2 + shift - z_p) = 0 near rho_p (Newton, 60 iterations).
inline Eigen::Vector3d paraboloid_foot(const Eigen::Vector3d& p, double a, double x0,
                                       double shift) {
  const Eigen::Vector2d offset(p.x() - x0, p.y());
  const double rho_p = offset.norm();
  double rho = rho_p;
  for (int k = 0; k < 60; ++k) {
    const double z = a * rho * rho + shift;
    const double f = (rho - rho_p) + 2.0 * a * rho * (z - p.z());
    const double df = 1.0 + 2.0 * a * (z - p.z()) + 4.0 * a * a * rho * rho;
    rho -= f / df;
  }
  const Eigen::Vector2d dir =
      rho_p > 0.0 ? Eigen::Vector2d(offset / rho_p) : Eigen::Vector2d(1.0, 0.0);
  return {x0 + rho * dir.x(), rho * dir.y(), a * rho * rho + shift};
}

}  // namespace growshell::test_support
