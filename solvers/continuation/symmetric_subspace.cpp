#include "solvers/continuation/symmetric_subspace.hpp"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "solvers/stability/subspace_rigid_motions.hpp"

namespace growshell {

namespace {

/// The eigenvectors (ascending eigenvalues) of sum_v d_v d_v^T, d_v = x_v - x_{image[v]}: the
/// directions in which a state differs from its image under g, largest last.
Eigen::Matrix3d difference_directions(const Eigen::Ref<const Eigen::VectorXd>& x,
                                      const VertexSymmetry& g) {
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (Eigen::Index v = 0; v < x.size() / 3; ++v) {
    const Eigen::Vector3d d =
        x.segment<3>(3 * v) - x.segment<3>(3 * g.image[static_cast<std::size_t>(v)]);
    scatter += d * d.transpose();
  }
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvectors();
}

}  // namespace

SymmetricSubspace::SymmetricSubspace(Eigen::Index vertex_count,
                                     const std::vector<VertexSymmetry>& generators)
    : group_(vertex_count, generators) {
  basis_ = group_.class_basis(std::vector<int>(generators.size(), 1));
}

Eigen::VectorXd SymmetricSubspace::restrict_to(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  if (x.size() != full_dimension())
    throw std::invalid_argument("SymmetricSubspace::restrict_to: need " +
                                std::to_string(full_dimension()) + " entries");
  return basis_.transpose() * x;
}

Eigen::VectorXd SymmetricSubspace::expand(const Eigen::Ref<const Eigen::VectorXd>& y) const {
  if (y.size() != dimension())
    throw std::invalid_argument("SymmetricSubspace::expand: need " + std::to_string(dimension()) +
                                " entries");
  return basis_ * y;
}

double SymmetricSubspace::asymmetry(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  const Eigen::VectorXd symmetric = expand(restrict_to(x));
  return (x - symmetric).lpNorm<Eigen::Infinity>();
}

std::vector<Eigen::Index> SymmetricSubspace::rigid_motion_pins(
    const Eigen::Ref<const Eigen::VectorXd>& x) const {
  if (x.size() != full_dimension())
    throw std::invalid_argument("SymmetricSubspace::rigid_motion_pins: need " +
                                std::to_string(full_dimension()) + " entries");
  return subspace_rigid_motions(basis_, x).pins;
}

void SymmetricSubspace::set_pin_configuration(const Eigen::Ref<const Eigen::VectorXd>& x) {
  if (x.size() != full_dimension())
    throw std::invalid_argument("SymmetricSubspace::set_pin_configuration: need " +
                                std::to_string(full_dimension()) + " entries");
  const double extent = std::max(1.0, x.cwiseAbs().maxCoeff());
  if (!(asymmetry(x) <= 1e-9 * extent))
    throw std::invalid_argument(
        "SymmetricSubspace::set_pin_configuration: the configuration is " +
        std::to_string(asymmetry(x)) + " off the subspace, not a symmetric one");
  pin_configuration_ = x;
}

std::vector<Eigen::Index> SymmetricSubspace::trace_pins(
    const Eigen::Ref<const Eigen::VectorXd>& x) const {
  return pin_configuration_.size() > 0 ? rigid_motion_pins(pin_configuration_)
                                       : rigid_motion_pins(x);
}

RigidMotion SymmetricSubspace::aligning_motion(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  if (x.size() != full_dimension())
    throw std::invalid_argument("SymmetricSubspace::aligning_motion: need " +
                                std::to_string(full_dimension()) + " entries");
  const Eigen::Index nv = x.size() / 3;
  if (group_.generators().size() == 1 && (group_.generators()[0].signs.array() < 0.0).count() == 2)
    return half_turn_aligning_motion(x);
  std::vector<int> axes;
  std::vector<Eigen::Vector3d> normals;
  for (const VertexSymmetry& g : group_.generators()) {
    if ((g.signs.array() < 0.0).count() != 1)
      throw std::invalid_argument(
          "SymmetricSubspace::aligning_motion: every generator must be a mirror (one sign -1)");
    int axis = 0;
    g.signs.minCoeff(&axis);
    if (std::find(axes.begin(), axes.end(), axis) != axes.end())
      throw std::invalid_argument("SymmetricSubspace::aligning_motion: two mirrors about axis " +
                                  std::to_string(axis));
    Eigen::Vector3d n = difference_directions(x, g).col(2);
    if (n(axis) < 0.0) n = -n;
    axes.push_back(axis);
    normals.push_back(n);
  }
  RigidMotion motion;
  if (axes.size() == 1) {
    motion.rotation = Eigen::Quaterniond::FromTwoVectors(normals[0], Eigen::Vector3d::Unit(axes[0]))
                          .toRotationMatrix();
  } else if (axes.size() >= 2) {
    // Rows of R: the first two normals (Gram-Schmidt) and their cross product, placed at their
    // axes and signed so that det R = +1; a third mirror's normal then follows.
    const Eigen::Vector3d a = normals[0].normalized();
    const Eigen::Vector3d b = (normals[1] - normals[1].dot(a) * a).normalized();
    const int third = 3 - axes[0] - axes[1];
    motion.rotation.row(axes[0]) = a.transpose();
    motion.rotation.row(axes[1]) = b.transpose();
    motion.rotation.row(third) = a.cross(b).transpose();
    if (motion.rotation.determinant() < 0.0) motion.rotation.row(third) *= -1.0;
  }
  // Centre along each mirror axis: a symmetric vertex set has its mean on the mirror plane.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (Eigen::Index v = 0; v < nv; ++v) mean += motion.rotation * x.segment<3>(3 * v);
  mean /= static_cast<double>(nv);
  for (const int axis : axes) motion.translation(axis) = -mean(axis);
  return motion;
}

RigidMotion SymmetricSubspace::half_turn_aligning_motion(
    const Eigen::Ref<const Eigen::VectorXd>& x) const {
  const VertexSymmetry& g = group_.generators()[0];
  int axis = 0;
  g.signs.maxCoeff(&axis);
  // For a state with the half turn about the line c + t u, x_v - x_image(v) = 2 P(x_v - c),
  // P the projector onto the plane normal to u: the differences span that plane, and u is
  // the direction in which they have no extent.
  const Eigen::Index nv = x.size() / 3;
  Eigen::Vector3d u = difference_directions(x, g).col(0);
  if (u(axis) < 0.0) u = -u;
  RigidMotion motion;
  motion.rotation =
      Eigen::Quaterniond::FromTwoVectors(u, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
  // Centre across the axis: a vertex set with the half turn has its mean on the axis.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (Eigen::Index v = 0; v < nv; ++v) mean += motion.rotation * x.segment<3>(3 * v);
  mean /= static_cast<double>(nv);
  for (int c = 0; c < 3; ++c)
    if (c != axis) motion.translation(c) = -mean(c);
  return motion;
}

SymmetricSubspace mirror_subspace(const ShellModel& model, const std::vector<int>& axes,
                                  double tolerance) {
  if (axes.empty()) throw std::invalid_argument("mirror_subspace: no mirror axes");
  for (std::size_t k = 0; k < axes.size(); ++k)
    for (std::size_t l = 0; l < k; ++l)
      if (axes[k] == axes[l])
        throw std::invalid_argument("mirror_subspace: axis " + std::to_string(axes[k]) +
                                    " given twice");
  const Eigen::VectorXd& X = model.reference_positions();
  const Eigen::Index nv = X.size() / 3;
  const Eigen::MatrixX3d points =
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), nv, 3);
  std::vector<VertexSymmetry> mirrors;
  for (const int axis : axes) {
    mirrors.push_back(mirror_symmetry(points, axis, tolerance));
    check_maps_faces_onto_faces(model.topology(), mirrors.back());
  }
  SymmetricSubspace subspace(nv, mirrors);
  subspace.set_pin_configuration(X);
  return subspace;
}

SymmetricSubspace two_mirror_subspace(const ShellModel& model, double tolerance) {
  return mirror_subspace(model, {0, 1}, tolerance);
}

SymmetricSubspace half_turn_subspace(const ShellModel& model, double tolerance) {
  const Eigen::VectorXd& X = model.reference_positions();
  const Eigen::Index nv = X.size() / 3;
  const Eigen::MatrixX3d points =
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), nv, 3);
  const VertexSymmetry half_turn = half_turn_symmetry(points, 2, tolerance);
  check_maps_faces_onto_faces(model.topology(), half_turn);
  // No pin configuration: the pins are chosen at each trace's start (see the header).
  return SymmetricSubspace(nv, {half_turn});
}

std::string subspace_start_mismatch(const SymmetricSubspace& subspace,
                                    const Eigen::Ref<const Eigen::VectorXd>& x,
                                    double max_asymmetry, const std::string& branch) {
  const double asymmetry = subspace.aligned_asymmetry(x);
  if (asymmetry <= max_asymmetry) return "";
  char note[300];
  std::snprintf(note, sizeof note,
                " is traced in the full space: its start is %.3g m off its image under the "
                "subspace's symmetry in every frame (more than %.3g m)",
                asymmetry, max_asymmetry);
  return branch + note;
}

}  // namespace growshell
