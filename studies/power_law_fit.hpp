#pragma once
/// \file
/// A power law y - L = A x^p through measured points, fitted by least squares on
/// log(y - L) = log A + p log x: how phi_e at the first branch point approaches 0 (c2 h^2) and
/// phi_e^max approaches its h -> 0 value as the thickness h falls (the thickness_series study).

#include <optional>
#include <string>
#include <vector>

namespace growshell {

/// The fitted law and how well it describes the points.
struct PowerLawFit {
  double limit = 0.0;      ///< L, given
  double amplitude = 0.0;  ///< A
  double exponent = 0.0;   ///< p
  int points = 0;          ///< the points used: x > 0, y > L, both finite
  /// max over the points used of |A x^p / (y - L) - 1|.
  double max_relative_misfit = 0.0;
};

/// The least-squares fit of y - limit = A x^p over the pairs (x[i], y[i]) with x > 0,
/// y > limit and both finite (the others are left out). Empty when fewer than two points
/// remain or their x are all equal, so that no line is defined. Throws std::invalid_argument
/// if x and y differ in length or the limit is not finite.
std::optional<PowerLawFit> fit_power_law(const std::vector<double>& x, const std::vector<double>& y,
                                         double limit);

}  // namespace growshell
