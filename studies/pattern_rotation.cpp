#include "studies/pattern_rotation.hpp"

#include <Eigen/Dense>

namespace growshell {

Eigen::VectorXd pattern_rotation(const ShellModel& model,
                                 const Eigen::Ref<const Eigen::VectorXd>& x,
                                 const std::vector<Eigen::Index>& pinned) {
  const Eigen::VectorXd& X = model.reference_positions();
  const Eigen::Vector3d c = model.settings().growth.center;
  Eigen::VectorXd out = Eigen::VectorXd::Zero(x.size());
  for (Eigen::Index v = 0; v < x.size() / 3; ++v) {
    const auto& ring = model.topology().one_ring(static_cast<int>(v));
    if (ring.size() < 2) continue;
    Eigen::Matrix2d XtX = Eigen::Matrix2d::Zero();
    Eigen::Matrix<double, 3, 2> xtX = Eigen::Matrix<double, 3, 2>::Zero();
    for (const int u : ring) {
      const Eigen::Vector2d dX = X.segment<2>(3 * u) - X.segment<2>(3 * v);
      const Eigen::Vector3d dx = x.segment<3>(3 * u) - x.segment<3>(3 * v);
      XtX += dX * dX.transpose();
      xtX += dx * dX.transpose();
    }
    const Eigen::Matrix<double, 3, 2> F = xtX * XtX.inverse();
    const Eigen::Vector2d R = X.segment<2>(3 * v) - c.head<2>();
    const Eigen::Vector3d r = x.segment<3>(3 * v) - c;
    out.segment<3>(3 * v) =
        Eigen::Vector3d(-r.y(), r.x(), 0.0) - F * Eigen::Vector2d(-R.y(), R.x());
  }
  for (const Eigen::Index d : pinned) out(d) = 0.0;
  return out;
}

}  // namespace growshell
