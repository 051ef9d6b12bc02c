// A state carried from one mesh onto another (transfer_state): exact for affine states across
// two mesh families that share no structure, with and without a turn; consistent with the
// mesh's own quarter turn for a curved state; and refusing bad input by name.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/Geometry>

#include "libshell/analysis/state_transfer.hpp"
#include "libshell/mesh/gmsh_disc_mesh.hpp"
#include "libshell/mesh/ring_disc_mesh.hpp"
#include "tests/support/sheet_states.hpp"

namespace growshell {
namespace {

ShellModel rings_model(double scale = 1.0) {
  RingDiscMeshOptions o;
  o.size_slope = 0.3 * scale;
  o.size_floor = 0.05 * scale;
  return ShellModel(make_ring_disc_mesh(o), ShellModelSettings{});
}

ShellModel gmsh_model() {
  GmshDiscMeshOptions o;
  o.size_slope = 0.3;
  o.size_floor = 0.05;
  return ShellModel(make_gmsh_disc_mesh(o), ShellModelSettings{});
}

Eigen::VectorXd affine_state(const ShellModel& model, const Eigen::Matrix3d& A,
                             const Eigen::Vector3d& b) {
  return test_support::map_reference(model, [&](const Eigen::Vector3d& X) { return A * X + b; });
}

/// A curved, sheared state given at the control points.
Eigen::VectorXd cubic_curved_state(const ShellModel& model) {
  return test_support::map_reference(model, [](const Eigen::Vector3d& X) {
    return Eigen::Vector3d(X.x() + 0.1 * X.y() * X.y(), X.y() - 0.2 * X.x() * X.y(),
                           X.x() * X.x() + 0.5 * X.y() * X.y() + 0.3 * X.x() * X.y() * X.y());
  });
}

TEST(StateTransfer, AffineStatesAreCarriedExactlyBetweenFamilies) {
  const ShellModel rings = rings_model();
  const ShellModel gmsh = gmsh_model();
  Eigen::Matrix3d A;
  A << 1.1, 0.2, 0.0, -0.3, 0.9, 0.0, 0.4, -0.7, 1.0;
  const Eigen::Vector3d b(0.3, -0.2, 0.5);
  const Eigen::VectorXd x = affine_state(rings, A, b);
  // Unturned: the affine map of the target's own control points, ghosts included.
  const Eigen::VectorXd onto = transfer_state(rings, x, gmsh);
  ASSERT_EQ(onto.size(), gmsh.dimension());
  EXPECT_LT((onto - affine_state(gmsh, A, b)).lpNorm<Eigen::Infinity>(), 1e-11);
  // Turned by 0.4 rad over the material and in space: X -> Q A Q^T X + Q b.
  const double turn = 0.4;
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::VectorXd turned = transfer_state(rings, x, gmsh, turn);
  EXPECT_LT((turned - affine_state(gmsh, Q * A * Q.transpose(), Q * b)).lpNorm<Eigen::Infinity>(),
            1e-11);
}

TEST(StateTransfer, TurningByASymmetryOfTheMeshPermutesTheTransferredPoints) {
  // The rings mesh maps onto itself under the quarter turn, so the state turned by pi/2 holds
  // at sheet vertex v the unturned transfer at the vertex w with X_w = Q^T X_v, turned by Q.
  // (A rim vertex or ghost lies outside the reference limit surface and takes the continuation
  // of its nearest element, which between equally near ones need not be the quarter-turned
  // choice: those are left out.)
  const ShellModel rings = rings_model();
  const Eigen::VectorXd x = cubic_curved_state(rings);
  const Eigen::VectorXd plain = transfer_state(rings, x, rings);
  const Eigen::VectorXd turned = transfer_state(rings, x, rings, std::numbers::pi / 2);
  const Eigen::Matrix3d Q =
      Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::VectorXd& X = rings.reference_positions();
  const Eigen::Index n = X.size() / 3;
  int matched = 0;
  int inside = 0;
  for (const int v : rings.sheet_vertices()) {
    if (X.segment<2>(3 * v).norm() > 1.0 - 1e-9) continue;
    ++inside;
    const Eigen::Vector3d source = Q.transpose() * X.segment<3>(3 * v);
    for (Eigen::Index w = 0; w < n; ++w) {
      if ((X.segment<3>(3 * w) - source).norm() > 1e-12) continue;
      EXPECT_LT((turned.segment<3>(3 * v) - Q * plain.segment<3>(3 * w)).norm(), 1e-11) << v;
      ++matched;
      break;
    }
  }
  EXPECT_EQ(matched, inside);  // each has its image
  EXPECT_GT(inside, 100);
}

TEST(StateTransfer, ACurvedStateComesBackToWithinTheSmoothingOfTheSubdivision) {
  // Carried onto its own mesh, a curved state's control points move to its limit surface: by
  // O(l^2 curvature), so a quarter as far on a mesh of half the element size.
  double previous = 0.0;
  for (const double scale : {1.0, 0.5}) {
    const ShellModel rings = rings_model(scale);
    const Eigen::VectorXd x = cubic_curved_state(rings);
    const Eigen::VectorXd back = transfer_state(rings, x, rings);
    double worst = 0.0;
    for (const int v : rings.sheet_vertices())
      worst = std::max(worst, (back - x).segment<3>(3 * v).norm());
    EXPECT_GT(worst, 1e-6);  // limit points, not the control points themselves
    if (previous > 0.0) {
      EXPECT_NEAR(previous / worst, 4.0, 1.0) << previous << " -> " << worst;
    }
    previous = worst;
  }
}

TEST(StateTransfer, RefusesBadInputByName) {
  const ShellModel rings = rings_model();
  const Eigen::VectorXd x = rings.reference_positions();
  EXPECT_THROW(transfer_state(rings, x.head(x.size() - 3), rings), std::invalid_argument);
  try {
    transfer_state(rings, x, rings, std::nan(""));
    FAIL() << "a non-finite turn was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("turn"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace growshell
