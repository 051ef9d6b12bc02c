// Contact penalty P = (k/2) sum m max(0, offset - d)^2: closed form for a point over a
// triangle, zero when every gap exceeds the offset, the sum over pairs on a folded disc,
// gradient and Hessian against central differences, Hessian pattern against every nonzero of a
// finite-difference Hessian, PenalizedEnergy = shell + penalty (and Newton runs on it) and, as
// a family in the excess angle, the shell's parameter and parameter derivative, the stiffness
// scale, bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/objective_at_parameter.hpp"
#include "core/parametrized_objective.hpp"
#include "libshell/contact/contact_penalty.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "solvers/newton/newton_solver.hpp"
#include "support/dense_symmetric.hpp"
#include "tests/support/expect_invalid_argument.hpp"
#include "tests/support/folded_disc_scene.hpp"

namespace growshell {
namespace {

using test_support::dense_symmetric;
using test_support::expect_invalid_argument_containing;
using test_support::FoldedDiscScene;

TEST(ContactPenalty, PointOverTriangleMatchesTheClosedForm) {
  // Identity proxy: the point (0.2, 0.3, z) over the face of (0,0,0), (1,0,0), (0,1,0):
  // d = z, P = (k/2)(offset - z)^2, dP/dp_z = -k (offset - z), d2P/dp_z^2 = k, and the
  // triangle's corners take -beta times the point's share.
  ContactProxy proxy;
  proxy.map.resize(12, 12);
  proxy.map.setIdentity();
  proxy.triangles.resize(1, 3);
  proxy.triangles << 0, 1, 2;
  proxy.edges.resize(3, 2);
  proxy.edges << 0, 1, 0, 2, 1, 2;
  proxy.reference_positions.resize(4, 3);
  proxy.reference_positions << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.2, 0.3, 0.04;
  ContactCandidates pairs;
  pairs.vertex_triangle.resize(1, 2);
  pairs.vertex_triangle << 3, 0;
  const double k = 250.0, offset = 0.1, z = 0.04;
  ContactPenalty penalty(proxy, pairs, offset, k, 12);
  Eigen::VectorXd x(12);
  x << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.2, 0.3, z;
  Eigen::VectorXd g;
  Eigen::SparseMatrix<double> H = penalty.hessian_pattern();
  const double P = penalty.evaluate(x, &g, &H);
  EXPECT_NEAR(P, 0.5 * k * (offset - z) * (offset - z), 1e-15);
  Eigen::VectorXd expected_g = Eigen::VectorXd::Zero(12);
  const Eigen::Vector3d beta(0.5, 0.2, 0.3);
  expected_g[11] = -k * (offset - z);
  for (int i = 0; i < 3; ++i) expected_g[3 * i + 2] = beta(i) * k * (offset - z);
  EXPECT_LT((g - expected_g).cwiseAbs().maxCoeff(), 1e-13);
  // In the face region d is linear in the point (d = n . (p - a)), so d2P/dp_z^2 = k exactly.
  EXPECT_NEAR(dense_symmetric(H)(11, 11), k, 1e-12);
  EXPECT_EQ(penalty.active_pairs(x), 1);
  x[11] = 0.15;  // beyond the offset: no contribution
  EXPECT_EQ(penalty.evaluate(x, &g, &H), 0.0);
  EXPECT_EQ(g.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(penalty.active_pairs(x), 0);
}

TEST(ContactPenalty, ZeroWhenEveryGapExceedsTheOffset) {
  const FoldedDiscScene scene(0.02, 1);
  // The layers are 0.08 +- 0.04 m apart (wobble 0.02 on each); find the smallest distance and
  // put the offset below it.
  ContactPenalty probe(scene.proxy, scene.pairs, 0.0, 1.0, scene.model.dimension());
  double smallest = 1e300;
  for (Eigen::Index k = 0; k < probe.constraints().count(); ++k)
    smallest = std::min(smallest, probe.constraints().pair_geometry(scene.x, k).distance);
  ASSERT_GT(smallest, 0.01);
  ContactPenalty penalty(scene.proxy, scene.pairs, 0.99 * smallest, 1e3, scene.model.dimension());
  Eigen::VectorXd g;
  Eigen::SparseMatrix<double> H = penalty.hessian_pattern();
  H.coeffs().setConstant(1.0);  // must be overwritten
  EXPECT_EQ(penalty.evaluate(scene.x, &g, &H), 0.0);
  EXPECT_EQ(g.size(), scene.model.dimension());
  EXPECT_EQ(g.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(H.coeffs().cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(penalty.active_pairs(scene.x), 0);
  EXPECT_GT(penalty.constraints().count(), 100);
}

TEST(ContactPenalty, ValueIsTheSumOverActivePairs) {
  // Recomputed from the pairs' distances and an independent evaluation of the mollifier from
  // the proxy's rest and current positions.
  const FoldedDiscScene scene(0.02, 1);
  const double k = 3e3, offset = 0.1;
  const Eigen::MatrixX3d y = proxy_positions(scene.proxy, scene.x);
  const Eigen::MatrixX3d& Y = scene.proxy.reference_positions;
  for (const bool mollify : {true, false}) {
    ContactPenalty penalty(scene.proxy, scene.pairs, offset, k, scene.model.dimension(),
                           ContactGapOptions{mollify});
    const ContactGapConstraints& c = penalty.constraints();
    double expected = 0.0;
    int active = 0, mollified = 0;
    for (Eigen::Index p = 0; p < c.count(); ++p) {
      const ContactPairGeometry g = c.pair_geometry(scene.x, p);
      if (g.distance >= offset) continue;
      ++active;
      double m = 1.0;
      if (mollify && g.type == ContactPairType::EdgeEdge) {
        const auto row = [](const Eigen::MatrixX3d& M, int i) {
          return Eigen::Vector3d(M.row(i).transpose());
        };
        const Eigen::Vector4i v = g.vertices;
        const double eps =
            edge_edge_mollifier_threshold(row(Y, v(0)), row(Y, v(1)), row(Y, v(2)), row(Y, v(3)));
        m = edge_edge_mollifier(row(y, v(0)), row(y, v(1)), row(y, v(2)), row(y, v(3)), eps);
        mollified += m < 1.0;
      }
      expected += 0.5 * k * m * (offset - g.distance) * (offset - g.distance);
    }
    const double P = penalty.evaluate(scene.x, nullptr, nullptr);
    std::cout << "[ penalty  ] mollify " << mollify << ": " << active << " of " << c.count()
              << " pairs active, " << mollified << " mollified, P = " << P << " J\n";
    EXPECT_GT(active, 100);
    if (mollify) {
      EXPECT_GT(mollified, 0);
    }
    EXPECT_NEAR(P, expected, 1e-13 * expected);
    EXPECT_EQ(penalty.active_pairs(scene.x), active);
  }
}

TEST(ContactPenalty, GradientAndHessianMatchCentralDifferences) {
  const FoldedDiscScene scene(0.02, 1);
  const Eigen::Index n = scene.model.dimension();
  const double k = 3e3, offset = 0.1;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (const bool mollify : {true, false}) {
    ContactPenalty penalty(scene.proxy, scene.pairs, offset, k, n, ContactGapOptions{mollify});
    const ContactGapConstraints& c = penalty.constraints();
    Eigen::SparseMatrix<double> H = penalty.hessian_pattern();
    Eigen::VectorXd g, gp, gm;
    const double h = 1e-6;
    double worst_value = 0.0, worst_gradient = 0.0;
    int skipped = 0, smooth_trials = 0;
    for (int trial = 0; trial < 10 && smooth_trials < 3; ++trial) {
      Eigen::VectorXd v(n);
      for (Eigen::Index i = 0; i < n; ++i) v[i] = U(rng);
      // Skip directions along which a pair changes region or crosses d = offset (where the
      // Hessian jumps): central differences assume one smooth function.
      bool smooth = true;
      for (Eigen::Index p = 0; p < c.count() && smooth; ++p) {
        const ContactPairGeometry g0 = c.pair_geometry(scene.x, p);
        for (const double sign : {1.0, -1.0}) {
          const ContactPairGeometry gs = c.pair_geometry(scene.x + sign * h * v, p);
          smooth = smooth && gs.point_triangle_region == g0.point_triangle_region &&
                   gs.edge_edge_region == g0.edge_edge_region &&
                   (gs.mollifier < 1.0) == (g0.mollifier < 1.0) &&
                   (gs.distance < offset) == (g0.distance < offset);
        }
      }
      if (!smooth) {
        ++skipped;
        continue;
      }
      ++smooth_trials;
      const double P = penalty.evaluate(scene.x, &g, &H);
      const double Pp = penalty.evaluate(scene.x + h * v, &gp, nullptr);
      const double Pm = penalty.evaluate(scene.x - h * v, &gm, nullptr);
      ASSERT_GT(P, 0.0);
      const double fd = (Pp - Pm) / (2.0 * h);
      const double gv = g.dot(v);
      worst_value = std::max(worst_value, std::abs(fd - gv) / std::abs(gv));
      const Eigen::VectorXd fd_g = (gp - gm) / (2.0 * h);
      const Eigen::VectorXd Hv = dense_symmetric(H) * v;
      worst_gradient =
          std::max(worst_gradient, (fd_g - Hv).cwiseAbs().maxCoeff() / Hv.cwiseAbs().maxCoeff());
    }
    std::cout << "[ FD       ] penalty, mollify " << mollify << ": relative error gradient "
              << worst_value << ", Hessian " << worst_gradient << " (" << skipped
              << " random directions skipped)\n";
    // A direction is skipped when some pair changes region, mollifier branch or activity
    // within the step; with ~2000 pairs that is rare, and three smooth directions must remain.
    EXPECT_EQ(smooth_trials, 3);
    // h = 1e-6 m: truncation ~ h^2 |P'''| and rounding ~ 1e-16 P / h, both ~1e-8 relative here.
    EXPECT_LT(worst_value, 1e-6);
    EXPECT_LT(worst_gradient, 1e-5);
  }
}

TEST(ContactPenalty, HessianPatternHoldsEveryNonzero) {
  // The full Hessian by central differences of the gradient along every coordinate: it agrees
  // with the assembled one, and every entry above 1e-6 of the largest is in the pattern.
  const FoldedDiscScene scene(0.02, 1);
  const Eigen::Index n = scene.model.dimension();
  ContactPenalty penalty(scene.proxy, scene.pairs, 0.1, 3e3, n);
  Eigen::SparseMatrix<double> H = penalty.hessian_pattern();
  Eigen::VectorXd g, gp, gm;
  penalty.evaluate(scene.x, &g, &H);
  Eigen::MatrixXd fd(n, n);
  const double h = 1e-6;
  for (Eigen::Index j = 0; j < n; ++j) {
    Eigen::VectorXd xp = scene.x, xm = scene.x;
    xp[j] += h;
    xm[j] -= h;
    penalty.evaluate(xp, &gp, nullptr);
    penalty.evaluate(xm, &gm, nullptr);
    fd.col(j) = (gp - gm) / (2.0 * h);
  }
  std::set<std::pair<Eigen::Index, Eigen::Index>> pattern;
  for (Eigen::Index j = 0; j < H.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(H, j); it; ++it)
      pattern.insert({it.row(), j});
  const double scale = fd.cwiseAbs().maxCoeff();
  int checked = 0, outside = 0;
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = 0; i <= j; ++i)
      if (std::abs(fd(i, j)) > 1e-6 * scale) {
        ++checked;
        outside += !pattern.count({i, j});
      }
  // A coordinate step may flip a pair's region or activity (a kink in the gradient), so the
  // dense comparison allows a few columns to disagree but the pattern test allows none.
  const Eigen::MatrixXd assembled = dense_symmetric(H);
  int bad_columns = 0;
  for (Eigen::Index j = 0; j < n; ++j)
    bad_columns += (fd.col(j) - assembled.col(j)).cwiseAbs().maxCoeff() > 1e-5 * scale;
  std::cout << "[ pattern  ] penalty: " << checked << " nonzeros checked, " << H.nonZeros()
            << " in the pattern, " << bad_columns << " of " << n
            << " finite-difference columns off\n";
  EXPECT_GT(checked, 1000);
  EXPECT_EQ(outside, 0);
  EXPECT_LE(bad_columns, n / 50);
}

TEST(ContactPenalty, PenalizedEnergyIsShellPlusPenalty) {
  const FoldedDiscScene scene(0.02, 1);
  const Eigen::Index n = scene.model.dimension();
  const ShellModel& shell = scene.model;
  const double phi_e = 0.5;
  ContactPenalty penalty(scene.proxy, scene.pairs, 0.1, 3e3, n);
  PenalizedEnergy total(shell, penalty);
  EXPECT_EQ(total.dimension(), n);

  // The merged pattern is the union of the two.
  const Eigen::SparseMatrix<double> merged = total.hessian_pattern();
  std::set<std::pair<Eigen::Index, Eigen::Index>> expected, actual;
  for (const Eigen::SparseMatrix<double>& part :
       {shell.hessian_pattern(), penalty.hessian_pattern()})
    for (Eigen::Index j = 0; j < part.outerSize(); ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(part, j); it; ++it)
        expected.insert({it.row(), j});
  for (Eigen::Index j = 0; j < merged.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(merged, j); it; ++it)
      actual.insert({it.row(), j});
  EXPECT_EQ(actual, expected);
  EXPECT_GT(static_cast<Eigen::Index>(expected.size()), shell.hessian_pattern().nonZeros());

  Eigen::VectorXd g, g_shell, g_penalty;
  Eigen::SparseMatrix<double> H = merged, H_shell = shell.hessian_pattern(),
                              H_penalty = penalty.hessian_pattern();
  const double E = total.evaluate(scene.x, phi_e, &g, &H);
  const double E_shell = shell.evaluate(scene.x, phi_e, &g_shell, &H_shell);
  const double P = penalty.evaluate(scene.x, &g_penalty, &H_penalty);
  ASSERT_GT(P, 0.0);
  EXPECT_NEAR(E, E_shell + P, 1e-14 * (E_shell + P));
  // Same additions in the same order: equal up to the last bit or so.
  const Eigen::VectorXd g_sum = g_shell + g_penalty;
  EXPECT_LE((g - g_sum).cwiseAbs().maxCoeff(), 1e-14 * g_sum.cwiseAbs().maxCoeff());
  const Eigen::MatrixXd H_sum = Eigen::MatrixXd(H_shell) + Eigen::MatrixXd(H_penalty);
  EXPECT_LE((Eigen::MatrixXd(H) - H_sum).cwiseAbs().maxCoeff(),
            1e-14 * H_sum.cwiseAbs().maxCoeff());
  EXPECT_EQ(total.evaluate(scene.x, phi_e, nullptr, nullptr), E);

  // The Newton solver accepts it (upper pattern with every diagonal) and lowers the energy.
  NewtonOptions options;
  options.max_iterations = 3;
  ObjectiveAtParameter total_at(total, phi_e);
  const NewtonResult result = NewtonSolver(options).minimize(total_at, scene.x);
  EXPECT_TRUE(std::isfinite(result.energy));
  EXPECT_LT(result.energy, E);
  EXPECT_GT(result.iterations, 0);
}

TEST(ContactPenalty, PenalizedEnergyIsAFamilyInTheShellsExcessAngle) {
  const FoldedDiscScene scene(0.02, 1);
  const Eigen::Index n = scene.model.dimension();
  const ShellModel& shell = scene.model;
  ContactPenalty penalty(scene.proxy, scene.pairs, 0.1, 3e3, n);
  PenalizedEnergy total(shell, penalty);
  const ParametrizedObjective& family = total;
  EXPECT_TRUE(family.accepts_parameter(0.7));
  EXPECT_FALSE(family.accepts_parameter(-7.0));
  // P does not depend on phi_e: the family's d(gradient)/d(phi_e) is the shell's, bit for bit,
  // and its energy follows the shell's at every angle.
  const double P = penalty.evaluate(scene.x, nullptr, nullptr);
  ASSERT_GT(P, 0.0);
  for (const double phi_e : {0.5, 0.7}) {
    const Eigen::VectorXd derivative = family.gradient_parameter_derivative(scene.x, phi_e);
    EXPECT_TRUE(derivative == shell.gradient_parameter_derivative(scene.x, phi_e));
    EXPECT_EQ(family.evaluate(scene.x, phi_e, nullptr, nullptr),
              shell.evaluate(scene.x, phi_e, nullptr, nullptr) + P);
  }
}

TEST(ContactPenalty, StiffnessScaleAndMeanSpacing) {
  EXPECT_NEAR(contact_stiffness_scale(1e4, 0.02, 0.01), 1e4 * 1e-4 / 0.02, 1e-12);
  const FoldedDiscScene scene(0.0, 2);
  const double l = proxy_mean_edge_length(scene.proxy);
  // 5 rings on the unit disc, 2 segments per element edge: spacing 1.11..1.40 R / (2 N).
  EXPECT_GT(l, 1.0 / 10.0);
  EXPECT_LT(l, 1.45 / 10.0);
  expect_invalid_argument_containing([] { contact_stiffness_scale(1e4, 0.0, 0.01); }, "thickness");
  expect_invalid_argument_containing([] { contact_stiffness_scale(-1.0, 0.02, 0.01); },
                                     "youngs_modulus");
  expect_invalid_argument_containing([] { contact_stiffness_scale(1e4, 0.02, std::nan("")); },
                                     "spacing");
}

TEST(ContactPenalty, RejectsBadInputNamingIt) {
  const FoldedDiscScene scene(0.02, 1);
  const Eigen::Index n = scene.model.dimension();
  expect_invalid_argument_containing(
      [&] { ContactPenalty(scene.proxy, scene.pairs, 0.1, -1.0, n); }, "stiffness");
  ContactPenalty penalty(scene.proxy, scene.pairs, 0.1, 1.0, n);
  expect_invalid_argument_containing([&] { penalty.set_stiffness(std::nan("")); }, "stiffness");
  expect_invalid_argument_containing(
      [&] { penalty.evaluate(Eigen::VectorXd::Zero(n - 1), nullptr, nullptr); }, "x has");
  Eigen::SparseMatrix<double> wrong(n, n);
  expect_invalid_argument_containing([&] { penalty.evaluate(scene.x, nullptr, &wrong); },
                                     "hessian_pattern");
  ContactPenalty bigger(scene.proxy, scene.pairs, 0.1, 1.0, n + 1);
  const ShellModel& shell = scene.model;
  expect_invalid_argument_containing([&] { PenalizedEnergy(shell, bigger); },
                                     "penalty has " + std::to_string(n + 1));
  PenalizedEnergy total(shell, penalty);
  expect_invalid_argument_containing([&] { total.evaluate(scene.x, 0.5, nullptr, &wrong); },
                                     "hessian_pattern");
}

}  // namespace
}  // namespace growshell
