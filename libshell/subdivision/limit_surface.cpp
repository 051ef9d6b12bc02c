#include "libshell/subdivision/limit_surface.hpp"

#include <Eigen/Geometry>

namespace growshell {

LimitSurfacePoint evaluate_limit_surface(const ControlPointRows& positions, const LoopPatch& patch,
                                         const PatchBasis& basis) {
  Eigen::MatrixX3d X(patch.size(), 3);
  for (int i = 0; i < patch.size(); ++i) X.row(i) = positions.row(patch.control[static_cast<std::size_t>(i)]);
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

LimitSurfacePoint evaluate_limit_surface(const ControlPointRows& positions, const LoopPatch& patch,
                                         double v, double w) {
  return evaluate_limit_surface(positions, patch, evaluate_patch_basis(patch, v, w));
}

}  // namespace growshell
