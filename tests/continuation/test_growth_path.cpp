// Growing a flat disc into the e-cone: the path lands in the two-fold (n = 2) cone, every
// reported point is a stable equilibrium with vanishing reaction forces at the pins, and the
// tangent predictor is the derivative of the equilibrium with respect to phi_e.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/objective_at_parameter.hpp"
#include "libshell/analysis/rim_folds.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "solvers/continuation/growth_path.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"
#include "solvers/stability/positive_definiteness.hpp"

namespace growshell {
namespace {

struct Scene {
  ShellModel model;
  std::vector<Eigen::Index> pinned;
};

Scene make_scene(int rings, double h) {
  DiscMeshOptions o;
  o.rings = rings;
  o.grading_exponent = 3.0;
  o.min_spacing = h / 2;
  ShellModelSettings s;
  s.thickness = constant_thickness(h);
  ShellModel model(make_disc_mesh(o), s);
  const Eigen::VectorXd& X = model.reference_positions();
  const Eigen::MatrixX3d P =
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), X.size() / 3, 3);
  auto pinned = mirror_axis_pinned_dofs(P, model.sheet_vertices(), Eigen::Vector3d::Zero());
  return {std::move(model), pinned};
}

/// Out-of-plane perturbation sum_m c_m r^m cos(m t), with both the two- and the three-fold
/// mode present so that the path itself must select the two-fold cone.
Eigen::VectorXd perturbation(const ShellModel& model, double amplitude) {
  const Eigen::VectorXd& X = model.reference_positions();
  Eigen::VectorXd dz = Eigen::VectorXd::Zero(X.size());
  for (Eigen::Index v = 0; v < X.size() / 3; ++v) {
    const double r = std::hypot(X(3 * v), X(3 * v + 1)), t = std::atan2(X(3 * v + 1), X(3 * v));
    dz(3 * v + 2) = amplitude * (0.3 * r * r * std::cos(2 * t) + r * r * r * std::cos(3 * t) +
                                 0.5 * r * std::cos(t));
  }
  return dz;
}

TEST(GrowthPath, FlatDiscGrowsIntoTheTwoFoldCone) {
  Scene scene = make_scene(8, 0.04);
  ShellModel& model = scene.model;
  NewtonOptions no;
  no.gradient_tolerance = 1e-7 * model.natural_force_scale();
  no.decrement_tolerance = 1e-6 * model.settings().material.youngs_modulus * std::pow(0.04, 3);
  const NewtonSolver newton(no);
  GrowthPathOptions po;
  po.max_step = 0.25;
  std::vector<GrowthPathPoint> points;
  const GrowthPathResult path = grow_along_path(
      model, model.reference_positions() + perturbation(model, 1e-3), 0.0, 2.0, scene.pinned,
      newton, [&](int attempt) { return perturbation(model, 1e-3 * attempt); }, po,
      [&](const GrowthPathPoint& p) { points.push_back(p); });
  ASSERT_TRUE(path.reached_target) << path.message;
  EXPECT_DOUBLE_EQ(path.last.excess_angle, 2.0);
  ASSERT_GE(points.size(), 8u);
  double previous_bending = 0.0;
  for (const GrowthPathPoint& p : points) {
    // Stable: the pinned Hessian is positive definite.
    ObjectiveAtParameter energy(model, p.excess_angle);
    EXPECT_TRUE(hessian_is_positive_definite(energy, p.x, scene.pinned)) << p.excess_angle;
    // Two folds once the sheet has buckled (the threshold at h = 0.04 lies below 0.25).
    const RimFoldAnalysis rim = analyze_rim_folds(model, p.x);
    EXPECT_EQ(rim.folds, 2) << "phi_e = " << p.excess_angle;
    EXPECT_GT(rim.mode_amplitudes(2), 2 * rim.mode_amplitudes(3)) << p.excess_angle;
    // Bending energy grows with growth on this range.
    const double bending = model.energy_breakdown(p.x, p.excess_angle).bending;
    EXPECT_GT(bending, previous_bending);
    previous_bending = bending;
  }
  // Pinning the six rigid-body dofs does not bias the equilibrium: at the end point the
  // reactions at the pins are no larger than the residual force left at the free dofs (a
  // biased pin would carry a force of the order of the elastic forces, ~Y h^3 / R). The
  // strict check on equilibria without a nearly free mode is in tests/solvers.
  Eigen::VectorXd g;
  model.evaluate(path.last.x, 2.0, &g, nullptr);
  double free_residual = 0.0, reaction = 0.0;
  std::vector<char> pinned(g.size(), 0);
  for (Eigen::Index d : scene.pinned) pinned[d] = 1;
  for (Eigen::Index i = 0; i < g.size(); ++i)
    (pinned[i] ? reaction : free_residual) =
        std::max(pinned[i] ? reaction : free_residual, std::abs(g(i)));
  EXPECT_LT(reaction, 10 * free_residual + 1e-12);
  EXPECT_LT(reaction, 1e-3 * model.natural_force_scale());
}

TEST(GrowthPath, TangentIsTheDerivativeOfTheEquilibrium) {
  Scene scene = make_scene(6, 0.04);
  ShellModel& model = scene.model;
  NewtonOptions no;
  no.gradient_tolerance = 1e-11 * model.natural_force_scale();
  const NewtonSolver newton(no);
  NewtonSolver solver = newton;
  // The flat branch below the buckling threshold: in-plane equilibria.
  const double phi = 0.004, dphi = 1e-5;
  auto equilibrium = [&](double p) {
    ObjectiveAtParameter energy(model, p);
    const NewtonResult r = solver.minimize(energy, model.reference_positions(), scene.pinned);
    EXPECT_TRUE(r.converged()) << r.message;
    return r.x;
  };
  const Eigen::VectorXd x = equilibrium(phi);
  const Eigen::VectorXd fd = (equilibrium(phi + dphi) - equilibrium(phi - dphi)) / (2 * dphi);
  const Eigen::VectorXd t = equilibrium_tangent(model, x, phi, scene.pinned);
  ASSERT_EQ(t.size(), x.size());
  // Central difference error O(dphi^2) relative ~1e-8; solver tolerance 1e-11.
  EXPECT_LE((t - fd).norm(), 1e-5 * t.norm());
}

TEST(GrowthPath, RejectsBadOptionsAndKeepsTheStartWhenNothingConverges) {
  Scene scene = make_scene(4, 0.04);
  NewtonOptions no;
  no.max_iterations = 0;  // nothing can converge from a perturbed state
  const NewtonSolver newton(no);
  GrowthPathOptions po;
  po.min_step = 0.5;
  po.max_step = 1.0;
  const Eigen::VectorXd x0 =
      scene.model.reference_positions() + perturbation(scene.model, 1e-2);
  std::vector<GrowthPathFailedStep> failed;
  const GrowthPathResult path = grow_along_path(
      scene.model, x0, 0.0, 1.0, scene.pinned, newton,
      [&](int) { return perturbation(scene.model, 1e-3); }, po, {}, {},
      [&](const GrowthPathFailedStep& f) { failed.push_back(f); });
  EXPECT_FALSE(path.reached_target);
  EXPECT_FALSE(path.message.empty());
  // Every failed step is reported as it is given up: the step of 1 halved to 0.5, then the
  // end (no next step) with the reason the path's message gives.
  ASSERT_EQ(failed.size(), 2u);
  EXPECT_EQ(failed[0].from, 0.0);
  EXPECT_EQ(failed[0].to, 1.0);
  EXPECT_EQ(failed[0].next_step, 0.5);
  EXPECT_FALSE(failed[0].why.empty());
  EXPECT_EQ(failed[1].to, 0.5);
  EXPECT_EQ(failed[1].next_step, 0.0);
  EXPECT_NE(path.message.find(failed[1].why), std::string::npos);
  EXPECT_EQ(path.last.x, x0);
  EXPECT_EQ(path.last.excess_angle, 0.0);
  po.min_step = 2.0;
  EXPECT_THROW(grow_along_path(scene.model, x0, 0.0, 1.0, scene.pinned, newton,
                               [&](int) { return x0; }, po),
               std::invalid_argument);
}

}  // namespace
}  // namespace growshell
