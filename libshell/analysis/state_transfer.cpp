#include "libshell/analysis/state_transfer.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>

#include "libshell/analysis/state_evaluator.hpp"

namespace growshell {

Eigen::VectorXd transfer_state(const ShellModel& from, const Eigen::Ref<const Eigen::VectorXd>& x,
                               const ShellModel& to, double turn) {
  if (!std::isfinite(turn)) throw std::invalid_argument("transfer_state: the turn must be finite");
  // Checks the size and finiteness of x.
  const StateEvaluator y = sheet_state_evaluator(from, x);
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d c(to.settings().growth.center.x(), to.settings().growth.center.y(), 0.0);
  const Eigen::VectorXd& X = to.reference_positions();
  Eigen::VectorXd out(to.dimension());
  for (Eigen::Index v = 0; v < to.dimension() / 3; ++v) {
    const Eigen::Vector3d Xv(X(3 * v), X(3 * v + 1), 0.0);
    out.segment<3>(3 * v) = Q * y(c + Q.transpose() * (Xv - c));
  }
  return out;
}

}  // namespace growshell
