#include <gtest/gtest.h>

#include <cmath>

#include "libshell/subdivision/triangle_quadrature.hpp"

namespace growshell {
namespace {

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

// Integral of v^a w^b over the parameter triangle: a! b! / (a + b + 2)!.
double exact_monomial_integral(int a, int b) {
  return factorial(a) * factorial(b) / factorial(a + b + 2);
}

TEST(TriangleQuadrature, IntegratesMonomialsUpToItsDegreeExactly) {
  for (int degree : kAvailableQuadratureDegrees) {
    const auto rule = triangle_quadrature(degree);
    for (int total = 0; total <= degree; ++total) {
      for (int a = 0; a <= total; ++a) {
        const int b = total - a;
        double sum = 0.0;
        for (const auto& p : rule) sum += p.weight * std::pow(p.v, a) * std::pow(p.w, b);
        // The tabulated points carry 15 significant digits.
        EXPECT_NEAR(sum, exact_monomial_integral(a, b), 1e-14)
            << "degree " << degree << " monomial v^" << a << " w^" << b;
      }
    }
  }
}

TEST(TriangleQuadrature, IsNotExactBeyondItsDegree) {
  // Guards against a rule silently replaced by a different one: every rule misses some
  // monomial of degree + 1 (degree 3 is served by the degree-4 rule, so check 4 -> 5).
  for (int degree : kAvailableQuadratureDegrees) {
    const auto rule = triangle_quadrature(degree);
    double worst = 0.0;
    for (int a = 0; a <= degree + 1; ++a) {
      const int b = degree + 1 - a;
      double sum = 0.0;
      for (const auto& p : rule) sum += p.weight * std::pow(p.v, a) * std::pow(p.w, b);
      worst = std::max(worst, std::abs(sum - exact_monomial_integral(a, b)));
    }
    EXPECT_GT(worst, 1e-8) << "degree " << degree;
  }
}

TEST(TriangleQuadrature, PointsInsideAndWeightsPositive) {
  for (int degree : kAvailableQuadratureDegrees) {
    for (const auto& p : triangle_quadrature(degree)) {
      EXPECT_GT(p.v, 0.0);
      EXPECT_GT(p.w, 0.0);
      EXPECT_LT(p.v + p.w, 1.0);
      EXPECT_GT(p.weight, 0.0);
    }
  }
}

TEST(TriangleQuadrature, RejectsUnavailableDegree) {
  EXPECT_THROW(triangle_quadrature(0), std::invalid_argument);
  EXPECT_THROW(triangle_quadrature(7), std::invalid_argument);
}

}  // namespace
}  // namespace growshell
