// Explicit damped dynamics (relax_by_damped_dynamics): both integrators reach the minimum of an
// ill-conditioned quadratic with unequal masses and a held dof, FIRE reaches Newton's
// equilibrium of the grown disc to the accuracy its force tolerance implies, and bad options are
// refused by name.
#include <gtest/gtest.h>

#include <Eigen/SparseLU>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/objective_at_parameter.hpp"
#include "libshell/assembly/shell_model.hpp"
#include "libshell/mesh/ring_disc_mesh.hpp"
#include "solvers/dynamics/damped_dynamics.hpp"
#include "solvers/newton/newton_solver.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"

namespace growshell {
namespace {

/// E = x^T A x / 2 - b^T x with a tridiagonal A whose stiffness spans a factor of 400.
class GradedStiffnessQuadratic : public SparseObjective {
 public:
  explicit GradedStiffnessQuadratic(Eigen::Index n) : A_(n, n), b_(n) {
    std::vector<Eigen::Triplet<double>> t;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double k = 1.0 + 399.0 * i / (n - 1);
      t.emplace_back(i, i, 2.0 * k);
      if (i + 1 < n) t.emplace_back(i, i + 1, -0.5 * k);
      b_(i) = std::cos(0.7 * i);
    }
    A_.setFromTriplets(t.begin(), t.end());  // upper triangle
    full_ = A_.selfadjointView<Eigen::Upper>();
  }
  Eigen::Index dimension() const override { return b_.size(); }
  Eigen::SparseMatrix<double> hessian_pattern() const override { return A_; }
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd* g,
                  Eigen::SparseMatrix<double>* h) override {
    const Eigen::VectorXd Ax = full_ * x;
    if (g) *g = Ax - b_;
    if (h) *h = A_;
    return 0.5 * x.dot(Ax) - b_.dot(x);
  }
  /// The minimiser with x[held] = value.
  Eigen::VectorXd minimiser(Eigen::Index held, double value) const {
    const Eigen::Index n = b_.size();
    Eigen::SparseMatrix<double> K = full_;
    Eigen::VectorXd rhs = b_ - full_.col(held) * value;
    for (Eigen::Index i = 0; i < n; ++i) {
      K.coeffRef(held, i) = i == held ? 1.0 : 0.0;
      if (i != held) K.coeffRef(i, held) = 0.0;
    }
    rhs(held) = value;
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(K);
    return lu.solve(rhs);
  }

 private:
  Eigen::SparseMatrix<double> A_, full_;
  Eigen::VectorXd b_;
};

TEST(DampedDynamics, BothIntegratorsReachTheMinimumOfAnIllConditionedQuadratic) {
  GradedStiffnessQuadratic q(40);
  Eigen::VectorXd mass(40);
  for (Eigen::Index i = 0; i < 40; ++i) mass(i) = 1.0 + 0.5 * std::sin(0.3 * i);
  Eigen::VectorXd x0 = Eigen::VectorXd::Zero(40);
  x0(7) = 0.25;  // held there
  const Eigen::VectorXd expected = q.minimiser(7, 0.25);
  for (const DampedIntegrator integrator :
       {DampedIntegrator::Fire, DampedIntegrator::ViscousVerlet}) {
    DampedDynamicsOptions o;
    o.integrator = integrator;
    o.gradient_tolerance = 1e-10;
    o.max_steps = 200000;
    const DampedDynamicsResult r = relax_by_damped_dynamics(q, x0, mass, {7}, o);
    ASSERT_TRUE(r.converged) << r.message;
    EXPECT_EQ(r.x(7), 0.25);  // the held dof never moved
    // |A^-1| <= 1 on the free dofs, so the state error is at most a few force tolerances.
    EXPECT_LT((r.x - expected).lpNorm<Eigen::Infinity>(), 1e-8) << static_cast<int>(integrator);
    EXPECT_EQ(r.gradient_evaluations, r.steps + 1);
    EXPECT_GT(r.time_step, 0.0);
  }
}

TEST(DampedDynamics, BothReachNewtonsEquilibriumOfAGrowingShell) {
  // A coarse disc (h = 0.1) grown to phi_e = 0.05, below its buckling threshold (10.6 h^2), from
  // a wrinkled start: Newton and both integrators find the same (flat, stretched) equilibrium.
  RingDiscMeshOptions mesh;
  mesh.size_slope = 0.4;
  mesh.size_floor = 0.1;
  ShellModelSettings settings;
  settings.thickness = constant_thickness(0.1);
  const ShellModel model(make_ring_disc_mesh(mesh), settings);
  const Eigen::VectorXd& X = model.reference_positions();
  Eigen::VectorXd x0 = X;
  for (Eigen::Index v = 0; v < X.size() / 3; ++v)
    x0(3 * v + 2) = 0.01 * X(3 * v) * X(3 * v + 1) + 0.004 * X(3 * v) * X(3 * v);
  const std::vector<Eigen::Index> pins = mirror_axis_pinned_dofs(
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), X.size() / 3, 3),
      model.sheet_vertices(), model.settings().growth.center);
  ObjectiveAtParameter energy(model, 0.05);
  const double tolerance = 1e-7 * model.natural_force_scale();
  NewtonOptions n;
  n.gradient_tolerance = tolerance;
  const NewtonResult newton = NewtonSolver(n).minimize(energy, x0, pins);
  ASSERT_TRUE(newton.converged()) << newton.message;
  const Eigen::VectorXd mass = (model.reference().vertex_areas().array() * 0.1 + 1e-12)
                                   .matrix()
                                   .replicate(1, 3)
                                   .transpose()
                                   .reshaped();
  for (const DampedIntegrator integrator :
       {DampedIntegrator::Fire, DampedIntegrator::ViscousVerlet}) {
    DampedDynamicsOptions o;
    o.integrator = integrator;
    o.gradient_tolerance = tolerance;
    o.max_steps = 1000000;
    const DampedDynamicsResult r = relax_by_damped_dynamics(energy, x0, mass, pins, o);
    ASSERT_TRUE(r.converged) << r.message;
    // E - E* is of order |g|^2 / (2 lambda_min): 2e-9 of E at this tolerance.
    EXPECT_NEAR(r.energy, newton.energy, 1e-8 * std::abs(newton.energy));
    EXPECT_LT((r.x - newton.x).lpNorm<Eigen::Infinity>(), 1e-5) << static_cast<int>(integrator);
    EXPECT_GT(r.gradient_evaluations, 10 * newton.iterations);  // the point of the baseline
  }
}

TEST(DampedDynamics, RefusesBadInputByName) {
  GradedStiffnessQuadratic q(5);
  const Eigen::VectorXd x0 = Eigen::VectorXd::Zero(5), mass = Eigen::VectorXd::Ones(5);
  const auto message = [&](const DampedDynamicsOptions& o, const Eigen::VectorXd& m,
                           std::vector<Eigen::Index> fixed) {
    try {
      relax_by_damped_dynamics(q, x0, m, fixed, o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  DampedDynamicsOptions o;
  o.step_fraction = 1.0;
  EXPECT_NE(message(o, mass, {}).find("step_fraction"), std::string::npos);
  o = {};
  o.damping_ratio = 0.0;
  EXPECT_NE(message(o, mass, {}).find("damping_ratio"), std::string::npos);
  EXPECT_NE(message({}, -mass, {}).find("mass"), std::string::npos);
  EXPECT_NE(message({}, mass, {9}).find("fixed dof 9"), std::string::npos);
}

}  // namespace
}  // namespace growshell
