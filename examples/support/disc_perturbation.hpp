#pragma once
// The seeded out-of-plane perturbation that starts a flat disc on the n = 2 e-cone
// (econe_at).

#include <Eigen/Core>
#include <cmath>
#include <random>

#include "libshell/assembly/shell_model.hpp"

namespace growshell::examples {

/// Uniform number in [-1, 1) from the generator's raw output (portable across libraries).
inline double uniform(std::mt19937& rng) { return 2.0 * (rng() / 4294967296.0) - 1.0; }

/// Smooth out-of-plane perturbation, mirror-symmetric about the x-axis (a mirror axis of the
/// mesh): sum over m = 1..4 of (r/R)^m a_m cos(m t). Keeping that symmetry fixes the
/// orientation of the fold pattern, which the axisymmetric continuum leaves free and the
/// six-fold mesh selects only through a nearly zero stiffness (docs/verification.md).
inline Eigen::VectorXd disc_perturbation(const ShellModel& model, double amplitude,
                                         std::mt19937& rng, double radius) {
  double a[5];
  for (int m = 1; m <= 4; ++m) a[m] = uniform(rng);
  const Eigen::VectorXd& X = model.reference_positions();
  Eigen::VectorXd dz = Eigen::VectorXd::Zero(X.size());
  for (Eigen::Index v = 0; v < X.size() / 3; ++v) {
    const double r = std::hypot(X(3 * v), X(3 * v + 1)) / radius;
    const double t = std::atan2(X(3 * v + 1), X(3 * v));
    double z = 0.0;
    for (int m = 1; m <= 4; ++m) z += std::pow(r, m) * a[m] * std::cos(m * t);
    dz(3 * v + 2) = amplitude * radius * z;
  }
  return dz;
}

}  // namespace growshell::examples
