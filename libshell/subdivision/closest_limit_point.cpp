#include "libshell/subdivision/closest_limit_point.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "libshell/subdivision/limit_surface.hpp"

namespace growshell {
namespace {

constexpr int kMaxIterations = 50;
constexpr int kMaxHalvings = 40;
constexpr double kStepTolerance = 1e-14;
constexpr double kGradientTolerance = 1e-13;

/// Outward normals (in the parameter plane) of the sides v = 0, w = 0 and v + w = 1, and the
/// directions along them.
const std::array<Eigen::Vector2d, 3> kOutward = {Eigen::Vector2d(-1.0, 0.0),
                                                 Eigen::Vector2d(0.0, -1.0),
                                                 Eigen::Vector2d(1.0, 1.0)};
const std::array<Eigen::Vector2d, 3> kAlong = {Eigen::Vector2d(0.0, 1.0), Eigen::Vector2d(1.0, 0.0),
                                               Eigen::Vector2d(1.0, -1.0) / std::sqrt(2.0)};

/// Slack of side k at xi (>= 0 inside the triangle).
double slack(const Eigen::Vector2d& xi, int k) {
  if (k == 0) return xi.x();
  if (k == 1) return xi.y();
  return 1.0 - xi.x() - xi.y();
}

/// xi with coordinates within rounding of a side put on it.
Eigen::Vector2d snap(Eigen::Vector2d xi) {
  constexpr double eps = 4.0 * std::numeric_limits<double>::epsilon();
  if (xi.x() < eps) xi.x() = 0.0;
  if (xi.y() < eps) xi.y() = 0.0;
  if (xi.x() + xi.y() > 1.0 - eps) {
    const double s = xi.x() + xi.y();
    xi.x() = std::min(1.0, xi.x() / s);
    xi.y() = 1.0 - xi.x();
  }
  return xi;
}

struct LocalQuadratic {
  Eigen::Vector3d position, residual;
  Eigen::Matrix<double, 3, 2> tangents;
  double value = 0.0;
  Eigen::Vector2d gradient;
  Eigen::Matrix2d hessian, metric;
};

LocalQuadratic local_quadratic(const ControlPointRows& positions, const LoopPatch& patch,
                               const Eigen::Vector3d& point, const Eigen::Vector2d& xi) {
  const LimitSurfacePoint s = evaluate_limit_surface(positions, patch, xi.x(), xi.y());
  LocalQuadratic q;
  q.position = s.position;
  q.residual = point - s.position;
  q.tangents = s.tangents;
  q.value = 0.5 * q.residual.squaredNorm();
  q.gradient = -s.tangents.transpose() * q.residual;
  q.metric = s.tangents.transpose() * s.tangents;
  Eigen::Matrix2d curvature;
  curvature << q.residual.dot(s.second.col(0)), q.residual.dot(s.second.col(2)),
      q.residual.dot(s.second.col(2)), q.residual.dot(s.second.col(1));
  q.hessian = q.metric - curvature;
  return q;
}

double half_squared_distance(const ControlPointRows& positions, const LoopPatch& patch,
                             const Eigen::Vector3d& point, const Eigen::Vector2d& xi) {
  const LimitSurfacePoint s = evaluate_limit_surface(positions, patch, xi.x(), xi.y());
  return 0.5 * (point - s.position).squaredNorm();
}

/// True if the symmetric matrix is positive definite with a margin relative to its size.
bool positive_definite(const Eigen::MatrixXd& m) {
  if (m.rows() == 0) return true;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(m, Eigen::EigenvaluesOnly);
  const double largest = eig.eigenvalues().cwiseAbs().maxCoeff();
  return eig.eigenvalues().minCoeff() > 1e-12 * largest;
}

}  // namespace

Eigen::Vector2d clamp_to_parameter_triangle(const Eigen::Ref<const Eigen::Vector2d>& parameter) {
  const Eigen::Vector2d p = parameter;
  if (p.x() >= 0.0 && p.y() >= 0.0 && p.x() + p.y() <= 1.0) return p;
  const std::array<Eigen::Vector2d, 3> corners = {Eigen::Vector2d(0.0, 0.0),
                                                  Eigen::Vector2d(1.0, 0.0),
                                                  Eigen::Vector2d(0.0, 1.0)};
  Eigen::Vector2d best = corners[0];
  double best_distance = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d& a = corners[static_cast<std::size_t>(k)];
    const Eigen::Vector2d& b = corners[static_cast<std::size_t>((k + 1) % 3)];
    const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    const Eigen::Vector2d q = a + t * (b - a);
    const double d = (p - q).squaredNorm();
    if (d < best_distance) {
      best_distance = d;
      best = q;
    }
  }
  return snap(best);
}

ClosestLimitPoint closest_limit_point(const ControlPointRows& positions, const LoopPatch& patch,
                                      const Eigen::Ref<const Eigen::Vector3d>& point,
                                      const Eigen::Ref<const Eigen::Vector2d>& start) {
  if (!point.allFinite())
    throw std::invalid_argument("closest_limit_point: the point is not finite");
  if (!start.allFinite())
    throw std::invalid_argument("closest_limit_point: the start parameter is not finite");
  const Eigen::Vector3d p = point;
  ClosestLimitPoint result;
  Eigen::Vector2d xi = clamp_to_parameter_triangle(start);
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    const LocalQuadratic q = local_quadratic(positions, patch, p, xi);
    result.iterations = iteration + 1;
    const double scale = q.tangents.norm() * (q.residual.norm() + p.cwiseAbs().maxCoeff() +
                                              q.tangents.norm());
    // The sides that bind: the point lies on them and the descent direction leaves through
    // them; then also those that the step itself would leave through.
    int active = 0;
    for (int k = 0; k < 3; ++k)
      if (slack(xi, k) <= 0.0 && -q.gradient.dot(kOutward[static_cast<std::size_t>(k)]) >
                                     kGradientTolerance * scale)
        active |= 1 << k;
    Eigen::Vector2d step = Eigen::Vector2d::Zero();
    double projected_gradient = 0.0;
    for (int round = 0; round < 3; ++round) {
      const int count = (active & 1) + ((active >> 1) & 1) + ((active >> 2) & 1);
      Eigen::MatrixXd z(2, std::max(0, 2 - count));
      if (count == 0) z = Eigen::Matrix2d::Identity();
      if (count == 1)
        for (int k = 0; k < 3; ++k)
          if (active & (1 << k)) z.col(0) = kAlong[static_cast<std::size_t>(k)];
      if (z.cols() == 0) {
        step.setZero();
        projected_gradient = 0.0;
        break;
      }
      const Eigen::VectorXd zg = z.transpose() * q.gradient;
      projected_gradient = zg.norm();
      Eigen::MatrixXd h = z.transpose() * q.hessian * z;
      if (!positive_definite(h)) h = z.transpose() * q.metric * z;
      step = -z * h.ldlt().solve(zg);
      int leaving = 0;
      for (int k = 0; k < 3; ++k)
        if (!(active & (1 << k)) && slack(xi, k) <= 0.0 &&
            step.dot(kOutward[static_cast<std::size_t>(k)]) > 0.0)
          leaving |= 1 << k;
      if (leaving == 0) break;
      active |= leaving;
      step.setZero();
    }
    result.active = active;
    if (projected_gradient <= kGradientTolerance * scale || step.norm() == 0.0) {
      result.converged = true;
      break;
    }
    // The longest feasible fraction of the step, then halvings until D falls.
    double alpha = 1.0;
    for (int k = 0; k < 3; ++k) {
      const double rate = step.dot(kOutward[static_cast<std::size_t>(k)]);
      if (!(active & (1 << k)) && rate > 0.0) {
        alpha = std::min(alpha, std::max(0.0, slack(xi, k)) / rate);
      }
    }
    // D is known only to the rounding of r = p - x; near the minimum Newton's decrease falls
    // below it, so a step that raises D by no more than that rounding is accepted too.
    const double slope = q.gradient.dot(step);
    const double rounding =
        16.0 * std::numeric_limits<double>::epsilon() *
        (q.residual.norm() * (p.cwiseAbs().maxCoeff() + q.position.cwiseAbs().maxCoeff()) +
         q.value);
    bool accepted = false;
    Eigen::Vector2d next = xi;
    for (int halving = 0; halving <= kMaxHalvings; ++halving, alpha *= 0.5) {
      next = snap(xi + alpha * step);
      const double value = half_squared_distance(positions, patch, p, next);
      if (value <= q.value + 1e-4 * alpha * slope + rounding) {
        accepted = true;
        break;
      }
    }
    if (!accepted) {
      // No step lowers D: at its minimum to rounding if the gradient is small there.
      result.converged = projected_gradient <= 1e3 * kGradientTolerance * scale;
      break;
    }
    const double moved = (next - xi).norm();
    xi = next;
    if (moved <= kStepTolerance) {
      result.converged = true;
      break;
    }
  }
  const LimitSurfacePoint s = evaluate_limit_surface(positions, patch, xi.x(), xi.y());
  result.parameter = xi;
  result.position = s.position;
  result.half_squared_distance = 0.5 * (p - s.position).squaredNorm();
  return result;
}

}  // namespace growshell
