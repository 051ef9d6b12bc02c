// The interpolated state of a ShellModel: exact at the sheet vertices, exact for affine states
// inside and outside the triangulation, and second-order accurate for a curved one.
#include <gtest/gtest.h>

#include <cmath>

#include "libshell/analysis/state_evaluator.hpp"
#include "libshell/mesh/disc_mesh.hpp"

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

TEST(StateEvaluator, SecondOrderForACurvedState) {
  // z = X^2 + Y^2 / 2 at the control points: the limit surface is that paraboloid up to a
  // constant shift of O(spacing^2), and the interpolation error is O(spacing^2) too.
  double previous = 0.0;
  for (int rings : {6, 12}) {
    ShellModel model = disc_model(rings);
    Eigen::VectorXd x = model.reference_positions();
    for (Eigen::Index v = 0; v < x.size() / 3; ++v)
      x(3 * v + 2) = x(3 * v) * x(3 * v) + 0.5 * x(3 * v + 1) * x(3 * v + 1);
    const StateEvaluator y = sheet_state_evaluator(model, x);
    double worst = 0.0;
    for (int k = 0; k < 50; ++k) {
      const double r = 0.8 * std::sqrt((k + 0.5) / 50.0), t = 2.4 * k;
      const Eigen::Vector3d X(r * std::cos(t), r * std::sin(t), 0.0);
      const double exact = X.x() * X.x() + 0.5 * X.y() * X.y();
      worst = std::max(worst, std::abs(y(X).z() - exact));
    }
    if (previous > 0.0) {
      EXPECT_GT(previous / worst, 3.0);  // halving the spacing: ~4x
    }
    EXPECT_LT(worst, 1.5 / (rings * rings));  // measured 0.87 / rings^2
    previous = worst;
  }
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
