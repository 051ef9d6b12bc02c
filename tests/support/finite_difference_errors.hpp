#pragma once
// Central-difference checks of a function of a contact pair's 12 coordinates: the relative
// errors of its analytic gradient and Hessian, and the step and tolerance the pair distance
// tests use on O(1) coordinates.

#include <functional>

#include "libshell/contact/point_triangle_distance.hpp"

namespace growshell::test_support {

/// Largest |analytic - central difference| relative to the largest analytic entry.
struct FdErrors {
  double gradient = 0.0;
  double hessian = 0.0;
};

/// The errors of `gradient` (against differences of `value`) and of `hessian` (against
/// differences of `gradient`) at x, with step `step` in each coordinate.
inline FdErrors finite_difference_errors(
    const Vector12d& x, double step, const std::function<double(const Vector12d&)>& value,
    const std::function<Vector12d(const Vector12d&)>& gradient,
    const std::function<Matrix12d(const Vector12d&)>& hessian) {
  const Vector12d g = gradient(x);
  const Matrix12d H = hessian(x);
  Vector12d g_fd;
  Matrix12d H_fd;
  for (int i = 0; i < 12; ++i) {
    Vector12d xp = x, xm = x;
    xp(i) += step;
    xm(i) -= step;
    // The step actually taken: far from the origin x +- h is rounded to the coordinate grid.
    const double width = xp(i) - xm(i);
    g_fd(i) = (value(xp) - value(xm)) / width;
    H_fd.col(i) = (gradient(xp) - gradient(xm)) / width;
  }
  return {(g - g_fd).cwiseAbs().maxCoeff() / g.cwiseAbs().maxCoeff(),
          (H - H_fd).cwiseAbs().maxCoeff() / H.cwiseAbs().maxCoeff()};
}

// Central differences with step h on O(1) coordinates: truncation ~ h^2 |f'''| ~ 1e-12 and
// rounding ~ eps |f| / h ~ 1e-10, both relative to O(1) derivatives. A tolerance of 1e-6
// relative to the largest entry leaves four orders of margin and still fails for any wrong
// term, which gives O(1) relative errors.
constexpr double kFdStep = 1e-6;
constexpr double kFdTolerance = 1e-6;

}  // namespace growshell::test_support
