#pragma once
// Contact proxies whose unknowns are the points themselves, for tests that place contact points
// and triangles directly.

#include <Eigen/Core>

#include "libshell/contact/contact_proxy.hpp"

namespace growshell::test_support {

/// A proxy whose map is the identity: the unknowns are the points themselves (3 i + c).
inline ContactProxy identity_proxy(const Eigen::MatrixX3d& points, const Eigen::MatrixX3i& triangles,
                                   const Eigen::MatrixX2i& edges = Eigen::MatrixX2i(0, 2)) {
  ContactProxy proxy;
  const Eigen::Index n = 3 * points.rows();
  proxy.map.resize(n, n);
  proxy.map.setIdentity();
  proxy.triangles = triangles;
  proxy.edges = edges;
  proxy.reference_positions = points;
  return proxy;
}

/// The points as one vector (x, y, z of point 0, then of point 1, ...).
inline Eigen::VectorXd flatten(const Eigen::MatrixX3d& points) {
  Eigen::VectorXd x(3 * points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i) x.segment<3>(3 * i) = points.row(i).transpose();
  return x;
}

}  // namespace growshell::test_support
