// pattern_orientation and pattern_phase_functional: the orientation of an n-fold out-of-plane
// pattern, exact where the mesh has the pattern's mirrors and to the mesh's quadrature error on a
// mesh with no symmetry; the functional vanishes on the state that sets it and measures a turn
// of the pattern to first order.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/mesh/gmsh_disc_mesh.hpp"
#include "libshell/mesh/ring_disc_mesh.hpp"
#include "studies/pattern_phase.hpp"

namespace growshell {
namespace {

ShellModel rings_model() {
  RingDiscMeshOptions o;
  o.size_slope = 0.25;
  o.size_floor = 0.05;
  return ShellModel(make_ring_disc_mesh(o), ShellModelSettings{});
}

ShellModel fine_gmsh_model() {
  GmshDiscMeshOptions o;
  o.size_slope = 0.15;
  o.size_floor = 0.03;
  return ShellModel(make_gmsh_disc_mesh(o), ShellModelSettings{});
}

/// The reference with z = r^2 cos(n (theta - theta0)).
Eigen::VectorXd pattern(const ShellModel& model, int n, double theta0) {
  Eigen::VectorXd x = model.reference_positions();
  for (Eigen::Index v = 0; v < x.size() / 3; ++v) {
    const double X = x(3 * v), Y = x(3 * v + 1);
    x(3 * v + 2) = (X * X + Y * Y) * std::cos(n * (std::atan2(Y, X) - theta0));
  }
  return x;
}

TEST(PatternOrientation, IsExactOnTheMirrorsOfTheRingsMesh) {
  const ShellModel model = rings_model();
  const Eigen::VectorXd none = Eigen::VectorXd::Zero(model.dimension());
  EXPECT_NEAR(pattern_orientation(model, pattern(model, 2, 0.0), none, 2), 0.0, 1e-13);
  EXPECT_NEAR(pattern_orientation(model, pattern(model, 2, std::numbers::pi / 4), none, 2),
              std::numbers::pi / 4, 1e-13);
  // A pattern at a general angle: the mesh's 4-fold harmonics bias the discrete Fourier
  // component slightly.
  EXPECT_NEAR(pattern_orientation(model, pattern(model, 2, 0.3), none, 2), 0.3, 2e-2);
  EXPECT_NEAR(pattern_orientation(model, pattern(model, 3, 0.2), none, 3), 0.2, 2e-2);
}

TEST(PatternOrientation, FallsBackOnTheDirectionForTheFlatSheet) {
  const ShellModel model = fine_gmsh_model();
  const Eigen::VectorXd flat = model.reference_positions();
  const Eigen::VectorXd mode = pattern(model, 2, -0.4) - flat;
  EXPECT_NEAR(pattern_orientation(model, flat, mode, 2), -0.4, 2e-2);
  EXPECT_THROW(pattern_orientation(model, flat, Eigen::VectorXd::Zero(model.dimension()), 2),
               std::invalid_argument);
  EXPECT_THROW(pattern_orientation(model, flat, mode, 0), std::invalid_argument);
  EXPECT_THROW(pattern_orientation(model, flat.head(9), mode, 2), std::invalid_argument);
}

TEST(PatternPhaseFunctional, VanishesOnItsStateAndMeasuresATurn) {
  const ShellModel model = fine_gmsh_model();
  const Eigen::VectorXd none = Eigen::VectorXd::Zero(model.dimension());
  const double theta0 = pattern_orientation(model, pattern(model, 2, 0.7), none, 2);
  const Eigen::VectorXd x = pattern(model, 2, theta0);
  const Eigen::VectorXd c = pattern_phase_functional(model, x, none, 2);
  double sum = 0.0;  // sum A_i r_i^2 cos^2: the scale of c . x for a turned pattern
  for (const int v : model.sheet_vertices())
    sum += std::abs(c(3 * v + 2)) * x.segment<2>(3 * v).squaredNorm();
  EXPECT_NEAR(c.dot(x), 0.0, 1e-12 * sum);
  // Turned by alpha the pattern gives c . x ~ sin(2 alpha) sum A r^2 sin^2 / ..., first order
  // in alpha, with the sign of the turn.
  const double alpha = 1e-3;
  const double turned = c.dot(pattern(model, 2, theta0 + alpha));
  const double back = c.dot(pattern(model, 2, theta0 - alpha));
  EXPECT_GT(std::abs(turned), 1e-4 * sum);
  EXPECT_NEAR(turned, -back, 1e-3 * std::abs(turned));
  // Only the out-of-plane components of sheet vertices enter.
  for (Eigen::Index v = 0; v < x.size() / 3; ++v) {
    EXPECT_EQ(c(3 * v), 0.0);
    EXPECT_EQ(c(3 * v + 1), 0.0);
  }
}

}  // namespace
}  // namespace growshell
