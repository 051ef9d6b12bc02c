#include "libshell/energy/circumferential_growth.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace growshell {
namespace {

/// Covariant components t_a = e_phi . A_a of the circumferential unit vector (zero on the
/// axis) and the weight w(r) of the excess angle there.
struct CircumferentialDirection {
  Eigen::Vector2d t = Eigen::Vector2d::Zero();
  double weight = 0.0;
};

CircumferentialDirection circumferential_direction(const CircumferentialGrowth& growth,
                                                   const Eigen::Vector3d& X,
                                                   const Eigen::Matrix<double, 3, 2>& A) {
  const Eigen::Vector3d normal = A.col(0).cross(A.col(1)).normalized();
  Eigen::Vector3d radial = X - growth.center;
  radial -= radial.dot(normal) * normal;
  const double r = radial.norm();
  if (!(r > 0.0)) return {};
  const Eigen::Vector3d e_phi = normal.cross(radial / r);
  return {A.transpose() * e_phi, excess_angle_weight(growth, r)};
}

}  // namespace

double excess_angle_weight(const CircumferentialGrowth& growth, double r) {
  const double eps = growth.smoothing_radius;
  if (eps == 0.0) return 1.0;
  switch (growth.smoothing_profile) {
    case GrowthSmoothingProfile::Gaussian:
      return -std::expm1(-(r / eps) * (r / eps));
    case GrowthSmoothingProfile::Rational:
      break;
  }
  return r * r / (r * r + eps * eps);
}

TargetMetricParts target_metric_parts(const CircumferentialGrowth& growth, const Eigen::Vector3d& X,
                                      const Eigen::Matrix<double, 3, 2>& A) {
  const CircumferentialDirection d = circumferential_direction(growth, X, A);
  return {A.transpose() * A, d.t, d.weight};
}

Eigen::Matrix2d target_metric(const CircumferentialGrowth& growth, const Eigen::Vector3d& X,
                              const Eigen::Matrix<double, 3, 2>& A, double excess_angle) {
  return target_metric(target_metric_parts(growth, X, A), excess_angle);
}

Eigen::Matrix2d target_metric_excess_angle_derivative(const CircumferentialGrowth& growth,
                                                      const Eigen::Vector3d& X,
                                                      const Eigen::Matrix<double, 3, 2>& A,
                                                      double excess_angle) {
  return target_metric_excess_angle_derivative(target_metric_parts(growth, X, A), excess_angle);
}

}  // namespace growshell
