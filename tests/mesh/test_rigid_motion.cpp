// rigid_velocity_fields: the six infinitesimal rigid motions of a state are the derivatives of
// finite rigid motions (RigidMotion) at the identity: a small translation or rotation about
// the stated centre moves every vertex by the field times the amount, to second order.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <stdexcept>

#include "libshell/mesh/rigid_motion.hpp"

namespace growshell {
namespace {

TEST(RigidVelocityFields, AreTheDerivativesOfRigidMotionsAboutTheCentre) {
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(12, -0.7, 1.3).array().sin();
  const Eigen::Vector3d centre(0.2, -0.1, 0.4);
  const Eigen::MatrixXd fields = rigid_velocity_fields(x, centre);
  ASSERT_EQ(fields.rows(), 12);
  ASSERT_EQ(fields.cols(), 6);
  const double eps = 1e-6;
  for (int c = 0; c < 3; ++c) {
    RigidMotion shift;
    shift.translation = eps * Eigen::Vector3d::Unit(c);
    EXPECT_LT(((shift.apply(x) - x) / eps - fields.col(c)).norm(), 1e-9) << "translation " << c;
    RigidMotion spin;
    spin.rotation = Eigen::AngleAxisd(eps, Eigen::Vector3d::Unit(c)).toRotationMatrix();
    spin.translation = centre - spin.rotation * centre;
    EXPECT_LT(((spin.apply(x) - x) / eps - fields.col(3 + c)).norm(), 1e-5) << "rotation " << c;
  }
}

TEST(RigidVelocityFields, NeedThreeEntriesPerVertex) {
  EXPECT_THROW(rigid_velocity_fields(Eigen::VectorXd::Zero(7)), std::invalid_argument);
}

TEST(WithoutRigidVelocity, RemovesExactlyTheRigidPartOfAVector) {
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(30, -0.7, 1.3).array().sin();
  const Eigen::MatrixXd fields = rigid_velocity_fields(x, Eigen::Vector3d(0.3, 0.1, -0.2));
  // A vector orthogonal to every rigid field, plus a rigid motion about another centre.
  Eigen::VectorXd w = Eigen::VectorXd::LinSpaced(30, 0.4, 2.9).array().cos();
  const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(fields).householderQ() *
                            Eigen::MatrixXd::Identity(30, 6);
  w -= Q * (Q.transpose() * w);
  Eigen::Matrix<double, 6, 1> a;
  a << 0.5, -1.0, 0.25, 2.0, -0.3, 0.7;
  const Eigen::VectorXd v = w + fields * a;
  EXPECT_LT((without_rigid_velocity(x, v) - w).cwiseAbs().maxCoeff(), 1e-14);
  // A rigid field alone has nothing left, and the result is orthogonal to every field.
  EXPECT_LT(without_rigid_velocity(x, fields.col(4)).norm(), 1e-14);
  EXPECT_LT((fields.transpose() * without_rigid_velocity(x, v)).cwiseAbs().maxCoeff(), 1e-13);
}

TEST(WithoutRigidVelocity, RefusesMismatchedSizesAndFewerThanThreeVertices) {
  EXPECT_THROW(without_rigid_velocity(Eigen::VectorXd::Ones(12), Eigen::VectorXd::Ones(9)),
               std::invalid_argument);
  EXPECT_THROW(without_rigid_velocity(Eigen::VectorXd::Ones(6), Eigen::VectorXd::Ones(6)),
               std::invalid_argument);
}

}  // namespace
}  // namespace growshell
