#pragma once
// Deformed states of a shell for the tests: the reference mapped point by point, and the
// folded sheet the contact tests use (pairs meeting at every angle).

#include <Eigen/Core>
#include <cmath>
#include <numbers>

#include "libshell/assembly/shell_model.hpp"

namespace growshell::test_support {

/// The state whose every control point is f(its reference position).
template <class F>
Eigen::VectorXd map_reference(const ShellModel& model, F f) {
  Eigen::VectorXd x = model.reference_positions();
  for (Eigen::Index v = 0; v < x.size() / 3; ++v)
    x.segment<3>(3 * v) = f(Eigen::Vector3d(x.segment<3>(3 * v)));
  return x;
}

/// The sheet folded about the line X = x0: the part X > x0 runs over a half cylinder of radius
/// rho and comes back, mirrored in x, as a flat layer at z = 2 rho over the part X < x0.
/// `wobble` adds a smooth, generic displacement (no symmetry, so no ties between regions and
/// pairs meet at every angle).
inline Eigen::VectorXd folded_sheet(const ShellModel& model, double x0, double rho, double wobble) {
  constexpr double pi = std::numbers::pi;
  return map_reference(model, [=](const Eigen::Vector3d& X) {
    const double s = X.x() - x0;
    Eigen::Vector3d p;
    if (s <= 0.0)
      p = Eigen::Vector3d(X.x(), X.y(), 0.0);
    else if (s < pi * rho)
      p = Eigen::Vector3d(x0 + rho * std::sin(s / rho), X.y(), rho * (1.0 - std::cos(s / rho)));
    else
      p = Eigen::Vector3d(x0 - (s - pi * rho), X.y(), 2.0 * rho);
    p += wobble * Eigen::Vector3d(std::sin(2.1 * X.x() + 1.3 * X.y() + 0.4),
                                  std::sin(1.7 * X.y() - 0.9 * X.x() + 1.1),
                                  std::cos(2.9 * X.x() + 0.6 * X.x() * X.y() + 0.2));
    return p;
  });
}

}  // namespace growshell::test_support
