#include "libshell/subdivision/limit_surface.hpp"

#include <Eigen/Geometry>

#include "libshell/subdivision/loop_basis.hpp"

namespace growshell {

LimitSurfacePoint evaluate_limit_surface(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                         const std::array<int, 12>& control, double v, double w) {
  const LoopBasisValues basis = evaluate_regular_loop_basis(v, w);
  Eigen::Matrix<double, 12, 3> X;
  for (int i = 0; i < 12; ++i) X.row(i) = positions.row(control[i]);
  LimitSurfacePoint p;
  p.position = X.transpose() * basis.value;
  p.tangents = X.transpose() * basis.first;
  p.second = X.transpose() * basis.second;
  p.normal = p.tangents.col(0).cross(p.tangents.col(1)).normalized();
  p.metric = p.tangents.transpose() * p.tangents;
  p.curvature_tensor << p.second.col(0).dot(p.normal), p.second.col(2).dot(p.normal),
      p.second.col(2).dot(p.normal), p.second.col(1).dot(p.normal);
  const Eigen::Matrix2d shape = p.metric.inverse() * p.curvature_tensor;
  p.mean_curvature = 0.5 * shape.trace();
  p.gaussian_curvature = p.curvature_tensor.determinant() / p.metric.determinant();
  return p;
}

}  // namespace growshell
