#pragma once
/// \file
/// A rigid motion p -> R p + t applied to vertex-major states (3 entries per vertex).

#include <Eigen/Core>
#include <stdexcept>

namespace growshell {

struct RigidMotion {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  /// R x_v + t for every vertex of the state x.
  Eigen::VectorXd apply(const Eigen::Ref<const Eigen::VectorXd>& x) const {
    Eigen::VectorXd out = rotate(x);
    for (Eigen::Index v = 0; v < out.size() / 3; ++v) out.segment<3>(3 * v) += translation;
    return out;
  }
  /// R^T (x_v - t): the inverse motion.
  Eigen::VectorXd apply_inverse(const Eigen::Ref<const Eigen::VectorXd>& x) const {
    Eigen::VectorXd out = x;
    for (Eigen::Index v = 0; v < out.size() / 3; ++v) out.segment<3>(3 * v) -= translation;
    return rotate_inverse(out);
  }
  /// R dx_v: a displacement or tangent (no translation).
  Eigen::VectorXd rotate(const Eigen::Ref<const Eigen::VectorXd>& dx) const {
    check(dx);
    Eigen::VectorXd out(dx.size());
    for (Eigen::Index v = 0; v < dx.size() / 3; ++v)
      out.segment<3>(3 * v) = rotation * dx.segment<3>(3 * v);
    return out;
  }
  /// R^T dx_v.
  Eigen::VectorXd rotate_inverse(const Eigen::Ref<const Eigen::VectorXd>& dx) const {
    check(dx);
    Eigen::VectorXd out(dx.size());
    for (Eigen::Index v = 0; v < dx.size() / 3; ++v)
      out.segment<3>(3 * v) = rotation.transpose() * dx.segment<3>(3 * v);
    return out;
  }

 private:
  static void check(const Eigen::Ref<const Eigen::VectorXd>& x) {
    if (x.size() % 3 != 0)
      throw std::invalid_argument("RigidMotion: a state needs 3 entries per vertex");
  }
};

}  // namespace growshell
