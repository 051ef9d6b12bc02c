#pragma once
// Random points in a cube and random proper rigid motions, for tests that check that a result
// does not depend on the frame.

#include <Eigen/Geometry>
#include <random>

namespace growshell::test_support {

/// A point uniform in the cube [-half_width, half_width]^3.
inline Eigen::Vector3d random_point(std::mt19937& rng, double half_width) {
  std::uniform_real_distribution<double> u(-half_width, half_width);
  return {u(rng), u(rng), u(rng)};
}

/// A random rotation (normalised Gaussian quaternion) followed by a translation uniform in
/// [-5, 5]^3.
inline Eigen::Isometry3d random_motion(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  // Draws in sequence (function arguments have no evaluation order), so runs are reproducible.
  const double w = g(rng), x = g(rng), y = g(rng), z = g(rng);
  const Eigen::Quaterniond q = Eigen::Quaterniond(w, x, y, z).normalized();
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.linear() = q.toRotationMatrix();
  motion.translation() = random_point(rng, 5.0);
  return motion;
}

}  // namespace growshell::test_support
