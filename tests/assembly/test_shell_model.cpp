// The assembled shell energy: finite-difference checks of gradient, Hessian and
// d(gradient)/d(phi_e); invariances; closed-form energies of exactly representable states.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>
#include <thread>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "tests/support/polygon_disc.hpp"

namespace growshell {
namespace {

ShellModelSettings settings_with(double h, int quadrature_degree = 2, int threads = 0) {
  ShellModelSettings s;
  s.material = {1e4, 0.3};
  s.thickness = constant_thickness(h);
  s.quadrature_degree = quadrature_degree;
  s.threads = threads;
  return s;
}

TriangleMesh small_disc(int rings = 3) {
  DiscMeshOptions o;
  o.rings = rings;
  return make_disc_mesh(o);
}

/// A bent, stretched configuration: a saddle plus random noise on the reference.
Eigen::VectorXd bent_state(const ShellModel& model, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd x = model.reference_positions();
  for (Eigen::Index v = 0; v < x.size() / 3; ++v) {
    const double X = x(3 * v), Y = x(3 * v + 1);
    x(3 * v + 2) += 0.3 * (X * X - Y * Y);
    for (int c = 0; c < 3; ++c) x(3 * v + c) += noise * u(rng);
  }
  return x;
}

// Central differences of the assembled energy with step 1e-6 m on O(1) coordinates: the
// truncation error is ~1e-12 and the rounding ~1e-16 |E| / 1e-6, both far below the stated
// 1e-6 relative tolerance, while any wrong or missing term gives O(1) errors.
constexpr double kStep = 1e-6;

/// Checks the energy against energy_breakdown, and the gradient, the Hessian and
/// d(gradient)/d(phi_e) against central differences (relative 1e-6), at x and phi_e.
void expect_derivatives_match_finite_differences(const ShellModel& model, const Eigen::VectorXd& x,
                                                 double phi_e) {
  const Eigen::Index n = model.dimension();
  Eigen::VectorXd g;
  Eigen::SparseMatrix<double> H = model.hessian_pattern();
  const double E = model.evaluate(x, phi_e, &g, &H);
  EXPECT_NEAR(E, model.evaluate(x, phi_e, nullptr, nullptr), 1e-12 * E);
  EXPECT_NEAR(E, model.energy_breakdown(x, phi_e).total(), 1e-12 * E);

  Eigen::VectorXd fd_g(n);
  Eigen::MatrixXd fd_H(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::VectorXd xp = x, xm = x, gp, gm;
    xp(i) += kStep;
    xm(i) -= kStep;
    const double Ep = model.evaluate(xp, phi_e, &gp, nullptr);
    const double Em = model.evaluate(xm, phi_e, &gm, nullptr);
    fd_g(i) = (Ep - Em) / (2 * kStep);
    fd_H.col(i) = (gp - gm) / (2 * kStep);
  }
  EXPECT_LE((g - fd_g).norm(), 1e-6 * g.norm());
  const Eigen::MatrixXd H_dense = Eigen::MatrixXd(H).selfadjointView<Eigen::Upper>();
  EXPECT_LE((H_dense - fd_H).norm(), 1e-6 * H_dense.norm());

  const Eigen::VectorXd dg = model.gradient_parameter_derivative(x, phi_e);
  const double dphi = 1e-6;
  Eigen::VectorXd gp, gm;
  model.evaluate(x, phi_e + dphi, &gp, nullptr);
  model.evaluate(x, phi_e - dphi, &gm, nullptr);
  EXPECT_LE((dg - (gp - gm) / (2 * dphi)).norm(), 1e-6 * dg.norm());
}

class ShellModelDerivatives : public ::testing::TestWithParam<std::tuple<double, int>> {};

TEST_P(ShellModelDerivatives, GradientHessianAndExcessAngleDerivativeMatchFiniteDifferences) {
  const auto [h, degree] = GetParam();
  ShellModel model(small_disc(), settings_with(h, degree));
  expect_derivatives_match_finite_differences(model, bent_state(model, 0.02, 1), 1.3);
}

INSTANTIATE_TEST_SUITE_P(ThicknessAndQuadrature, ShellModelDerivatives,
                         ::testing::Combine(::testing::Values(1e-3, 0.04),
                                            ::testing::Values(1, 2, 6)));

TEST(ShellModel, SmoothedGrowthAndNeoHookeanDerivativesMatchFiniteDifferences) {
  // The same checks with the other stretching law and a smoothed centre whose radius spans
  // several elements of the small disc.
  ShellModelSettings settings = settings_with(0.04, 2);
  settings.material.stretching_law = StretchingLaw::kNeoHookean;
  settings.growth.smoothing_radius = 0.3;
  ShellModel model(small_disc(), settings);
  expect_derivatives_match_finite_differences(model, bent_state(model, 0.02, 5), 1.3);
}

class IrregularMeshDerivatives : public ::testing::TestWithParam<int> {};

TEST_P(IrregularMeshDerivatives, GradientHessianAndExcessAngleDerivativeMatchFiniteDifferences) {
  // A disc whose centre has valence n (its n elements have an extraordinary corner), curved and
  // perturbed, with rim elements next to the ghost layer too; and a thin and a thick sheet.
  const int n = GetParam();
  for (const double h : {1e-3, 0.04}) {
    SCOPED_TRACE("valence " + std::to_string(n) + ", h = " + std::to_string(h));
    ShellModel model(test_support::polygon_disc(n, 4, 0.25), settings_with(h, 2));
    ASSERT_EQ(model.patches().num_irregular(), n == 3 ? 6 : n);
    expect_derivatives_match_finite_differences(model, bent_state(model, 0.02, 3), 1.3);
  }
}

INSTANTIATE_TEST_SUITE_P(Valences3To12, IrregularMeshDerivatives,
                         ::testing::Values(3, 4, 5, 7, 8, 12));

TEST(ShellModel, IrregularFlatDiscHasNoEnergyAndItsRigidMotionsNone) {
  // The reference of a mesh with an extraordinary vertex is stress-free, and stays so when moved.
  ShellModel model(test_support::polygon_disc(5, 5, 0.2), settings_with(0.02));
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
  Eigen::VectorXd x = model.reference_positions();
  for (Eigen::Index v = 0; v < x.size() / 3; ++v)
    x.segment<3>(3 * v) = R * x.segment<3>(3 * v) + Eigen::Vector3d(0.1, 0.2, 0.3);
  Eigen::VectorXd g;
  EXPECT_LT(model.evaluate(model.reference_positions(), 0.0, nullptr, nullptr), 1e-25);
  EXPECT_LT(model.evaluate(x, 0.0, &g, nullptr), 1e-20);
  EXPECT_LT(g.cwiseAbs().maxCoeff(), 1e-10 * model.natural_force_scale());
}

TEST(ShellModel, AssemblyIsIndependentOfThreadCount) {
  ShellModel one(small_disc(5), settings_with(0.02, 2, 1));
  ShellModel two(small_disc(5), settings_with(0.02, 2, 2));
  const Eigen::VectorXd x = bent_state(one, 0.01, 2);
  Eigen::VectorXd g1, g2;
  Eigen::SparseMatrix<double> H1 = one.hessian_pattern(), H2 = two.hessian_pattern();
  const double E1 = one.evaluate(x, 2.0, &g1, &H1), E2 = two.evaluate(x, 2.0, &g2, &H2);
  // Only the order of the floating-point sums differs.
  EXPECT_NEAR(E1, E2, 1e-13 * E1);
  EXPECT_LE((g1 - g2).norm(), 1e-12 * g1.norm());
  EXPECT_LE((Eigen::VectorXd(Eigen::Map<Eigen::VectorXd>(H1.valuePtr(), H1.nonZeros())) -
             Eigen::Map<Eigen::VectorXd>(H2.valuePtr(), H2.nonZeros()))
                .norm(),
            1e-12 * H1.norm());
}

TEST(ShellModel, EvaluationDependsOnlyOnItsArgumentsNotOnEarlierCalls) {
  // phi_e is an argument, not state: interleaved evaluations at two angles, and the same ones
  // from two threads at once on one model, give the same bits as a fresh model.
  const ShellModel model(small_disc(5), settings_with(0.02, 2, 1));
  const Eigen::VectorXd x = bent_state(model, 0.01, 4);
  struct Result {
    double energy = 0.0;
    Eigen::VectorXd gradient, derivative;
    Eigen::SparseMatrix<double> hessian;
  };
  const auto at = [&](const ShellModel& m, double phi) {
    Result r;
    r.hessian = m.hessian_pattern();
    r.energy = m.evaluate(x, phi, &r.gradient, &r.hessian);
    r.derivative = m.gradient_parameter_derivative(x, phi);
    return r;
  };
  const auto same = [](const Result& a, const Result& b) {
    return a.energy == b.energy && a.gradient == b.gradient && a.derivative == b.derivative &&
           Eigen::Map<const Eigen::VectorXd>(a.hessian.valuePtr(), a.hessian.nonZeros()) ==
               Eigen::Map<const Eigen::VectorXd>(b.hessian.valuePtr(), b.hessian.nonZeros());
  };
  const Result first = at(model, 1.0);
  const Result other = at(model, 2.0);
  const Result again = at(model, 1.0);
  EXPECT_TRUE(same(first, again));
  EXPECT_NE(first.energy, other.energy);
  EXPECT_TRUE(same(first, at(ShellModel(small_disc(5), settings_with(0.02, 2, 1)), 1.0)));
  Result in_thread_a, in_thread_b;
  std::thread a([&] { in_thread_a = at(model, 1.0); });
  std::thread b([&] { in_thread_b = at(model, 2.0); });
  a.join();
  b.join();
  EXPECT_TRUE(same(in_thread_a, first));
  EXPECT_TRUE(same(in_thread_b, other));
}

TEST(ShellModel, RigidMotionsOfTheFlatStateCarryNoEnergyOrForce) {
  ShellModel model(small_disc(6), settings_with(0.02));
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.3, -1.0, 0.5).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(0.4, -2.0, 3.0);
  Eigen::VectorXd x = model.reference_positions();
  for (Eigen::Index v = 0; v < x.size() / 3; ++v) x.segment<3>(3 * v) = R * x.segment<3>(3 * v) + t;
  Eigen::VectorXd g;
  const double E = model.evaluate(x, 0.0, &g, nullptr);
  // Scales: a unit strain would cost Y h * area ~ 600 J; a 1/R curvature Y h^3 ~ 0.08 J.
  EXPECT_LT(std::abs(E), 1e-24);
  EXPECT_LT(g.lpNorm<Eigen::Infinity>(), 1e-10 * model.natural_force_scale());
}

TEST(ShellModel, EnergyOfABentStateIsInvariantUnderRotation) {
  ShellModel model(small_disc(5), settings_with(0.02));
  const double phi_e = 2.5;
  const Eigen::VectorXd x = bent_state(model, 0.01, 3);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(2.2, Eigen::Vector3d(1.0, 1.0, -0.4).normalized()).toRotationMatrix();
  Eigen::VectorXd y = x;
  for (Eigen::Index v = 0; v < x.size() / 3; ++v) y.segment<3>(3 * v) = R * x.segment<3>(3 * v);
  Eigen::VectorXd gx, gy;
  const double Ex = model.evaluate(x, phi_e, &gx, nullptr), Ey = model.evaluate(y, phi_e, &gy, nullptr);
  EXPECT_NEAR(Ex, Ey, 1e-12 * Ex);
  for (Eigen::Index v = 0; v < x.size() / 3; ++v)
    EXPECT_LE((R * gx.segment<3>(3 * v) - gy.segment<3>(3 * v)).norm(), 1e-10 * gx.norm());
}

TEST(ShellModel, UniformInPlaneStretchGivesTheClosedFormEnergy) {
  // x = (1 + s) X: eps = e I with e = ((1+s)^2 - 1)/2, U_s = 2 (1 + nu) e^2, exactly
  // representable, so the only error is rounding.
  const double h = 0.02, s = 0.03;
  ShellModel model(small_disc(6), settings_with(h));
  const Eigen::VectorXd x = (1 + s) * model.reference_positions();
  const ShellEnergyBreakdown parts = model.energy_breakdown(x, 0.0);
  const double e = ((1 + s) * (1 + s) - 1) / 2;
  const double expected = stretching_modulus(model.settings().material, h) * 2 *
                          (1 + model.settings().material.poisson_ratio) * e * e *
                          model.reference().reference_area();
  EXPECT_NEAR(parts.stretching, expected, 1e-12 * expected);
  EXPECT_LT(parts.bending, 1e-20);
  EXPECT_NEAR(parts.current_area, (1 + s) * (1 + s) * model.reference().reference_area(),
              1e-12);
}

TEST(ShellModel, FlatDiscGrownButNotRelaxedGivesTheClosedFormEnergy) {
  // At the reference positions the metric is A while abar = diag(1, lambda^2) in the polar
  // frame: eps has eigenvalues 0 and (1/lambda^2 - 1)/2, so U_s = eps_t^2 and the grown
  // measure is lambda times the reference area.
  const double h = 0.02;
  for (double phi : {0.5, 3.0, 4 * std::numbers::pi}) {
    ShellModel model(small_disc(6), settings_with(h));
    const double lambda = 1 + phi / (2 * std::numbers::pi);
    const double eps_t = 0.5 * (1 / (lambda * lambda) - 1);
    const ShellEnergyBreakdown parts = model.energy_breakdown(model.reference_positions(), phi);
    const double area = model.reference().reference_area();
    const double expected =
        stretching_modulus(model.settings().material, h) * eps_t * eps_t * lambda * area;
    EXPECT_NEAR(parts.stretching, expected, 1e-12 * expected) << "phi_e = " << phi;
    EXPECT_NEAR(parts.grown_area, lambda * area, 1e-12 * area);
  }
}

TEST(ShellModel, BadInputIsRejectedWithTheOffendingValueNamed) {
  ShellModelSettings s = settings_with(0.02);
  s.material.poisson_ratio = 0.5;
  try {
    ShellModel model(small_disc(), s);
    FAIL() << "nu = 0.5 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("poisson_ratio"), std::string::npos) << e.what();
  }
  s = settings_with(0.0);
  try {
    ShellModel model(small_disc(), s);
    FAIL() << "h = 0 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("thickness"), std::string::npos) << e.what();
  }
  s = settings_with(0.02);
  s.thickness = [](const Eigen::Vector3d& X) { return X.x() > 0.5 ? -1.0 : 0.02; };
  EXPECT_THROW(ShellModel(small_disc(), s), std::invalid_argument);
  ShellModel model(small_disc(), settings_with(0.02));
  const Eigen::VectorXd flat = model.reference_positions();
  EXPECT_THROW(model.evaluate(flat, std::nan(""), nullptr, nullptr), std::invalid_argument);
  EXPECT_THROW(model.evaluate(flat, -7.0, nullptr, nullptr), std::invalid_argument);
  EXPECT_THROW(model.gradient_parameter_derivative(flat, std::nan("")), std::invalid_argument);
  EXPECT_THROW(model.energy_breakdown(flat, -7.0), std::invalid_argument);
  EXPECT_FALSE(model.accepts_parameter(-2 * std::numbers::pi));
  EXPECT_TRUE(model.accepts_parameter(-6.0));
  EXPECT_THROW(model.evaluate(Eigen::VectorXd::Zero(5), 0.0, nullptr, nullptr), std::invalid_argument);
}

TEST(ShellModel, DegenerateConfigurationGivesNonFiniteEnergyNotACrash) {
  ShellModel model(small_disc(), settings_with(0.02));
  const Eigen::VectorXd collapsed = Eigen::VectorXd::Zero(model.dimension());
  EXPECT_FALSE(std::isfinite(model.evaluate(collapsed, 0.0, nullptr, nullptr)));
}

}  // namespace
}  // namespace growshell

namespace growshell {
namespace {

TEST(ShellModel, CylinderBendingEnergyConvergesToTheAnalyticValue) {
  // A strip L x W wrapped isometrically onto a cylinder of radius rho (control points sampled
  // on it): kappa = diag(1/rho, 0), U_b = 1/rho^2, E_b = c_b L W / rho^2. The limit surface of
  // sampled points lies O(l^2) inside the cylinder, so the error must fall like l^2.
  const double rho = 0.5, h = 0.01;
  const Material material{1e4, 0.3};
  std::vector<double> errors;
  for (int cells : {8, 16, 32}) {
    StripMeshOptions o;
    o.length = 1.0;
    o.width = 0.25;
    o.cells_x = cells;
    o.cells_y = cells / 4;
    TriangleMesh mesh = make_strip_mesh(o);
    ShellModelSettings s;
    s.material = material;
    s.thickness = constant_thickness(h);
    ShellModel model(mesh, s);
    Eigen::VectorXd x = model.reference_positions();
    for (Eigen::Index v = 0; v < x.size() / 3; ++v) {
      const double X = x(3 * v);
      x(3 * v) = rho * std::sin(X / rho);
      x(3 * v + 2) = rho * (1 - std::cos(X / rho));
    }
    const double area = model.reference().reference_area();
    const double expected = bending_modulus(material, h) * area / (rho * rho);
    errors.push_back(std::abs(model.energy_breakdown(x, 0.0).bending / expected - 1.0));
  }
  std::printf("cylinder bending energy relative errors: %.3e %.3e %.3e\n", errors[0], errors[1],
              errors[2]);
  for (std::size_t k = 0; k + 1 < errors.size(); ++k)
    EXPECT_GT(std::log2(errors[k] / errors[k + 1]), 1.8);
  EXPECT_LT(errors.back(), 2e-3);  // measured 1.30e-3 at 32 cells
}

}  // namespace
}  // namespace growshell
