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

}  // namespace
}  // namespace growshell
