// minimize_with_constraints (Ipopt): KKT solutions of small problems known in closed form or
// by an independent active-set solve, the sign and units of the multipliers (forces), fixed
// dofs, warm starts, non-finite energies, and a shell pressed onto a support.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <unistd.h>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "solvers/contact/constrained_minimizer.hpp"

namespace growshell {
namespace {

using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;

Eigen::SparseMatrix<double> upper_of(const Eigen::SparseMatrix<double>& a) {
  Eigen::SparseMatrix<double> u = a.triangularView<Eigen::Upper>();
  u.makeCompressed();
  return u;
}

// E(x) = 1/2 x^T A x - b^T x with A symmetric (given in full).
class QuadraticEnergy : public SparseObjective {
 public:
  QuadraticEnergy(Eigen::SparseMatrix<double> a, Eigen::VectorXd b)
      : a_(std::move(a)), b_(std::move(b)), upper_(upper_of(a_)) {}
  Eigen::Index dimension() const override { return b_.size(); }
  Eigen::SparseMatrix<double> hessian_pattern() const override { return upper_; }
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd* gradient,
                  Eigen::SparseMatrix<double>* hessian_upper) override {
    ++evaluations;
    const Eigen::VectorXd ax = a_ * x;
    if (gradient != nullptr) *gradient = ax - b_;
    if (hessian_upper != nullptr) *hessian_upper = upper_;
    return 0.5 * x.dot(ax) - b_.dot(x);
  }
  int evaluations = 0;

 private:
  Eigen::SparseMatrix<double> a_;
  Eigen::VectorXd b_;
  Eigen::SparseMatrix<double> upper_;
};

// c(x) = G x - d >= 0.
class LinearConstraints : public InequalityConstraints {
 public:
  LinearConstraints(RowMajor g, Eigen::VectorXd d) : g_(std::move(g)), d_(std::move(d)) {
    g_.makeCompressed();
  }
  Eigen::Index dimension() const override { return g_.cols(); }
  Eigen::Index count() const override { return g_.rows(); }
  RowMajor jacobian_pattern() const override { return g_; }
  Eigen::SparseMatrix<double> hessian_pattern() const override {
    Eigen::SparseMatrix<double> empty(g_.cols(), g_.cols());
    empty.makeCompressed();
    return empty;
  }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd& values,
                RowMajor* jacobian) override {
    values = g_ * x - d_;
    if (jacobian != nullptr) *jacobian = g_;
  }
  void weighted_hessian(const Eigen::Ref<const Eigen::VectorXd>&,
                        const Eigen::Ref<const Eigen::VectorXd>&,
                        Eigen::SparseMatrix<double>&) override {}

 private:
  RowMajor g_;
  Eigen::VectorXd d_;
};

// One constraint c(x) = side (r^2 - |x|^2) >= 0: side = +1 keeps x inside the ball of radius r,
// side = -1 outside. Its Hessian -2 side I makes the constraint curvature matter.
class BallConstraint : public InequalityConstraints {
 public:
  BallConstraint(Eigen::Index n, double radius, double side) : n_(n), r_(radius), side_(side) {}
  Eigen::Index dimension() const override { return n_; }
  Eigen::Index count() const override { return 1; }
  RowMajor jacobian_pattern() const override {
    RowMajor j(1, n_);
    for (Eigen::Index i = 0; i < n_; ++i) j.insert(0, i) = 1.0;
    j.makeCompressed();
    return j;
  }
  Eigen::SparseMatrix<double> hessian_pattern() const override {
    Eigen::SparseMatrix<double> h(n_, n_);
    for (Eigen::Index i = 0; i < n_; ++i) h.insert(i, i) = 1.0;
    h.makeCompressed();
    return h;
  }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd& values,
                RowMajor* jacobian) override {
    values.resize(1);
    values(0) = side_ * (r_ * r_ - x.squaredNorm());
    if (jacobian != nullptr) {
      for (Eigen::Index i = 0; i < n_; ++i) jacobian->valuePtr()[i] = -2.0 * side_ * x(i);
    }
  }
  void weighted_hessian(const Eigen::Ref<const Eigen::VectorXd>&,
                        const Eigen::Ref<const Eigen::VectorXd>& weights,
                        Eigen::SparseMatrix<double>& hessian_upper) override {
    for (Eigen::Index i = 0; i < n_; ++i) hessian_upper.valuePtr()[i] = -2.0 * side_ * weights(0);
  }

 private:
  Eigen::Index n_;
  double r_;
  double side_;
};

// dE/dx - J^T mu over the dofs not in `fixed` (the out-of-balance force of the KKT system).
double kkt_residual(SparseObjective& energy, InequalityConstraints& constraints,
                    const ConstrainedResult& r, const std::vector<Eigen::Index>& fixed = {}) {
  Eigen::VectorXd g;
  energy.evaluate(r.x, &g, nullptr);
  Eigen::VectorXd c;
  RowMajor j = constraints.jacobian_pattern();
  constraints.evaluate(r.x, c, &j);
  Eigen::VectorXd residual = g - j.transpose() * r.multipliers;
  for (const Eigen::Index d : fixed) residual(d) = 0.0;
  return residual.lpNorm<Eigen::Infinity>();
}

ConstrainedMinimizerOptions tight_options() {
  ConstrainedMinimizerOptions o;
  o.tolerance = 1e-12;
  o.acceptable_tolerance = 1e-10;
  o.constraint_violation_tolerance = 1e-12;
  o.complementarity_tolerance = 1e-12;
  o.dual_infeasibility_tolerance = 1e-10;
  return o;
}

// ---------------------------------------------------------------------------------------
// (1) Convex quadratic, linear constraints: the KKT point from an independent solve of the
// equality-constrained system on the active set, confirmed optimal by mu > 0 there and
// strict feasibility of the inactive constraint.
TEST(ConstrainedMinimizer, QuadraticWithLinearConstraintsMatchesKkt) {
  Eigen::MatrixXd a_dense(3, 3);
  a_dense << 4.0, 1.0, 0.0,  //
      1.0, 3.0, 0.5,         //
      0.0, 0.5, 2.0;
  const Eigen::Vector3d b(-1.0, -2.0, 0.5);
  // c1 = x0 + x1 - 1, c2 = x2 - 0.5 (both active), c3 = 5 - x0 (inactive).
  Eigen::MatrixXd g_dense(3, 3);
  g_dense << 1.0, 1.0, 0.0,  //
      0.0, 0.0, 1.0,         //
      -1.0, 0.0, 0.0;
  const Eigen::Vector3d d(1.0, 0.5, -5.0);

  // KKT on the active set {c1, c2}: A x - b = G_a^T mu, G_a x = d_a.
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(5, 5);
  kkt.topLeftCorner(3, 3) = a_dense;
  kkt.topRightCorner(3, 2) = -g_dense.topRows(2).transpose();
  kkt.bottomLeftCorner(2, 3) = g_dense.topRows(2);
  Eigen::VectorXd rhs(5);
  rhs.head<3>() = b;
  rhs.tail<2>() = d.head<2>();
  const Eigen::VectorXd sol = kkt.fullPivLu().solve(rhs);
  const Eigen::Vector3d x_star = sol.head(3);
  const Eigen::Vector2d mu_star = sol.tail(2);
  ASSERT_GT(mu_star.minCoeff(), 0.1);  // the guessed active set is the right one
  ASSERT_GT(5.0 - x_star(0), 1.0);

  QuadraticEnergy energy(a_dense.sparseView(), b);
  LinearConstraints constraints(g_dense.sparseView(), d);
  const ConstrainedResult r = minimize_with_constraints(energy, constraints,
                                                        Eigen::Vector3d(2.0, 2.0, 2.0), {},
                                                        tight_options());
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.message.rfind("Ipopt: converged", 0), 0u) << r.message;
  // Ipopt stops when complementarity mu_k c_k <= 1e-12, so active gaps are <= 1e-12 / mu_k
  // ~ 1e-11 and x, mu are off by that times O(|A^-1|) = O(1): 1e-8 leaves three decades.
  // Measured: |dx| 8.6e-14, |dmu| / mu 2.2e-13 (7 iterations).
  EXPECT_LE((r.x - x_star).lpNorm<Eigen::Infinity>(), 1e-8);
  EXPECT_NEAR(r.multipliers(0), mu_star(0), 1e-8 * mu_star(0));
  EXPECT_NEAR(r.multipliers(1), mu_star(1), 1e-8 * mu_star(1));
  // The inactive constraint carries no force: mu_3 c_3 <= 1e-12 with c_3 ~ 4 (measured
  // mu_3 = 2.9e-14).
  EXPECT_GE(r.multipliers(2), 0.0);
  EXPECT_LE(r.multipliers(2), 1e-11);
  // Sign convention: dE/dx = sum mu_k dc_k/dx.
  EXPECT_LE(kkt_residual(energy, constraints, r), 1e-10);
  EXPECT_NEAR(r.energy, 0.5 * x_star.dot(a_dense * x_star) - b.dot(x_star), 1e-10);
  EXPECT_LE(r.max_violation, 1e-12);
}

// (2) An inactive constraint changes nothing: the unconstrained minimum A^-1 b and a zero
// multiplier.
TEST(ConstrainedMinimizer, InactiveConstraintLeavesUnconstrainedMinimum) {
  Eigen::MatrixXd a_dense(2, 2);
  a_dense << 2.0, 0.5, 0.5, 1.0;
  const Eigen::Vector2d b(1.0, -0.5);
  const Eigen::Vector2d x_free = a_dense.ldlt().solve(b);
  // c = x0 + 3 >= 0; x_free(0) = 0.857, so c = 3.86 at the minimum.
  Eigen::MatrixXd g_dense(1, 2);
  g_dense << 1.0, 0.0;
  QuadraticEnergy energy(a_dense.sparseView(), b);
  LinearConstraints constraints(g_dense.sparseView(), Eigen::VectorXd::Constant(1, -3.0));
  const ConstrainedResult r = minimize_with_constraints(energy, constraints,
                                                        Eigen::Vector2d(-1.0, 1.0), {},
                                                        tight_options());
  ASSERT_TRUE(r.converged()) << r.message;
  // The barrier leaves mu = (final barrier parameter) / c <= 1e-12 / 3.9; the x error is that
  // force over the stiffness, so 1e-10 is loose. Measured: |dx| 1.9e-14, mu 3.4e-14.
  EXPECT_LE((r.x - x_free).lpNorm<Eigen::Infinity>(), 1e-10);
  EXPECT_GE(r.multipliers(0), 0.0);
  EXPECT_LE(r.multipliers(0), 1e-12);
  EXPECT_EQ(r.max_violation, 0.0);
}

// ---------------------------------------------------------------------------------------
// A "sheet" of points on a grid pressed by forces f_i against a parallel sheet, modelled as
// gaps c_i = z_i - h >= 0: in-plane tethers k (x, y towards the grid point) and shear springs
// k_c (z_i - z_j)^2 / 2 between grid neighbours, load energy sum f_i z_i. Every point ends in
// contact at z = h, the springs are then unloaded, and equilibrium of each point's z gives
// mu_i = f_i exactly: the multipliers are the contact forces in newtons.
struct PressedSheet {
  static constexpr int kSide = 6;
  static constexpr double kGap = 0.02;  // h (m)
  static constexpr double kForce = 3.0;  // mean load per point f0 (N)
  int points() const { return kSide * kSide; }
  Eigen::Index dofs() const { return 3 * points(); }

  Eigen::VectorXd loads(double factor = 1.0) const {
    Eigen::VectorXd f(points());
    for (int i = 0; i < points(); ++i) f(i) = factor * kForce * (1.0 + 0.5 * std::sin(1.3 * i));
    return f;
  }

  // Tether stiffness k (N/m) and shear stiffness k_c (N/m): k_c h ~ f0 so that the springs
  // matter on the way down.
  QuadraticEnergy energy(const Eigen::VectorXd& f) const {
    const double k = 50.0;
    const double kc = 100.0;
    std::vector<Eigen::Triplet<double>> t;
    Eigen::VectorXd b = Eigen::VectorXd::Zero(dofs());
    auto z = [](int p) { return 3 * p + 2; };
    for (int i = 0; i < kSide; ++i) {
      for (int j = 0; j < kSide; ++j) {
        const int p = i * kSide + j;
        t.emplace_back(3 * p, 3 * p, k);
        t.emplace_back(3 * p + 1, 3 * p + 1, k);
        b(3 * p) = k * 0.1 * j;
        b(3 * p + 1) = k * 0.1 * i;
        b(z(p)) = -f(p);
        for (const int q : {j + 1 < kSide ? p + 1 : -1, i + 1 < kSide ? p + kSide : -1}) {
          if (q < 0) continue;
          t.emplace_back(z(p), z(p), kc);
          t.emplace_back(z(q), z(q), kc);
          t.emplace_back(z(p), z(q), -kc);
          t.emplace_back(z(q), z(p), -kc);
        }
      }
    }
    Eigen::SparseMatrix<double> a(dofs(), dofs());
    a.setFromTriplets(t.begin(), t.end());
    return QuadraticEnergy(a, b);
  }

  LinearConstraints gaps() const {
    RowMajor g(points(), dofs());
    for (int p = 0; p < points(); ++p) g.insert(p, 3 * p + 2) = 1.0;
    return LinearConstraints(g, Eigen::VectorXd::Constant(points(), kGap));
  }

  // Above the support, slightly uneven and off the grid in-plane.
  Eigen::VectorXd start() const {
    Eigen::VectorXd x(dofs());
    for (int i = 0; i < kSide; ++i) {
      for (int j = 0; j < kSide; ++j) {
        const int p = i * kSide + j;
        x.segment<3>(3 * p) << 0.1 * j + 0.01, 0.1 * i - 0.02, 0.1 + 0.01 * std::cos(p);
      }
    }
    return x;
  }

  // Scales for Ipopt: positions and gaps in units of h, forces in units of f0; tolerances
  // tightened relative to h and f0.
  ConstrainedMinimizerOptions options() const {
    ConstrainedMinimizerOptions o;
    o.length_scale = kGap;
    o.force_scale = kForce;
    o.tolerance = 1e-10;
    o.acceptable_tolerance = 1e-8;
    o.constraint_violation_tolerance = 1e-10 * kGap;
    o.complementarity_tolerance = 1e-10 * kGap * kForce;
    o.dual_infeasibility_tolerance = 1e-10 * kForce;
    return o;
  }
};

// (3) The sheet stops exactly at distance h and each multiplier equals the applied force.
TEST(ConstrainedMinimizer, PressedSheetStopsAtDistanceHWithContactForces) {
  const PressedSheet sheet;
  const Eigen::VectorXd f = sheet.loads();
  QuadraticEnergy energy = sheet.energy(f);
  LinearConstraints gaps = sheet.gaps();
  const ConstrainedResult r =
      minimize_with_constraints(energy, gaps, sheet.start(), {}, sheet.options());
  ASSERT_TRUE(r.converged()) << r.message;
  // Complementarity <= 1e-10 h f0 with mu_i >= f0 / 2 puts every gap within 2e-10 h of zero,
  // and violation <= 1.1e-10 h: 1e-9 h leaves a factor of 5. Measured: 8.2e-12 h (8
  // iterations).
  double worst_gap = 0.0;
  double worst_in_plane = 0.0;
  for (int p = 0; p < sheet.points(); ++p) {
    worst_gap = std::max(worst_gap, std::abs(r.x(3 * p + 2) - PressedSheet::kGap));
    worst_in_plane = std::max({worst_in_plane, std::abs(r.x(3 * p) - 0.1 * (p % 6)),
                               std::abs(r.x(3 * p + 1) - 0.1 * (p / 6))});
  }
  EXPECT_LE(worst_gap, 1e-9 * PressedSheet::kGap) << worst_gap;
  EXPECT_LE(worst_in_plane, 1e-12);
  // mu_i - f_i = (spring force on i) <= 4 k_c * (gap spread 2e-10 h) + dual tolerance 1e-10 f0
  // ~ 1e-10 f0: 1e-8 relative is safe. Measured: 3.8e-11.
  const double force_error = ((r.multipliers - f).cwiseQuotient(f)).lpNorm<Eigen::Infinity>();
  EXPECT_LE(force_error, 1e-8) << force_error;
  // Ipopt's relaxation of c >= 0 is 1e-11 h here, so the bound is 1.1e-10 h (measured 3.9e-12 h).
  EXPECT_LE(r.max_violation, 1.1e-10 * PressedSheet::kGap);
}

// (4) Fixed dofs keep their x0 values bit for bit; the rest is still in equilibrium.
TEST(ConstrainedMinimizer, FixedDofsStayFixedExactly) {
  const PressedSheet sheet;
  QuadraticEnergy energy = sheet.energy(sheet.loads());
  LinearConstraints gaps = sheet.gaps();
  const Eigen::VectorXd x0 = sheet.start();
  // Corner point 0 held completely (above the support), point 14 held only in z, point 20
  // only in-plane.
  const std::vector<Eigen::Index> fixed = {0, 1, 2, 3 * 14 + 2, 3 * 20, 3 * 20 + 1};
  const ConstrainedResult r = minimize_with_constraints(energy, gaps, x0, fixed, sheet.options());
  ASSERT_TRUE(r.converged()) << r.message;
  for (const Eigen::Index d : fixed) EXPECT_EQ(r.x(d), x0(d)) << "dof " << d;
  // The held points lift their neighbours (which then carry less contact force); the free
  // dofs balance to Ipopt's dual tolerance 1e-10 f0 (measured 2.8e-15 N). Point 1, next to
  // the held corner, lifts off completely (measured mu_1 = 0 to 1e-13 against f_1 = 4.4 N).
  EXPECT_LE(kkt_residual(energy, gaps, r, fixed), 1e-9 * PressedSheet::kForce);
  EXPECT_LT(r.multipliers(1), sheet.loads()(1));
  EXPECT_LE(r.max_violation, 1.1e-10 * PressedSheet::kGap);
}

// (5) Warm start: the next step of a loading path (loads up 5 %) started from the previous
// solution and its multipliers takes fewer iterations than a cold start of the same problem,
// and restarting at a solution takes at most a few. Measured: cold 5, warm 2 iterations;
// restart at the solution 1 iteration, moving x by 7e-18 m.
TEST(ConstrainedMinimizer, WarmStartFromPreviousSolutionIsFaster) {
  const PressedSheet sheet;
  QuadraticEnergy energy = sheet.energy(sheet.loads());
  LinearConstraints gaps = sheet.gaps();
  const ConstrainedResult first =
      minimize_with_constraints(energy, gaps, sheet.start(), {}, sheet.options());
  ASSERT_TRUE(first.converged()) << first.message;

  const ConstrainedResult again = minimize_with_constraints(energy, gaps, first.x, {},
                                                            sheet.options(), &first.multipliers);
  ASSERT_TRUE(again.converged()) << again.message;
  EXPECT_LE(again.iterations, 3) << again.message;
  EXPECT_LE((again.x - first.x).lpNorm<Eigen::Infinity>(), 1e-9 * PressedSheet::kGap);

  const Eigen::VectorXd f2 = sheet.loads(1.05);
  QuadraticEnergy energy2 = sheet.energy(f2);
  const ConstrainedResult cold =
      minimize_with_constraints(energy2, gaps, first.x, {}, sheet.options());
  const ConstrainedResult warm = minimize_with_constraints(energy2, gaps, first.x, {},
                                                           sheet.options(), &first.multipliers);
  ASSERT_TRUE(cold.converged()) << cold.message;
  ASSERT_TRUE(warm.converged()) << warm.message;
  EXPECT_LT(warm.iterations, cold.iterations) << warm.message << " vs " << cold.message;
  EXPECT_LE(((warm.multipliers - f2).cwiseQuotient(f2)).lpNorm<Eigen::Infinity>(), 1e-8);
  // warm_start = false ignores the multipliers: the same iterations as the cold start.
  ConstrainedMinimizerOptions no_warm = sheet.options();
  no_warm.warm_start = false;
  const ConstrainedResult ignored =
      minimize_with_constraints(energy2, gaps, first.x, {}, no_warm, &first.multipliers);
  EXPECT_EQ(ignored.iterations, cold.iterations);
}

// ---------------------------------------------------------------------------------------
// (6) Non-finite energies. NaN at x0: Ipopt cannot start; the result says so and x stays x0.
// NaN outside |x| < 1 with the minimum beyond: Ipopt cuts its steps at the NaN region,
// x stays finite, and the message counts the rejected evaluations.
class NanOutsideBall : public SparseObjective {
 public:
  explicit NanOutsideBall(double radius) : radius_(radius) {}
  Eigen::Index dimension() const override { return 2; }
  Eigen::SparseMatrix<double> hessian_pattern() const override {
    Eigen::SparseMatrix<double> h(2, 2);
    h.insert(0, 0) = 1.0;
    h.insert(1, 1) = 1.0;
    h.makeCompressed();
    return h;
  }
  // 1/2 |x - (3, 0)|^2, NaN where |x| >= radius.
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd* gradient,
                  Eigen::SparseMatrix<double>* hessian_upper) override {
    const Eigen::Vector2d p(3.0, 0.0);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const bool inside = x.norm() < radius_;
    if (gradient != nullptr) *gradient = inside ? Eigen::VectorXd(x - p) : Eigen::VectorXd::Constant(2, nan);
    if (hessian_upper != nullptr) {
      hessian_upper->valuePtr()[0] = hessian_upper->valuePtr()[1] = inside ? 1.0 : nan;
    }
    return inside ? 0.5 * (x - p).squaredNorm() : nan;
  }

 private:
  double radius_;
};

TEST(ConstrainedMinimizer, NanEnergyGivesClearFailureAndFiniteX) {
  Eigen::MatrixXd g_dense(1, 2);
  g_dense << 0.0, 1.0;  // x1 + 5 >= 0, inactive
  LinearConstraints constraints(g_dense.sparseView(), Eigen::VectorXd::Constant(1, -5.0));
  {
    NanOutsideBall energy(1.0);
    const Eigen::Vector2d x0(2.0, 0.0);  // already in the NaN region
    const ConstrainedResult r =
        minimize_with_constraints(energy, constraints, x0, {}, ConstrainedMinimizerOptions{});
    EXPECT_FALSE(r.converged());
    EXPECT_EQ(r.status, -13);  // Invalid_Number_Detected
    EXPECT_NE(r.message.find("Ipopt: error in evaluating the energy"), std::string::npos)
        << r.message;
    EXPECT_NE(r.message.find("non-finite energy"), std::string::npos) << r.message;
    EXPECT_EQ(r.x, Eigen::VectorXd(x0));
  }
  {
    NanOutsideBall energy(1.0);
    // Measured: Maximum_Iterations_Exceeded at x = (0.99998, 0.0059) on the NaN boundary,
    // ~50 rejected NaN trial points per iteration.
    ConstrainedMinimizerOptions o;
    o.max_iterations = 30;
    const ConstrainedResult r =
        minimize_with_constraints(energy, constraints, Eigen::Vector2d(0.0, 0.0), {}, o);
    EXPECT_FALSE(r.converged()) << r.message;
    EXPECT_TRUE(r.x.allFinite());
    EXPECT_LT(r.x.norm(), 1.0);
    EXPECT_TRUE(std::isfinite(r.energy));
    EXPECT_NE(r.message.find("non-finite energy"), std::string::npos) << r.message;
  }
}

// ---------------------------------------------------------------------------------------
// Curved constraints: the constraint Hessian enters the Lagrangian with the right sign.
// E = |x - p|^2 / 2 with p outside the unit ball, x kept inside: x* = p / |p| and
// mu = (|p| - 1) / 2 (from x - p = mu * (-2 x)). The Lagrangian Hessian (1 + 2 mu) I is what
// makes Newton converge quadratically; the wrong sign, (1 - 2 mu) I = -3.5 I here, gives an
// indefinite KKT system (measured with the sign deliberately flipped in the library: 101
// iterations; with the right sign 9, and x, mu within 4e-14).
TEST(ConstrainedMinimizer, CurvedConstraintUsesLagrangianHessian) {
  const Eigen::Vector3d p(6.0, 5.0, 3.0 * std::sqrt(3.0));  // |p| = 8.75 (rounded below)
  QuadraticEnergy energy(Eigen::MatrixXd::Identity(3, 3).sparseView(), p);
  BallConstraint inside(3, 1.0, +1.0);
  const ConstrainedResult r = minimize_with_constraints(energy, inside, Eigen::Vector3d(0.1, -0.2, 0.3),
                                                        {}, tight_options());
  ASSERT_TRUE(r.converged()) << r.message;
  const double mu = (p.norm() - 1.0) / 2.0;
  EXPECT_LE((r.x - p.normalized()).lpNorm<Eigen::Infinity>(), 1e-10);
  EXPECT_NEAR(r.multipliers(0), mu, 1e-9 * mu);
  EXPECT_LE(r.iterations, 12) << r.message;
}

// ---------------------------------------------------------------------------------------
// (7) A shell: a flat disc (radius 1 m, h = 0.02, 4 rings) pulled down by forces on its outer
// part and resting on a support that keeps the control points of the inner rings at z >= 0.
// The shell energy is invariant under vertical translation, so the support must carry the
// whole load: sum mu_k = sum f_i.
class LoadedShell : public SparseObjective {
 public:
  /// The flat, ungrown shell (phi_e = 0) under the load.
  LoadedShell(const ShellModel& shell, Eigen::VectorXd load) : shell_(shell), load_(std::move(load)) {}
  Eigen::Index dimension() const override { return shell_.dimension(); }
  Eigen::SparseMatrix<double> hessian_pattern() const override { return shell_.hessian_pattern(); }
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd* gradient,
                  Eigen::SparseMatrix<double>* hessian_upper) override {
    const double e = shell_.evaluate(x, 0.0, gradient, hessian_upper);
    if (gradient != nullptr) *gradient += load_;
    return e + load_.dot(x);
  }

 private:
  const ShellModel& shell_;
  Eigen::VectorXd load_;  // dE/dx of the load: +f on the z dof of a point pulled down by f
};

TEST(ConstrainedMinimizer, ShellDiscHangsOnSupport) {
  DiscMeshOptions mesh;
  mesh.rings = 4;
  ShellModelSettings settings;
  ShellModel shell(make_disc_mesh(mesh), settings);
  const Eigen::VectorXd x0 = shell.reference_positions();
  const Eigen::Index n = shell.dimension();
  const Eigen::Index vertices = n / 3;
  const double force = 0.001 * shell.natural_force_scale();  // per pulled control point (N)
  Eigen::VectorXd load = Eigen::VectorXd::Zero(n);
  std::vector<Eigen::Index> supported;
  for (Eigen::Index v = 0; v < vertices; ++v) {
    const double r = x0.segment<2>(3 * v).norm();
    if (r > 0.6) load(3 * v + 2) = force;
    if (r < 0.3) supported.push_back(v);
  }
  ASSERT_EQ(supported.size(), 7u);  // centre and ring 1
  RowMajor g(static_cast<Eigen::Index>(supported.size()), n);
  for (std::size_t k = 0; k < supported.size(); ++k) {
    g.insert(static_cast<Eigen::Index>(k), 3 * supported[k] + 2) = 1.0;
  }
  LinearConstraints support(g, Eigen::VectorXd::Zero(g.rows()));
  LoadedShell energy(shell, load);
  // In-plane rigid motions: x, y of the centre and y of ring 1's vertex on the +x axis.
  const std::vector<Eigen::Index> fixed = {0, 1, 3 * 1 + 1};
  ASSERT_NEAR(x0(3 * 1 + 1), 0.0, 1e-12);

  ConstrainedMinimizerOptions o;
  const double h = 0.02;
  o.length_scale = h;
  o.force_scale = shell.natural_force_scale();
  o.tolerance = 1e-9;
  o.constraint_violation_tolerance = 1e-9 * h;
  o.complementarity_tolerance = 1e-9 * h * o.force_scale;
  o.dual_infeasibility_tolerance = 1e-9 * o.force_scale;
  const ConstrainedResult r = minimize_with_constraints(energy, support, x0, fixed, o);
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_LE(r.max_violation, 1.1e-9 * h);
  const double total = load.sum();
  // Vertical balance holds to the dual tolerance per dof, 1e-9 F over 91 z dofs, against a
  // total load of 0.06 F; measured relative error 2e-16 (11 iterations). The load is small
  // (1e-3 F per point): the rim sags by 1.8 h, a moderately nonlinear state.
  EXPECT_NEAR(r.multipliers.sum(), total, 1e-7 * total);
  EXPECT_GE(r.multipliers.minCoeff(), 0.0);
  // The rim hangs below the support: it really bent.
  double lowest = 0.0;
  for (Eigen::Index v = 0; v < vertices; ++v) lowest = std::min(lowest, r.x(3 * v + 2));
  EXPECT_LT(lowest, -h) << lowest;
  EXPECT_LE(kkt_residual(energy, support, r, fixed), 1e-8 * o.force_scale);  // measured 7e-13 F
}

// The library prints nothing, and a stray ipopt.opt in the working directory (which Ipopt's
// default initialisation would read) changes nothing: here it asks for verbose output and
// zero iterations.
TEST(ConstrainedMinimizer, SilentAndIgnoresIpoptOptFile) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      ("growshell_ipopt_opt_" + std::to_string(static_cast<long>(::getpid())));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "ipopt.opt") << "print_level 12\nmax_iter 0\n";
  const std::filesystem::path previous = std::filesystem::current_path();
  std::filesystem::current_path(dir);

  const PressedSheet sheet;
  QuadraticEnergy energy = sheet.energy(sheet.loads());
  LinearConstraints gaps = sheet.gaps();
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  const ConstrainedResult r =
      minimize_with_constraints(energy, gaps, sheet.start(), {}, sheet.options());
  const std::string out = testing::internal::GetCapturedStdout();
  const std::string err = testing::internal::GetCapturedStderr();
  std::filesystem::current_path(previous);
  std::filesystem::remove_all(dir);

  EXPECT_TRUE(r.converged()) << r.message;
  EXPECT_GT(r.iterations, 0);
  EXPECT_EQ(out, "");
  EXPECT_EQ(err, "");
}

// Bad input is rejected with a message naming it.
TEST(ConstrainedMinimizer, RejectsBadInput) {
  QuadraticEnergy energy(Eigen::MatrixXd::Identity(2, 2).sparseView(), Eigen::Vector2d(1, 1));
  Eigen::MatrixXd g_dense(1, 2);
  g_dense << 1.0, 0.0;
  LinearConstraints constraints(g_dense.sparseView(), Eigen::VectorXd::Zero(1));
  const Eigen::Vector2d x0(0.5, 0.5);
  auto message_of = [&](auto&& call) {
    try {
      call();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_NE(message_of([&] {
              minimize_with_constraints(energy, constraints, Eigen::Vector3d::Zero(), {}, {});
            }).find("x0 has size 3"),
            std::string::npos);
  EXPECT_NE(message_of([&] {
              minimize_with_constraints(energy, constraints, x0, {2}, {});
            }).find("fixed dof 2"),
            std::string::npos);
  EXPECT_NE(message_of([&] {
              minimize_with_constraints(energy, constraints, x0, {1, 1}, {});
            }).find("listed twice"),
            std::string::npos);
  const Eigen::VectorXd negative = Eigen::VectorXd::Constant(1, -1.0);
  EXPECT_NE(message_of([&] {
              minimize_with_constraints(energy, constraints, x0, {}, {}, &negative);
            }).find("initial multiplier 0"),
            std::string::npos);
  ConstrainedMinimizerOptions bad;
  bad.tolerance = 0.0;
  EXPECT_NE(message_of([&] {
              minimize_with_constraints(energy, constraints, x0, {}, bad);
            }).find("tolerance"),
            std::string::npos);
  ConstrainedMinimizerOptions unknown_solver;
  unknown_solver.linear_solver = "no-such-solver";
  EXPECT_NE(message_of([&] {
              minimize_with_constraints(energy, constraints, x0, {}, unknown_solver);
            }).find("linear_solver"),
            std::string::npos);
}

}  // namespace
}  // namespace growshell
