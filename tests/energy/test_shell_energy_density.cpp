// Finite-difference checks of the quadrature-point energy: gradient and Hessian with respect
// to the 15-entry surface jet, and the derivative of the gradient with respect to a growth
// parameter (through the target metric).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "libshell/energy/shell_energy_density.hpp"

namespace growshell {
namespace {

JetVector random_jet_vector(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  JetVector s;
  for (int i = 0; i < 15; ++i) s(i) = u(rng);
  // Keep a_1, a_2 well away from parallel: a stretched, sheared, bent patch.
  s.segment<3>(kJetA1) += Eigen::Vector3d(1.5, 0.0, 0.0);
  s.segment<3>(kJetA2) += Eigen::Vector3d(0.0, 1.5, 0.0);
  return s;
}

SurfaceJet to_jet(const JetVector& s) {
  return {s.segment<3>(kJetA1), s.segment<3>(kJetA2), s.segment<3>(kJetA11),
          s.segment<3>(kJetA22), s.segment<3>(kJetA12)};
}

ShellPointRest random_rest(std::mt19937& rng, double thickness) {
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  Eigen::Matrix2d F;
  F << 1.0 + u(rng), u(rng), u(rng), 1.0 + u(rng);
  return {F.transpose() * F, 0.17, thickness};
}

double energy_of(const JetVector& s, const ShellPointRest& rest, const Material& m) {
  return shell_point_energy(to_jet(s), rest, m).total();
}

// Central differences have truncation error O(step^2) and rounding O(eps |E| / step); with
// step = 1e-5 on O(1) inputs both are ~1e-10 relative, so 1e-6 leaves a wide margin and still
// fails for any wrong term (those give O(1) relative errors).
constexpr double kStep = 1e-5;
constexpr double kTolerance = 1e-6;

class ShellDensityDerivatives : public ::testing::TestWithParam<double> {};

TEST_P(ShellDensityDerivatives, GradientMatchesFiniteDifferences) {
  std::mt19937 rng(7);
  Material material{1e4, 0.3};
  for (int trial = 0; trial < 20; ++trial) {
    const JetVector s = random_jet_vector(rng);
    const ShellPointRest rest = random_rest(rng, GetParam());
    JetVector g;
    const double E = shell_point_gradient(to_jet(s), rest, material, g);
    EXPECT_NEAR(E, energy_of(s, rest, material), 1e-12 * std::abs(E));
    JetVector fd;
    for (int i = 0; i < 15; ++i) {
      JetVector sp = s, sm = s;
      sp(i) += kStep;
      sm(i) -= kStep;
      fd(i) = (energy_of(sp, rest, material) - energy_of(sm, rest, material)) / (2 * kStep);
    }
    EXPECT_LE((g - fd).norm(), kTolerance * g.norm()) << "trial " << trial;
  }
}

TEST_P(ShellDensityDerivatives, HessianMatchesFiniteDifferencesOfGradient) {
  std::mt19937 rng(11);
  Material material{1e4, 0.3};
  for (int trial = 0; trial < 20; ++trial) {
    const JetVector s = random_jet_vector(rng);
    const ShellPointRest rest = random_rest(rng, GetParam());
    JetVector g, g_from_hessian;
    JetMatrix H;
    const double E = shell_point_hessian(to_jet(s), rest, material, g_from_hessian, H);
    shell_point_gradient(to_jet(s), rest, material, g);
    EXPECT_NEAR(E, energy_of(s, rest, material), 1e-12 * std::abs(E));
    EXPECT_LE((g - g_from_hessian).norm(), 1e-14 * g.norm());
    EXPECT_LE((H - H.transpose()).norm(), 1e-12 * H.norm());
    JetMatrix fd;
    for (int i = 0; i < 15; ++i) {
      JetVector sp = s, sm = s, gp, gm;
      sp(i) += kStep;
      sm(i) -= kStep;
      shell_point_gradient(to_jet(sp), rest, material, gp);
      shell_point_gradient(to_jet(sm), rest, material, gm);
      fd.col(i) = (gp - gm) / (2 * kStep);
    }
    EXPECT_LE((H - fd).norm(), kTolerance * H.norm()) << "trial " << trial;
  }
}

TEST_P(ShellDensityDerivatives, ParameterDerivativeOfGradientMatchesFiniteDifferences) {
  std::mt19937 rng(13);
  Material material{1e4, 0.3};
  for (int trial = 0; trial < 20; ++trial) {
    const JetVector s = random_jet_vector(rng);
    ShellPointRest rest = random_rest(rng, GetParam());
    Eigen::Matrix2d dabar;
    dabar << 0.4, -0.1, -0.1, 0.7;
    const JetVector exact =
        shell_point_gradient_parameter_derivative(to_jet(s), rest, material, dabar);
    ShellPointRest plus = rest, minus = rest;
    plus.target_metric += kStep * dabar;
    minus.target_metric -= kStep * dabar;
    JetVector gp, gm;
    shell_point_gradient(to_jet(s), plus, material, gp);
    shell_point_gradient(to_jet(s), minus, material, gm);
    const JetVector fd = (gp - gm) / (2 * kStep);
    EXPECT_LE((exact - fd).norm(), kTolerance * exact.norm()) << "trial " << trial;
  }
}

// Thicknesses from the thinnest to the thickest sheet of the brief, and beyond: the
// bending/stretching stiffness ratio spans 1e-8 .. 1e-1.
INSTANTIATE_TEST_SUITE_P(Thicknesses, ShellDensityDerivatives,
                         ::testing::Values(1e-4, 1e-3, 0.02, 0.3));

TEST(ShellDensity, RigidRotationLeavesEnergyUnchanged) {
  std::mt19937 rng(3);
  Material material{1e4, 0.3};
  const JetVector s = random_jet_vector(rng);
  const ShellPointRest rest = random_rest(rng, 0.05);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  JetVector rotated;
  for (int b = 0; b < 5; ++b) rotated.segment<3>(3 * b) = R * s.segment<3>(3 * b);
  const ShellPointEnergy a = shell_point_energy(to_jet(s), rest, material);
  const ShellPointEnergy c = shell_point_energy(to_jet(rotated), rest, material);
  EXPECT_NEAR(a.stretching, c.stretching, 1e-13 * a.stretching);
  EXPECT_NEAR(a.bending, c.bending, 1e-13 * a.bending);
}

TEST(ShellDensity, IsotropicStrainGivesClosedFormDensities) {
  // a = (1 + t)^2 abar with abar = I, b = diag(k1, k2): U_s = 2 (1 + nu) e^2 with
  // e = ((1+t)^2 - 1)/2, U_b = k1^2 + k2^2 + 2 nu k1 k2.
  Material material{2.0, 0.25};
  const double t = 0.1, k1 = 0.3, k2 = -0.2, h = 0.1;
  SurfaceJet jet{{1 + t, 0, 0}, {0, 1 + t, 0}, {0, 0, k1}, {0, 0, k2}, {0, 0, 0}};
  const ShellPointRest rest{Eigen::Matrix2d::Identity(), 0.5, h};
  const ShellPointEnergy p = shell_point_energy(jet, rest, material);
  const double e = ((1 + t) * (1 + t) - 1) / 2;
  const double Us = 2 * (1 + material.poisson_ratio) * e * e;
  const double kk1 = k1 / ((1 + t) * (1 + t)) * (1 + t), kk2 = k2 / (1 + t);
  // b_ab = a_ab . n with n = e_z: b = diag(k1, k2), kappa = abar^-1 b = diag(k1, k2).
  (void)kk1;
  (void)kk2;
  const double Ub = k1 * k1 + k2 * k2 + 2 * material.poisson_ratio * k1 * k2;
  EXPECT_NEAR(p.stretching, 0.5 * stretching_modulus(material, h) * Us, 1e-15);
  EXPECT_NEAR(p.bending, 0.5 * bending_modulus(material, h) * Ub, 1e-15);
  EXPECT_NEAR(p.bending_density_integral, 0.5 * Ub, 1e-15);
  EXPECT_NEAR(p.current_area, 0.5 * (1 + t) * (1 + t), 1e-15);
}

}  // namespace
}  // namespace growshell
