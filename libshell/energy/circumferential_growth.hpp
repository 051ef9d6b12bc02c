#pragma once
/// \file
/// Circumferential growth about an axis: the growth tensor G(phi_e) and the target metric.

#include <Eigen/Core>
#include <numbers>

namespace growshell {

/// Growth only along circles about `center` (a point of the reference plane z = 0, metres):
///   G = e_r (x) e_r + lambda e_phi (x) e_phi,  lambda = 1 + phi_e / (2 pi),
/// which equals inserting a wedge of angle phi_e (the excess angle, radians) into the sheet.
/// Thickness does not grow. For a curved reference the radial direction is the projection of
/// X - center onto the tangent plane.
///
/// With smoothing_radius epsilon > 0 the excess angle rises from 0 at the centre to phi_e
/// over a disc of radius about epsilon: lambda(r) = 1 + w(r) phi_e / (2 pi), with the weight
/// w(r) of the smoothing profile. The grown metric then has no point singularity: its
/// Gaussian curvature -phi_e is spread over r ~ epsilon instead of sitting at the centre.
enum class GrowthSmoothingProfile {
  /// w = r^2 / (r^2 + epsilon^2): half the excess angle at r = epsilon, a deficit
  /// epsilon^2 / r^2 far away (the growth differs from the singular one everywhere).
  Rational,
  /// w = 1 - exp(-r^2 / epsilon^2): 63 % at r = epsilon, equal to the singular growth to
  /// 1e-4 beyond r = 3 epsilon (the growth is changed only inside the core).
  Gaussian,
};

struct CircumferentialGrowth {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double smoothing_radius = 0.0;  ///< epsilon (m), >= 0; 0 = growth singular at the centre
  GrowthSmoothingProfile smoothing_profile = GrowthSmoothingProfile::Rational;
};

/// Circumferential stretch lambda = 1 + phi_e / (2 pi) (dimensionless).
inline double circumferential_stretch(double excess_angle) {
  return 1.0 + excess_angle / (2.0 * std::numbers::pi);
}

/// Weight w(r) of the excess angle at distance r (m) from the centre, of the growth's
/// smoothing profile; 1 for epsilon = 0.
double excess_angle_weight(const CircumferentialGrowth& growth, double r);

/// What the target metric at one reference point is made of, apart from phi_e: the reference
/// metric A^T A, the covariant components t_a = e_phi . A_a of the circumferential unit vector
/// (zero on the axis, where the growth is undefined) and the weight w(r) of the excess angle.
struct TargetMetricParts {
  Eigen::Matrix2d reference_metric = Eigen::Matrix2d::Identity();
  Eigen::Vector2d circumferential = Eigen::Vector2d::Zero();
  double weight = 0.0;
};

/// The parts at reference point X with reference tangents A (as target_metric).
TargetMetricParts target_metric_parts(const CircumferentialGrowth& growth, const Eigen::Vector3d& X,
                                      const Eigen::Matrix<double, 3, 2>& A);

/// abar = A^T A + (lambda^2 - 1) t t^T, lambda = 1 + w phi_e / (2 pi), from the parts: a few
/// flops (inline: assembly calls it at every quadrature point), bit for bit what
/// target_metric returns at the same point.
inline Eigen::Matrix2d target_metric(const TargetMetricParts& parts, double excess_angle) {
  const double lambda = circumferential_stretch(parts.weight * excess_angle);
  return parts.reference_metric +
         (lambda * lambda - 1.0) * parts.circumferential * parts.circumferential.transpose();
}

/// d abar / d phi_e = (lambda w / pi) t t^T from the parts.
inline Eigen::Matrix2d target_metric_excess_angle_derivative(const TargetMetricParts& parts,
                                                             double excess_angle) {
  const double lambda = circumferential_stretch(parts.weight * excess_angle);
  return (lambda * parts.weight / std::numbers::pi) * parts.circumferential *
         parts.circumferential.transpose();
}

/// Target (grown) metric abar_ab = (G A_a) . (G A_b) at reference point X with reference
/// tangents A = [A_1 A_2] (covariant basis of the parameter coordinates, metres):
///   abar = A^T A + (lambda^2 - 1) t t^T,  t_a = e_phi . A_a,  lambda = lambda(r).
/// At X on the axis (no circumferential direction) the growth is undefined; abar = A^T A there.
Eigen::Matrix2d target_metric(const CircumferentialGrowth& growth, const Eigen::Vector3d& X,
                              const Eigen::Matrix<double, 3, 2>& A, double excess_angle);

/// d abar / d phi_e = (lambda w / pi) t t^T, same conventions as target_metric.
Eigen::Matrix2d target_metric_excess_angle_derivative(const CircumferentialGrowth& growth,
                                                      const Eigen::Vector3d& X,
                                                      const Eigen::Matrix<double, 3, 2>& A,
                                                      double excess_angle);

}  // namespace growshell
