#include "libshell/energy/circumferential_growth.hpp"

#include <Eigen/Geometry>
#include <numbers>

namespace growshell {
namespace {

/// Covariant components t_a = e_phi . A_a of the circumferential unit vector; zero on the axis.
Eigen::Vector2d circumferential_components(const CircumferentialGrowth& growth,
                                           const Eigen::Vector3d& X,
                                           const Eigen::Matrix<double, 3, 2>& A) {
  const Eigen::Vector3d normal = A.col(0).cross(A.col(1)).normalized();
  Eigen::Vector3d radial = X - growth.center;
  radial -= radial.dot(normal) * normal;
  const double r = radial.norm();
  if (!(r > 0.0)) return Eigen::Vector2d::Zero();
  const Eigen::Vector3d e_phi = normal.cross(radial / r);
  return A.transpose() * e_phi;
}

}  // namespace

double circumferential_stretch(double excess_angle) {
  return 1.0 + excess_angle / (2.0 * std::numbers::pi);
}

Eigen::Matrix2d target_metric(const CircumferentialGrowth& growth, const Eigen::Vector3d& X,
                              const Eigen::Matrix<double, 3, 2>& A, double excess_angle) {
  const Eigen::Vector2d t = circumferential_components(growth, X, A);
  const double lambda = circumferential_stretch(excess_angle);
  return A.transpose() * A + (lambda * lambda - 1.0) * t * t.transpose();
}

Eigen::Matrix2d target_metric_excess_angle_derivative(const CircumferentialGrowth& growth,
                                                      const Eigen::Vector3d& X,
                                                      const Eigen::Matrix<double, 3, 2>& A,
                                                      double excess_angle) {
  const Eigen::Vector2d t = circumferential_components(growth, X, A);
  const double lambda = circumferential_stretch(excess_angle);
  return (lambda / std::numbers::pi) * t * t.transpose();
}

}  // namespace growshell
