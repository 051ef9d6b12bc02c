// The state of a ShellModel at a material point: exact at the sheet vertices, exact for affine
// states inside and outside the triangulation, and the exact limit surface at any parameter point
// of any element, on a lattice disc and on an unstructured Gmsh disc with irregular vertices.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "libshell/analysis/state_evaluator.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/mesh/gmsh_disc_mesh.hpp"
#include "libshell/subdivision/limit_surface.hpp"

namespace growshell {
namespace {

ShellModel disc_model(int rings) {
  DiscMeshOptions o;
  o.rings = rings;
  return ShellModel(make_disc_mesh(o), ShellModelSettings{});
}

TEST(StateEvaluator, ExactAtVerticesAndForAffineStates) {
  ShellModel model = disc_model(6);
  Eigen::Matrix3d A;
  A << 1.1, 0.2, 0.0, -0.3, 0.9, 0.0, 0.4, -0.7, 1.0;
  const Eigen::Vector3d b(0.3, -0.2, 0.5);
  Eigen::VectorXd x = model.reference_positions();
  for (Eigen::Index v = 0; v < x.size() / 3; ++v) x.segment<3>(3 * v) = A * x.segment<3>(3 * v) + b;
  const StateEvaluator y = sheet_state_evaluator(model, x);
  // Loop limit positions reproduce affine maps, and so does the interpolation, also outside
  // the rim polygon (extrapolation from the nearest triangle).
  for (const Eigen::Vector3d& X : {Eigen::Vector3d(0.0, 0.0, 0.0), Eigen::Vector3d(0.31, -0.42, 0.0),
                                  Eigen::Vector3d(-0.7, 0.69, 0.0), Eigen::Vector3d(1.0, 0.0, 0.0),
                                  Eigen::Vector3d(std::cos(1.0), std::sin(1.0), 0.0)})
    EXPECT_LT((y(X) - (A * X + b)).norm(), 1e-12) << X.transpose();
  const Eigen::MatrixX3d ref = model.limit_positions(model.reference_positions());
  const Eigen::MatrixX3d cur = model.limit_positions(x);
  for (Eigen::Index k = 0; k < ref.rows(); ++k)
    EXPECT_LT((y(ref.row(k).transpose()) - cur.row(k).transpose()).norm(), 1e-12);
}

/// A curved, sheared state: z = X^2 + Y^2 / 2 and an in-plane twist at the control points.
Eigen::VectorXd quadratic_curved_state(const ShellModel& model) {
  Eigen::VectorXd x = model.reference_positions();
  for (Eigen::Index v = 0; v < x.size() / 3; ++v) {
    const double X = x(3 * v), Y = x(3 * v + 1);
    x(3 * v) += 0.1 * Y * Y;
    x(3 * v + 1) -= 0.2 * X * Y;
    x(3 * v + 2) = X * X + 0.5 * Y * Y;
  }
  return x;
}

/// At the reference limit point of each element's parameter points, the evaluator gives the
/// current limit surface at the same parameter point.
double worst_limit_surface_error(const ShellModel& model, const Eigen::VectorXd& x) {
  const StateEvaluator y = sheet_state_evaluator(model, x);
  const Eigen::VectorXd& X = model.reference_positions();
  const auto rows = [](const Eigen::VectorXd& v) {
    return Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(v.data(), v.size() / 3, 3);
  };
  const Eigen::MatrixX3d reference = rows(X), current = rows(x);
  double worst = 0.0;
  for (Eigen::Index e = 0; e < model.num_elements(); e += 3) {
    const LoopPatch& patch = model.patches().patch[static_cast<std::size_t>(e)];
    for (const Eigen::Vector2d& q : {Eigen::Vector2d(1.0 / 3, 1.0 / 3), Eigen::Vector2d(0.1, 0.05),
                                     Eigen::Vector2d(0.7, 0.2), Eigen::Vector2d(0.02, 0.9),
                                     Eigen::Vector2d(0.5, 0.0)}) {
      const Eigen::Vector3d P = evaluate_limit_surface(reference, patch, q(0), q(1)).position;
      const Eigen::Vector3d expected = evaluate_limit_surface(current, patch, q(0), q(1)).position;
      worst = std::max(worst, (y(P) - expected).norm());
    }
  }
  return worst;
}

TEST(StateEvaluator, IsTheLimitSurfaceOnALatticeDisc) {
  const ShellModel model = disc_model(8);
  EXPECT_LT(worst_limit_surface_error(model, quadratic_curved_state(model)), 1e-11);
}

/// A coarse Gmsh disc (size slope 0.3, floor 0.05) with irregular vertices.
ShellModel irregular_gmsh_model() {
  GmshDiscMeshOptions o;
  o.size_slope = 0.3;
  o.size_floor = 0.05;
  return ShellModel(make_gmsh_disc_mesh(o), ShellModelSettings{});
}

TEST(StateEvaluator, IsTheLimitSurfaceOnAnUnstructuredDiscWithIrregularVertices) {
  const ShellModel model = irregular_gmsh_model();
  ASSERT_GT(model.patches().num_irregular(), 10);
  EXPECT_LT(worst_limit_surface_error(model, quadratic_curved_state(model)), 1e-11);
}

// MaterialPointSampling: the points located once, then one sparse product per state, give the
// evaluator's values for two different states, at points inside the reference surface (a
// spiral over the disc) and beyond its rim (to 1.03 R, first-order continuation), on the Gmsh
// disc with irregular vertices.
TEST(StateEvaluator, SamplingFixedMaterialPointsIsTheEvaluator) {
  const ShellModel model = irregular_gmsh_model();
  ASSERT_GT(model.patches().num_irregular(), 10);
  const int n = 200;
  Eigen::MatrixX3d points(n, 3);
  for (int k = 0; k < n; ++k) {
    const double r = 1.03 * (k + 0.5) / n, t = 0.37 * k;
    points.row(k) << r * std::cos(t), r * std::sin(t), 0.0;
  }
  const MaterialPointSampling sampling(model, points);
  EXPECT_EQ(sampling.size(), n);
  Eigen::VectorXd bent = quadratic_curved_state(model);
  for (Eigen::Index i = 2; i < bent.size(); i += 3) bent(i) += 0.3 * std::sin(7.0 * bent(i - 2));
  for (const Eigen::VectorXd& x : {quadratic_curved_state(model), bent}) {
    const StateEvaluator y = sheet_state_evaluator(model, x);
    const Eigen::MatrixX3d sampled = sampling.positions(x);
    double worst = 0.0;
    for (int k = 0; k < n; ++k)
      worst = std::max(worst, (sampled.row(k).transpose() - y(points.row(k).transpose())).norm());
    EXPECT_LT(worst, 1e-13);
  }
  EXPECT_THROW(sampling.positions(Eigen::VectorXd::Zero(7)), std::invalid_argument);
  points(3, 0) = std::nan("");
  EXPECT_THROW(MaterialPointSampling(model, points), std::invalid_argument);
}

TEST(StateEvaluator, RejectsBadStates) {
  ShellModel model = disc_model(3);
  EXPECT_THROW(sheet_state_evaluator(model, Eigen::VectorXd::Zero(5)), std::invalid_argument);
  Eigen::VectorXd x = model.reference_positions();
  x(4) = std::nan("");
  EXPECT_THROW(sheet_state_evaluator(model, x), std::invalid_argument);
}

}  // namespace
}  // namespace growshell
