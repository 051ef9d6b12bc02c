#pragma once
/// \file
/// A rigid motion p -> R p + t applied to vertex-major states (3 entries per vertex), and the
/// infinitesimal rigid motions of a state.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/QR>
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

/// The six rigid velocity fields of the state x (3 entries per vertex), as columns: the
/// translations along x, y, z, then the rotations about the axes through `centre`,
/// e_c x (p - centre) at each vertex p. Not normalised.
inline Eigen::MatrixXd rigid_velocity_fields(const Eigen::Ref<const Eigen::VectorXd>& x,
                                             const Eigen::Vector3d& centre = Eigen::Vector3d::Zero()) {
  if (x.size() % 3 != 0)
    throw std::invalid_argument("rigid_velocity_fields: a state needs 3 entries per vertex");
  Eigen::MatrixXd fields = Eigen::MatrixXd::Zero(x.size(), 6);
  for (Eigen::Index v = 0; v < x.size() / 3; ++v) {
    const Eigen::Vector3d p = x.segment<3>(3 * v) - centre;
    for (int c = 0; c < 3; ++c) {
      fields(3 * v + c, c) = 1.0;
      fields.block<3, 1>(3 * v, 3 + c) = Eigen::Vector3d(Eigen::Vector3d::Unit(c)).cross(p);
    }
  }
  return fields;
}

/// v (3 entries per vertex) without its part along the six rigid velocity fields of the state
/// x: v minus its orthogonal projection onto their span. E.g. the modes of a Hessian held by
/// pins carry a rigid motion that the pins pick; without it a mode of a symmetric state lies
/// in a class of the symmetry up to the pins' other effects. Throws as rigid_velocity_fields,
/// if v and x differ in size, and for fewer than 3 vertices.
inline Eigen::VectorXd without_rigid_velocity(const Eigen::Ref<const Eigen::VectorXd>& x,
                                              const Eigen::Ref<const Eigen::VectorXd>& v) {
  if (v.size() != x.size())
    throw std::invalid_argument("without_rigid_velocity: the state and the vector differ in size");
  if (x.size() < 9)
    throw std::invalid_argument("without_rigid_velocity: a state needs at least 3 vertices");
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < x.size() / 3; ++i) centre += x.segment<3>(3 * i);
  centre /= static_cast<double>(x.size() / 3);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(rigid_velocity_fields(x, centre));
  const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(x.size(), 6);
  return v - Q * (Q.transpose() * v);
}

}  // namespace growshell
