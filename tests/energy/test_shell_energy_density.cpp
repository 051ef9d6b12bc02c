// Finite-difference checks of the quadrature-point energy: gradient and Hessian with respect
// to the 15-entry surface jet, and the derivative of the gradient with respect to a growth
// parameter (through the target metric), for both stretching laws; closed forms; the
// small-strain agreement of the laws and their ellipticity under compression.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <tuple>

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

class ShellDensityDerivatives
    : public ::testing::TestWithParam<std::tuple<double, StretchingLaw>> {
 protected:
  double thickness() const { return std::get<0>(GetParam()); }
  Material material() const { return {1e4, 0.3, std::get<1>(GetParam())}; }
};

TEST_P(ShellDensityDerivatives, GradientMatchesFiniteDifferences) {
  std::mt19937 rng(7);
  const Material material = this->material();
  for (int trial = 0; trial < 20; ++trial) {
    const JetVector s = random_jet_vector(rng);
    const ShellPointRest rest = random_rest(rng, thickness());
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
  const Material material = this->material();
  for (int trial = 0; trial < 20; ++trial) {
    const JetVector s = random_jet_vector(rng);
    const ShellPointRest rest = random_rest(rng, thickness());
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
  const Material material = this->material();
  for (int trial = 0; trial < 20; ++trial) {
    const JetVector s = random_jet_vector(rng);
    ShellPointRest rest = random_rest(rng, thickness());
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
INSTANTIATE_TEST_SUITE_P(
    ThicknessesAndLaws, ShellDensityDerivatives,
    ::testing::Combine(::testing::Values(1e-4, 1e-3, 0.02, 0.3),
                       ::testing::Values(StretchingLaw::kSaintVenantKirchhoff,
                                         StretchingLaw::kNeoHookean)));

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
  const Material material{2.0, 0.25, StretchingLaw::kSaintVenantKirchhoff};
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

TEST(ShellDensity, NeoHookeanIsotropicStrainGivesClosedForm) {
  // a = (1 + t)^2 I, abar = I: tr M = 2 (1+t)^2, L = ln det M = 4 ln(1+t).
  const Material material{2.0, 0.25, StretchingLaw::kNeoHookean};
  const double t = -0.3, h = 0.1, nu = material.poisson_ratio;
  SurfaceJet jet{{1 + t, 0, 0}, {0, 1 + t, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  const ShellPointRest rest{Eigen::Matrix2d::Identity(), 0.5, h};
  const double L = 4 * std::log(1 + t);
  const double Us = 0.5 * (1 - nu) * (2 * (1 + t) * (1 + t) - 2 - L) + 0.25 * nu * L * L;
  EXPECT_NEAR(shell_point_energy(jet, rest, material).stretching,
              0.5 * stretching_modulus(material, h) * Us, 1e-15);
}

TEST(ShellDensity, LawsAgreeToSecondOrderInTheStrain) {
  // Both laws are nu (tr e)^2 + (1 - nu) tr(e^2) + O(e^3): halving a random strain halves the
  // relative difference of the stretching energies (ratio 2 within 5%), and at strain 1e-4 it
  // is below 1e-3.
  std::mt19937 rng(5);
  const ShellPointRest rest = random_rest(rng, 0.01);
  const Eigen::Matrix2d direction = (Eigen::Matrix2d() << 0.7, 0.2, 0.2, -0.4).finished();
  auto relative_difference = [&](double size) {
    // a = abar + 2 size * direction realised by a1, a2 = columns of chol(a).
    const Eigen::Matrix2d a = rest.target_metric + 2 * size * direction;
    const Eigen::Matrix2d U = a.llt().matrixU();
    const SurfaceJet jet{{U(0, 0), 0, 0}, {U(0, 1), U(1, 1), 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    const double svk = shell_point_energy(
        jet, rest, {1e4, 0.3, StretchingLaw::kSaintVenantKirchhoff}).stretching;
    const double nh =
        shell_point_energy(jet, rest, {1e4, 0.3, StretchingLaw::kNeoHookean}).stretching;
    return std::abs(nh - svk) / svk;
  };
  EXPECT_LT(relative_difference(1e-4), 1e-3);
  EXPECT_NEAR(relative_difference(2e-3) / relative_difference(1e-3), 2.0, 0.1);
}

// Smallest eigenvalue over in-plane directions n of the acoustic tensor
// Q_ik(n) = d2W / dF_ia dF_kb n_a n_b of a flat sheet with F = diag(stretch_1, stretch_2),
// read from the jet Hessian (a_a = F e_a; the in-plane entries of a_1, a_2).
double smallest_acoustic_eigenvalue(double stretch_1, double stretch_2, StretchingLaw law) {
  const Material material{1e4, 0.3, law};
  const SurfaceJet jet{{stretch_1, 0, 0}, {0, stretch_2, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  const ShellPointRest rest{Eigen::Matrix2d::Identity(), 0.5, 0.01};
  JetVector g;
  JetMatrix H;
  shell_point_hessian(jet, rest, material, g, H);
  const int block[2] = {kJetA1, kJetA2};
  double smallest = 1e300;
  for (int k = 0; k < 180; ++k) {
    const double angle = M_PI * k / 180.0, n[2] = {std::cos(angle), std::sin(angle)};
    Eigen::Matrix2d Q = Eigen::Matrix2d::Zero();
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        for (int a = 0; a < 2; ++a)
          for (int b = 0; b < 2; ++b) Q(i, j) += H(block[a] + i, block[b] + j) * n[a] * n[b];
    smallest = std::min(smallest, Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(Q)
                                      .eigenvalues()(0));
  }
  return smallest;
}

TEST(ShellDensity, SaintVenantKirchhoffLosesEllipticityUnderLargeCompression) {
  // With the radial stretch 1 and nu = 0.3 the quadratic law loses ellipticity below a
  // circumferential stretch of 0.655 (an independent 2x2 computation gives the threshold); the
  // neo-Hookean law stays elliptic down to 0.2.
  EXPECT_GT(smallest_acoustic_eigenvalue(1.0, 0.67, StretchingLaw::kSaintVenantKirchhoff), 0.0);
  EXPECT_LT(smallest_acoustic_eigenvalue(1.0, 0.64, StretchingLaw::kSaintVenantKirchhoff), 0.0);
  for (double stretch : {0.9, 0.64, 0.4, 0.2})
    EXPECT_GT(smallest_acoustic_eigenvalue(1.0, stretch, StretchingLaw::kNeoHookean), 0.0)
        << "stretch " << stretch;
}

}  // namespace
}  // namespace growshell
