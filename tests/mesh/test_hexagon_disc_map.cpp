#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "libshell/mesh/hexagon_disc_map.hpp"

namespace growshell {
namespace {

using Complex = std::complex<double>;

TEST(HexagonDiscMap, FixesCentreAndCornersAndRespectsTheSymmetries) {
  EXPECT_EQ(std::abs(hexagon_to_disc(0.0)), 0.0);
  for (int k = 0; k < 6; ++k) {
    const Complex corner = std::polar(1.0, k * std::numbers::pi / 3);
    EXPECT_NEAR(std::abs(hexagon_to_disc(corner) - corner), 0.0, 1e-15);
  }
  const Complex z(0.41, 0.27);
  const Complex w = hexagon_to_disc(z);
  EXPECT_NEAR(std::abs(hexagon_to_disc(std::conj(z)) - std::conj(w)), 0.0, 1e-13);
  const Complex rot = std::polar(1.0, std::numbers::pi / 3);
  EXPECT_NEAR(std::abs(hexagon_to_disc(rot * z) - rot * w), 0.0, 1e-13);
}

TEST(HexagonDiscMap, SidesGoOntoTheUnitCircleAndInteriorInside) {
  const Complex a(1.0, 0.0), b = std::polar(1.0, std::numbers::pi / 3);
  for (double t : {0.05, 0.2, 0.5, 0.8, 0.97}) {
    EXPECT_NEAR(std::abs(hexagon_to_disc((1 - t) * a + t * b)), 1.0, 1e-12) << "t = " << t;
    EXPECT_LT(std::abs(hexagon_to_disc(0.95 * ((1 - t) * a + t * b))), 1.0);
  }
}

TEST(HexagonDiscMap, IsConformalAndInvertsTheSchwarzChristoffelMap) {
  // Cauchy-Riemann: dg/dy = i dg/dx (central differences, step 1e-6: error ~1e-10).
  for (const Complex z : {Complex(0.1, 0.05), Complex(0.6, 0.2), Complex(0.8, 0.1),
                          Complex(0.97, 0.02), Complex(0.3, 0.7)}) {
    const double h = 1e-6;
    const Complex gx = (hexagon_to_disc(z + h) - hexagon_to_disc(z - h)) / (2 * h);
    const Complex gy =
        (hexagon_to_disc(z + Complex(0, h)) - hexagon_to_disc(z - Complex(0, h))) / (2 * h);
    EXPECT_NEAR(std::abs(gy - Complex(0, 1) * gx), 0.0, 1e-8 * std::abs(gx));
    EXPECT_NEAR(std::abs(disc_to_hexagon(hexagon_to_disc(z)) - z), 0.0, 1e-13);
  }
}

TEST(HexagonDiscMap, ContinuesAcrossASideByReflection) {
  // Just outside a side the map is the reflection in the unit circle of the mirrored point.
  const Complex inside(0.8, 0.2);
  const Complex normal = std::polar(1.0, std::numbers::pi / 6);
  const double apothem = std::cos(std::numbers::pi / 6);
  const double d = apothem - (inside * std::conj(normal)).real();
  const Complex outside = inside + 2.0 * d * normal;
  const Complex w = hexagon_to_disc(inside);
  EXPECT_NEAR(std::abs(hexagon_to_disc(outside) - w / std::norm(w)), 0.0, 1e-13);
}

}  // namespace
}  // namespace growshell
