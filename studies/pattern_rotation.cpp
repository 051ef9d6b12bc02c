#include "studies/pattern_rotation.hpp"

#include <Eigen/Dense>
#include <stdexcept>
#include <string>

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
  if (pinned.empty()) return out;
  if (pinned.size() != 6)
    throw std::invalid_argument("pattern_rotation: " + std::to_string(pinned.size()) +
                                " pinned dofs; the rigid motions take six");
  // Rigid velocity u_v = w + omega x (x_v - c): its component k at vertex v is
  // e_k . w + ((x_v - c) x e_k) . omega. Six pins, six unknowns (w, omega).
  Eigen::Matrix<double, 6, 6> A;
  Eigen::Matrix<double, 6, 1> b;
  for (int row = 0; row < 6; ++row) {
    const Eigen::Index d = pinned[static_cast<std::size_t>(row)];
    if (d < 0 || d >= x.size())
      throw std::invalid_argument("pattern_rotation: pinned dof " + std::to_string(d) +
                                  " is out of range");
    const Eigen::Index v = d / 3;
    const Eigen::Vector3d e = Eigen::Vector3d::Unit(static_cast<int>(d % 3));
    A.block<1, 3>(row, 0) = e.transpose();
    A.block<1, 3>(row, 3) = (x.segment<3>(3 * v) - c).cross(e).transpose();
    b(row) = -out(d);
  }
  const Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>> lu(A);
  if (lu.rank() < 6)
    throw std::invalid_argument("pattern_rotation: the pinned dofs leave a rigid motion free");
  const Eigen::Matrix<double, 6, 1> rigid = lu.solve(b);
  const Eigen::Vector3d w = rigid.head<3>(), omega = rigid.tail<3>();
  for (Eigen::Index v = 0; v < x.size() / 3; ++v)
    out.segment<3>(3 * v) += w + omega.cross(x.segment<3>(3 * v) - c);
  for (const Eigen::Index d : pinned) out(d) = 0.0;  // round-off
  return out;
}

}  // namespace growshell
