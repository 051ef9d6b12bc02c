// The phase condition: the Lagrangian family's gradient and Hessian against finite
// differences, and traces of a problem with an exact rotational symmetry, whose branch is a
// circle of equilibria at every lambda (a singular Hessian along the orbit), held on the
// hyperplane y = 0 with a vanishing multiplier; with the symmetry broken slightly, the
// multiplier is the breaking force.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <vector>

#include "solvers/continuation/phase_condition_trace.hpp"
#include "solvers/continuation/phase_conditioned_family.hpp"

namespace growshell {
namespace {

/// E = (r^2 - lambda)^2 / 4 + tilt x y + sum_i k_i/2 (p_i - q x)^2, r^2 = x^2 + y^2, with
/// passive dofs p_i coupled to x. For tilt = 0 every point of the circle r^2 = lambda (p_i = q
/// x) is an equilibrium: the rotation of (x, y) is a symmetry, and the Hessian is singular
/// along it. tilt != 0 breaks it.
class RingFamily : public ParametrizedObjective {
 public:
  RingFamily(int passive, double tilt) : n_(2 + passive), tilt_(tilt) {}
  Eigen::Index dimension() const override { return n_; }
  Eigen::SparseMatrix<double> hessian_pattern() const override {
    std::vector<Eigen::Triplet<double>> t = {{0, 0, 0.0}, {0, 1, 0.0}, {1, 1, 0.0}};
    for (int i = 2; i < n_; ++i) {
      t.emplace_back(0, i, 0.0);
      t.emplace_back(i, i, 0.0);
    }
    Eigen::SparseMatrix<double> H(n_, n_);
    H.setFromTriplets(t.begin(), t.end());
    H.makeCompressed();
    return H;
  }
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& z, double lambda, Eigen::VectorXd* g,
                  Eigen::SparseMatrix<double>* H) const override {
    const double x = z(0), y = z(1), r2 = x * x + y * y, s = r2 - lambda;
    double E = s * s / 4 + tilt_ * x * y;
    Eigen::VectorXd grad = Eigen::VectorXd::Zero(n_);
    grad(0) = s * x + tilt_ * y;
    grad(1) = s * y + tilt_ * x;
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(n_, n_);
    D(0, 0) = s + 2 * x * x;
    D(0, 1) = 2 * x * y + tilt_;
    D(1, 1) = s + 2 * y * y;
    for (int i = 2; i < n_; ++i) {
      const double k = 1.0 + 0.5 * i, d = z(i) - kQ * x;
      E += 0.5 * k * d * d;
      grad(i) += k * d;
      grad(0) -= kQ * k * d;
      D(0, 0) += kQ * kQ * k;
      D(0, i) = -kQ * k;
      D(i, i) = k;
    }
    if (g) *g = grad;
    if (H) {
      for (Eigen::Index col = 0; col < H->outerSize(); ++col)
        for (Eigen::SparseMatrix<double>::InnerIterator it(*H, col); it; ++it)
          it.valueRef() = D(it.row(), col);
    }
    return E;
  }
  Eigen::VectorXd gradient_parameter_derivative(const Eigen::Ref<const Eigen::VectorXd>& z,
                                                double) const override {
    Eigen::VectorXd d = Eigen::VectorXd::Zero(n_);
    d(0) = -z(0);
    d(1) = -z(1);
    return d;
  }
  static constexpr double kQ = 0.3;

 private:
  int n_;
  double tilt_;
};

Eigen::MatrixXd dense_upper_symmetric(const Eigen::SparseMatrix<double>& upper) {
  Eigen::MatrixXd D = Eigen::MatrixXd(upper);
  return D.selfadjointView<Eigen::Upper>();
}

TEST(PhaseConditionedFamily, GradientAndHessianMatchFiniteDifferences) {
  RingFamily ring(3, 0.05);
  const double lambda = 1.3;
  Eigen::VectorXd c(5);
  c << 0.2, -0.7, 0.0, 0.4, 0.1;
  PhaseConditionedFamily family(ring, c, 0.25);
  ASSERT_EQ(family.dimension(), 6);
  Eigen::VectorXd z(6);
  z << 0.8, 0.3, -0.2, 0.5, 0.1, 0.7;
  Eigen::VectorXd g;
  Eigen::SparseMatrix<double> H = family.hessian_pattern();
  family.evaluate(z, lambda, &g, &H);
  const Eigen::MatrixXd Hd = dense_upper_symmetric(H);
  const double step = 1e-6;
  for (int i = 0; i < 6; ++i) {
    Eigen::VectorXd zp = z, zm = z, gp, gm;
    zp(i) += step;
    zm(i) -= step;
    const double fd =
        (family.evaluate(zp, lambda, &gp, nullptr) - family.evaluate(zm, lambda, &gm, nullptr)) /
        (2 * step);
    EXPECT_NEAR(g(i), fd, 1e-8) << "gradient entry " << i;
    for (int j = 0; j < 6; ++j)
      EXPECT_NEAR(Hd(j, i), (gp(j) - gm(j)) / (2 * step), 1e-7) << "Hessian entry " << j << ", " << i;
  }
  // The last gradient entry is the constraint c . x - b; d/dlambda leaves it alone.
  EXPECT_NEAR(g(5), c.dot(z.head(5)) - 0.25, 1e-15);
  EXPECT_EQ(family.gradient_parameter_derivative(z, lambda)(5), 0.0);
}

TEST(PhaseConditionedFamily, RejectsABadFunctional) {
  RingFamily ring(1, 0.0);
  EXPECT_THROW(PhaseConditionedFamily(ring, Eigen::VectorXd::Zero(3), 0.0), std::invalid_argument);
  EXPECT_THROW(PhaseConditionedFamily(ring, Eigen::VectorXd::Ones(2), 0.0), std::invalid_argument);
  Eigen::VectorXd bad = Eigen::VectorXd::Ones(3);
  bad(1) = std::nan("");
  EXPECT_THROW(PhaseConditionedFamily(ring, bad, 0.0), std::invalid_argument);
}

/// The circle branch from (1, 0) at lambda = 1 to lambda = 3, held on y = 0.
BranchTrace trace_ring(
    RingFamily& ring, std::vector<BranchSample>& samples,
    std::function<bool(const BranchSample& from, const BranchSample& to)> accept_step = {}) {
  const Eigen::Index n = ring.dimension();
  Eigen::VectorXd x0 = Eigen::VectorXd::Zero(n);
  x0(0) = 1.0;
  for (Eigen::Index i = 2; i < n; ++i) x0(i) = RingFamily::kQ;
  Eigen::VectorXd functional = Eigen::VectorXd::Zero(n);
  functional(1) = 2.0;  // any scale: the trace uses the unit functional
  Eigen::VectorXd direction = Eigen::VectorXd::Zero(n);
  direction(0) = 0.5;
  for (Eigen::Index i = 2; i < n; ++i) direction(i) = 0.5 * RingFamily::kQ;
  ArclengthOptions options;
  options.initial_step = 0.1;
  options.max_step = 0.2;
  options.parameter_max = 3.0;
  options.gradient_tolerance = 1e-11;
  options.accept_step = std::move(accept_step);
  return trace_branch_with_phase_condition(ring, functional, x0, 1.0, direction, 1.0, {}, options,
                                           [&](const BranchSample& s) { samples.push_back(s); });
}

TEST(PhaseConditionTrace, HoldsAnExactSymmetryOrbitWithAVanishingMultiplier) {
  RingFamily ring(2, 0.0);
  std::vector<BranchSample> samples;
  const BranchTrace trace = trace_ring(ring, samples);
  EXPECT_TRUE(trace.reached_bound) << trace.message;
  EXPECT_TRUE(trace.special_points.empty());
  ASSERT_GT(samples.size(), 5u);
  Eigen::Index checked = 0;
  for (const BranchSample& s : samples) {
    ASSERT_EQ(s.x.size(), 4) << "the multiplier is stripped from the samples";
    EXPECT_NEAR(s.x(1), 0.0, 1e-12);
    EXPECT_NEAR(s.x(0), std::sqrt(s.parameter), 1e-9);
    // Stable on the hyperplane: the orbit's neutral direction is left out of the count.
    EXPECT_EQ(s.negative_eigenvalues, 0);
    Eigen::VectorXd g;
    ring.evaluate(s.x, s.parameter, &g, nullptr);
    EXPECT_NEAR(phase_multiplier(g, Eigen::Vector4d(0, 1, 0, 0), {}), 0.0, 1e-10);
    ++checked;
  }
  EXPECT_EQ(checked, static_cast<Eigen::Index>(samples.size()));
  EXPECT_GE(trace.last.parameter, 3.0);  // the trace stops at the first sample past the bound
}

TEST(PhaseConditionTrace, TheMultiplierIsTheForceThatBreaksTheSymmetry) {
  // With E + tilt x y the hyperplane y = 0 is no longer an orbit of equilibria: on it the
  // gradient's y component is tilt x, which the multiplier holds.
  const double tilt = 1e-3;
  RingFamily ring(2, tilt);
  std::vector<BranchSample> samples;
  const BranchTrace trace = trace_ring(ring, samples);
  EXPECT_TRUE(trace.reached_bound) << trace.message;
  ASSERT_GT(samples.size(), 5u);
  for (const BranchSample& s : samples) {
    EXPECT_NEAR(s.x(1), 0.0, 1e-12);
    Eigen::VectorXd g;
    ring.evaluate(s.x, s.parameter, &g, nullptr);
    EXPECT_NEAR(g(0), 0.0, 1e-10);
    EXPECT_NEAR(phase_multiplier(g, Eigen::Vector4d(0, 1, 0, 0), {}), -tilt * s.x(0), 1e-10);
  }
}

TEST(PhaseConditionTrace, TheStepTestSeesStatesWithoutTheMultiplier) {
  // ArclengthOptions::accept_step is the caller's test of its own states (e.g. a symmetry
  // measure that needs the model's unknowns): it must not see the multiplier appended.
  RingFamily ring(2, 1e-3);
  std::vector<BranchSample> plain, tested;
  const BranchTrace reference = trace_ring(ring, plain);
  int calls = 0, wrong_sizes = 0;
  const BranchTrace trace =
      trace_ring(ring, tested, [&](const BranchSample& from, const BranchSample& to) {
        ++calls;
        for (const BranchSample* s : {&from, &to})
          if (s->x.size() != 4 || s->tangent_state.size() != 4) ++wrong_sizes;
        return true;
      });
  EXPECT_GT(calls, 5);
  EXPECT_EQ(wrong_sizes, 0);
  // A test that accepts every step leaves the trace as it is.
  ASSERT_EQ(tested.size(), plain.size());
  for (std::size_t i = 0; i < plain.size(); ++i) EXPECT_EQ(tested[i].parameter, plain[i].parameter);
  EXPECT_EQ(trace.message, reference.message);
}

TEST(PhaseMultiplier, IgnoresThePinnedDofs) {
  const Eigen::Vector3d g(1.0, 2.0, 100.0), c(0.5, 1.0, 1.0);
  EXPECT_NEAR(phase_multiplier(g, c, {2}), -2.0, 1e-15);
  EXPECT_THROW(phase_multiplier(g, Eigen::Vector3d(0, 0, 1), {2}), std::invalid_argument);
  EXPECT_THROW(phase_multiplier(g, Eigen::Vector2d(1, 1), {}), std::invalid_argument);
}

}  // namespace
}  // namespace growshell
