// Energy crossings of two sampled branches: the crossing located on the cubic Hermite
// interpolants converges with fourth order, its error estimate tracks the true error, folded
// branches give one crossing per sheet, and shared-sample roots are reported once.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "solvers/continuation/branch_crossing.hpp"

namespace growshell {
namespace {

/// Root of f on [lo, hi] (f(lo), f(hi) of opposite sign) by bisection to machine resolution.
double bisect(const std::function<double(double)>& f, double lo, double hi) {
  double f_lo = f(lo);
  EXPECT_LT(f_lo * f(hi), 0.0) << "test setup: no bracket on [" << lo << ", " << hi << "]";
  for (int k = 0; k < 200; ++k) {
    const double m = 0.5 * (lo + hi);
    if (m <= lo || m >= hi) break;
    const double fm = f(m);
    if ((fm > 0) == (f_lo > 0)) {
      lo = m;
      f_lo = fm;
    } else {
      hi = m;
    }
  }
  return 0.5 * (lo + hi);
}

// The analytic pair: two crossings on [0, 3], near 0.33 and 2.5.
double energy_a(double l) { return std::sin(l) + 0.1 * l * l; }
double slope_a(double l) { return std::cos(l) + 0.2 * l; }
double energy_b(double l) { return 0.3 + 0.05 * l * l * l; }
double slope_b(double l) { return 0.15 * l * l; }

std::vector<BranchEnergySample> sample_on(const std::vector<double>& lambdas,
                                          double (*energy)(double), double (*slope)(double)) {
  std::vector<BranchEnergySample> out;
  for (double l : lambdas) out.push_back({l, energy(l), slope(l)});
  return out;
}

std::vector<double> grid(double first, double step, int count) {
  std::vector<double> out;
  for (int k = 0; k < count; ++k) out.push_back(first + k * step);
  return out;
}

double exact_analytic_root(double lo, double hi) {
  return bisect([](double l) { return energy_a(l) - energy_b(l); }, lo, hi);
}

TEST(HermiteEnergy, ReproducesCubicsInEitherOrderAndMatchesTheSamples) {
  auto cubic = [](double l) { return 0.7 - 1.3 * l + 0.4 * l * l + 2.1 * l * l * l; };
  auto cubic_slope = [](double l) { return -1.3 + 0.8 * l + 6.3 * l * l; };
  const BranchEnergySample s0{0.4, cubic(0.4), cubic_slope(0.4)};
  const BranchEnergySample s1{1.1, cubic(1.1), cubic_slope(1.1)};
  // Rounding only: values O(1..10), a handful of operations.
  for (double l : {0.4, 0.5, 0.77, 1.1, -0.3, 1.8}) {
    EXPECT_NEAR(hermite_energy(s0, s1, l), cubic(l), 1e-12) << "lambda " << l;
    EXPECT_NEAR(hermite_energy(s1, s0, l), cubic(l), 1e-12) << "reversed, lambda " << l;
  }
  // The basis weights are exactly 0/1 at the ends, so the samples come back bit-exactly.
  EXPECT_EQ(hermite_energy(s0, s1, 0.4), s0.energy);
  EXPECT_EQ(hermite_energy(s0, s1, 1.1), s1.energy);
  // A quartic is not reproduced: the check above can fail.
  const BranchEnergySample q0{0.0, 0.0, 0.0}, q1{1.0, 1.0, 4.0};
  // l^4 - Hermite = l^2 (l-1)^2: at 0.3, 0.0081 - 0.0441.
  EXPECT_NEAR(hermite_energy(q0, q1, 0.3), -0.036, 1e-15);
  EXPECT_THROW(hermite_energy(s0, s0, 0.5), std::invalid_argument);
}

TEST(EnergyCrossings, AnalyticBranchesOnRegularGrids) {
  const double exact[2] = {exact_analytic_root(0.0, 1.0), exact_analytic_root(2.0, 3.0)};
  for (double step : {0.2, 0.1, 0.05}) {
    const int count = static_cast<int>(std::lround(3.0 / step)) + 1;
    const auto a = sample_on(grid(0.0, step, count), energy_a, slope_a);
    const auto b = sample_on(grid(0.0, step, count), energy_b, slope_b);
    const auto crossings = energy_crossings(a, b);
    ASSERT_EQ(crossings.size(), 2u) << "step " << step;
    for (int k = 0; k < 2; ++k) {
      const EnergyCrossing& c = crossings[k];
      const double error = std::abs(c.parameter - exact[k]);
      std::printf("step %.3f root %.10f error %.3e estimate %.3e ratio %.2f\n", step, exact[k],
                  error, c.error_estimate, c.error_estimate / error);
      // The brief's accuracy target; the actual error is ~1e-6 at step 0.2 (printed).
      EXPECT_LT(error, 1e-4);
      // Fourth-order interpolation error bound: |E''''| <= 1 / 24 * (step/2)^4 / |slope diff|.
      EXPECT_LT(error, std::pow(0.5 * step, 4) / 24.0 / std::abs(c.slope_difference) + 1e-10);
      EXPECT_NEAR(c.slope_difference, slope_a(exact[k]) - slope_b(exact[k]), 1e-3);
      EXPECT_NEAR(c.energy, energy_a(exact[k]), 1e-4);
      EXPECT_GE(c.error_estimate, error / 10) << "estimate too optimistic";
      EXPECT_LE(c.error_estimate, error * 10) << "estimate too pessimistic";
      // The reported intervals hold the crossing (both grids ascend).
      EXPECT_LE(a[c.segment_a].parameter, c.parameter);
      EXPECT_GE(a[c.segment_a + 1].parameter, c.parameter);
      EXPECT_LE(b[c.segment_b].parameter, c.parameter);
      EXPECT_GE(b[c.segment_b + 1].parameter, c.parameter);
    }
  }
}

// The error at a given step depends on where the root falls inside its interval (it vanishes
// at a sample), so the order is measured on the worst case over nine offsets of the grid.
TEST(EnergyCrossings, FourthOrderConvergenceAndEstimateQuality) {
  const double root = exact_analytic_root(2.0, 3.0);
  std::vector<double> worst;
  double min_ratio = std::numeric_limits<double>::infinity(), max_ratio = 0.0;
  for (double step : {0.2, 0.1, 0.05, 0.025}) {
    double worst_error = 0.0;
    for (int k = 1; k <= 9; ++k) {
      const double offset = 0.1 * k;  // root at this fraction of its interval
      const int half = static_cast<int>(std::ceil(1.0 / step));
      const auto lambdas = grid(root - (half + offset) * step, step, 2 * half + 1);
      const auto a = sample_on(lambdas, energy_a, slope_a);
      const auto b = sample_on(lambdas, energy_b, slope_b);
      const auto crossings = energy_crossings(a, b, 1e-15);
      ASSERT_EQ(crossings.size(), 1u) << "step " << step << " offset " << offset;
      const double error = std::abs(crossings[0].parameter - root);
      worst_error = std::max(worst_error, error);
      const double ratio = crossings[0].error_estimate / error;
      min_ratio = std::min(min_ratio, ratio);
      max_ratio = std::max(max_ratio, ratio);
    }
    worst.push_back(worst_error);
  }
  for (std::size_t k = 0; k < worst.size(); ++k) {
    std::printf("step %.4f worst error %.3e%s", 0.2 / (1 << k), worst[k], k == 0 ? "\n" : "");
    if (k > 0) std::printf("  ratio to previous %.2f\n", worst[k - 1] / worst[k]);
  }
  std::printf("estimate / true error over all 36 runs: %.3f .. %.3f\n", min_ratio, max_ratio);
  // 16 = 2^4 for a fourth-order method; the fourth derivative sampled inside the interval
  // moves by O(step), so at step 0.2 the ratio may deviate by a few units.
  for (std::size_t k = 1; k < worst.size(); ++k) {
    EXPECT_GT(worst[k - 1] / worst[k], 12.0) << "halving " << k;
    EXPECT_LT(worst[k - 1] / worst[k], 20.0) << "halving " << k;
  }
  EXPECT_GT(min_ratio, 0.1);
  EXPECT_LT(max_ratio, 10.0);
}

// A branch traced up to a fold at lambda = 1 and back: lambda(s) = 1 - (s-1)^2. Its slope
// dE/dlambda = g(s) = 1 + s is smooth through the fold, and E(s) = int g lambda'(s) ds =
// 2 s - 2 s^3 / 3 (the cusp of E(lambda) at the fold). Branch b, E = 0.2 + 0.5 lambda, crosses
// each sheet once.
TEST(EnergyCrossings, FoldedBranchCrossedTwice) {
  auto lambda_of = [](double s) { return 1.0 - (s - 1.0) * (s - 1.0); };
  auto energy_of = [](double s) { return 2.0 * s - 2.0 * s * s * s / 3.0; };
  std::vector<BranchEnergySample> a;
  for (int k = 0; k <= 40; ++k) {
    const double s = 0.05 * k;
    a.push_back({lambda_of(s), energy_of(s), 1.0 + s});
  }
  std::vector<BranchEnergySample> b;
  for (int k = 0; k <= 14; ++k) {
    const double l = -0.2 + 0.1 * k;
    b.push_back({l, 0.2 + 0.5 * l, 0.5});
  }
  auto mismatch = [&](double s) { return energy_of(s) - 0.2 - 0.5 * lambda_of(s); };
  const double s_low = bisect(mismatch, 0.0, 0.99);
  const double s_high = bisect(mismatch, 1.01, 2.0);
  const double exact[2] = {lambda_of(s_low), lambda_of(s_high)};  // ascending: 0.34, 0.66

  const auto crossings = energy_crossings(a, b);
  ASSERT_EQ(crossings.size(), 2u);
  for (int k = 0; k < 2; ++k) {
    const double error = std::abs(crossings[k].parameter - exact[k]);
    std::printf("fold: crossing %d lambda %.8f error %.3e estimate %.3e\n", k, exact[k], error,
                crossings[k].error_estimate);
    EXPECT_LT(error, 1e-4);
    EXPECT_GE(crossings[k].error_estimate, error / 10);
    EXPECT_LE(crossings[k].error_estimate, error * 10 + 1e-9);
  }
  // The first crossing (lambda 0.34) is on the lower sheet (s < 1, samples 0..20), the second on
  // the upper one.
  EXPECT_LT(crossings[0].segment_a, 20u);
  EXPECT_GE(crossings[1].segment_a, 20u);
  EXPECT_NEAR(crossings[0].energy, energy_of(s_low), 1e-4);
  EXPECT_NEAR(crossings[1].energy, energy_of(s_high), 1e-4);
}

// E_a = lambda and E_b = 1 - lambda cross exactly at a shared sample, which four interval
// pairs contain; a repeated sample (zero-width interval) in a must not break adjacency.
TEST(EnergyCrossings, RootAtSharedSampleReportedOnce) {
  std::vector<BranchEnergySample> a, b;
  for (double l : {0.0, 0.25, 0.25, 0.5, 0.75, 1.0}) a.push_back({l, l, 1.0});
  for (double l : {0.0, 0.25, 0.5, 0.75, 1.0}) b.push_back({l, 1.0 - l, -1.0});
  const auto crossings = energy_crossings(a, b);
  ASSERT_EQ(crossings.size(), 1u);
  EXPECT_EQ(crossings[0].parameter, 0.5);
  EXPECT_EQ(crossings[0].energy, 0.5);
  EXPECT_EQ(crossings[0].slope_difference, 2.0);
  // Linear data: both interpolants are exact, the estimate is zero.
  EXPECT_EQ(crossings[0].error_estimate, 0.0);
}

TEST(EnergyCrossings, IdenticalBranchesHaveNoIsolatedCrossing) {
  const auto a = sample_on(grid(0.0, 0.1, 11), energy_a, slope_a);
  EXPECT_TRUE(energy_crossings(a, a).empty());
}

TEST(EnergyCrossings, NoOverlapGivesNothing) {
  const auto a = sample_on(grid(0.0, 0.1, 11), energy_a, slope_a);
  const auto b = sample_on(grid(1.05, 0.1, 11), energy_a, slope_a);
  EXPECT_TRUE(energy_crossings(a, b).empty());
  // Overlapping ranges with no crossing: b shifted up by 1 in energy.
  auto c = a;
  for (auto& s : c) s.energy += 1.0;
  EXPECT_TRUE(energy_crossings(a, c).empty());
}

TEST(EnergyCrossings, BadInputThrowsNamingTheSample) {
  const auto good = sample_on(grid(0.0, 0.1, 5), energy_a, slope_a);
  auto expect_message = [&](const std::vector<BranchEnergySample>& a,
                            const std::vector<BranchEnergySample>& b, double tolerance,
                            const std::string& needle) {
    try {
      energy_crossings(a, b, tolerance);
      ADD_FAILURE() << "no throw, expected '" << needle << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  auto bad = good;
  bad[2].energy = std::numeric_limits<double>::quiet_NaN();
  expect_message(good, bad, 1e-10, "branch b sample 2 has a non-finite energy");
  bad = good;
  bad[3].energy_slope = std::numeric_limits<double>::infinity();
  expect_message(bad, good, 1e-10, "branch a sample 3 has a non-finite energy_slope");
  bad = good;
  bad[0].parameter = std::numeric_limits<double>::quiet_NaN();
  expect_message(good, bad, 1e-10, "branch b sample 0 has a non-finite parameter");
  expect_message({good[0]}, good, 1e-10, "branch a has 1 sample");
  expect_message(good, {}, 1e-10, "branch b has 0 sample");
  expect_message(good, good, 0.0, "tolerance");
}

// A branch traced in two pieces (the contact-free cone, then the trace with contact from
// its last sample) crosses another branch in its first piece: only the joined samples find it.
TEST(JoinBranchSamples, CrossingInTheEarlierPieceIsFoundOnlyOnTheJoinedBranch) {
  const auto earlier = sample_on(grid(0.0, 0.1, 11), energy_a, slope_a);  // 0 .. 1.0
  const auto later = sample_on(grid(1.0, 0.1, 21), energy_a, slope_a);    // 1.0 .. 3.0
  const auto other = sample_on(grid(0.0, 0.1, 31), energy_b, slope_b);
  const std::vector<BranchEnergySample> joined = join_branch_samples(earlier, later);
  ASSERT_EQ(joined.size(), earlier.size() - 1 + later.size());  // the shared 1.0 once
  for (std::size_t i = 1; i < joined.size(); ++i)
    EXPECT_GT(joined[i].parameter, joined[i - 1].parameter);
  const double first = exact_analytic_root(0.0, 1.0), second = exact_analytic_root(2.0, 3.0);
  const std::vector<EnergyCrossing> alone = energy_crossings(later, other);
  ASSERT_EQ(alone.size(), 1u);
  EXPECT_NEAR(alone[0].parameter, second, 1e-4);
  const std::vector<EnergyCrossing> both = energy_crossings(joined, other);
  ASSERT_EQ(both.size(), 2u);
  EXPECT_NEAR(both[0].parameter, first, 1e-4);
  EXPECT_NEAR(both[1].parameter, second, 1e-4);
  EXPECT_EQ(join_branch_samples({}, later).size(), later.size());
  EXPECT_EQ(join_branch_samples(earlier, {}).size(), earlier.size());
}

TEST(JoinBranchSamples, EarlierPieceMustIncrease) {
  auto earlier = sample_on(grid(0.0, 0.1, 5), energy_a, slope_a);
  earlier[3].parameter = earlier[2].parameter;
  try {
    join_branch_samples(earlier, {});
    ADD_FAILURE() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("earlier sample 3 does not increase"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace growshell
